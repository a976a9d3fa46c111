#pragma once
// Sampling a tabulated discrete distribution in O(1) with no search: Walker's alias
// method, built by Vose's algorithm ("A linear algorithm for generating random numbers
// with a given distribution", IEEE TSE 17, 1991). Cell i of n is kept with probability
// prob[i] and otherwise gives way to alias[i]; one uniform u picks the cell (u n) and,
// from the rest of its digits, whether to keep it and the position within the chosen
// cell, which is uniform: so a piecewise-constant density is sampled exactly. One cache
// line holds eight cells, and no branch depends on the table's contents.
#include <cstdint>
#include <vector>

namespace luxtrace {

class AliasTable {
public:
    AliasTable() = default;
    // `weights`: n >= 1 non-negative numbers with a positive sum.
    explicit AliasTable(const std::vector<double>& weights);

    struct Pick {
        int cell;
        double t;  // uniform in [0, 1): the position within the cell
    };
    // u in [0, 1).
    Pick sample(double u) const {
        const double x = u * static_cast<double>(cells_.size());
        const auto i = std::min(static_cast<std::size_t>(x), cells_.size() - 1);
        const double f = x - static_cast<double>(i);  // uniform in [0, 1)
        const Cell c = cells_[i];
        const double keep = c.prob;
        if (f < keep) return {static_cast<int>(i), f / keep};
        return {static_cast<int>(c.alias), (f - keep) / (1.0 - keep)};
    }
    // The probability of cell i (for tests).
    double probability(int i) const;

private:
    struct Cell {
        float prob;           // keep cell i when f < prob (1 for a full cell)
        std::uint32_t alias;  // else take this one
    };
    std::vector<Cell> cells_;
};

}  // namespace luxtrace
