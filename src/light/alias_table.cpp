#include "luxtrace/light/alias_table.hpp"

#include <algorithm>
#include <stdexcept>

namespace luxtrace {

AliasTable::AliasTable(const std::vector<double>& weights) {
    const std::size_t n = weights.size();
    double sum = 0.0;
    for (double w : weights) {
        if (!(w >= 0.0)) throw std::invalid_argument("AliasTable: negative or NaN weight");
        sum += w;
    }
    if (n == 0 || !(sum > 0.0)) throw std::invalid_argument("AliasTable: no weight");
    // Vose: scaled probabilities n p_i; cells below 1 are topped up by cells above 1.
    std::vector<double> scaled(n);
    for (std::size_t i = 0; i < n; ++i) scaled[i] = weights[i] * static_cast<double>(n) / sum;
    std::vector<std::uint32_t> small, large;
    for (std::size_t i = 0; i < n; ++i) (scaled[i] < 1.0 ? small : large).push_back(static_cast<std::uint32_t>(i));
    cells_.assign(n, Cell{1.0f, 0});
    for (std::size_t i = 0; i < n; ++i) cells_[i].alias = static_cast<std::uint32_t>(i);
    while (!small.empty() && !large.empty()) {
        const std::uint32_t s = small.back(), l = large.back();
        small.pop_back();
        cells_[s] = {static_cast<float>(scaled[s]), l};
        scaled[l] -= 1.0 - scaled[s];
        if (scaled[l] < 1.0) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // What is left is 1 up to rounding: kept whole.
    for (std::uint32_t i : small) cells_[i] = {1.0f, i};
    for (std::uint32_t i : large) cells_[i] = {1.0f, i};
}

double AliasTable::probability(int i) const {
    const double n = static_cast<double>(cells_.size());
    double p = cells_[static_cast<std::size_t>(i)].prob / n;
    for (const Cell& c : cells_)
        if (c.alias == static_cast<std::uint32_t>(i) && &c != &cells_[static_cast<std::size_t>(i)])
            p += (1.0 - c.prob) / n;
    return p;
}

}  // namespace luxtrace
