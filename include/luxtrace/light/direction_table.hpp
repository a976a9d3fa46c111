#pragma once
// A distribution of directions tabulated on a grid of 1 degree of polar angle by 1 degree
// of azimuth around a pole, sampled by an alias table over the cells (sky_directions.hpp,
// portal.hpp). Each cell's weight is the integral of the density over the cell, by a
// 4 x 4 Gauss-Legendre rule in cos(polar angle) and azimuth, in which solid angle is
// uniform (dw = d(cos Z) d alpha). Within a cell, cos Z and the azimuth are drawn from
// densities linear in each, with the means of the density's own over the cell: the cells
// carry the flux and the first moments exactly (to the rule's accuracy), what remains is
// of second order in the cell's size.
//
// Directions in the table's frame: z the pole; azimuth clockwise from +y seen from above
// the pole, so (Z, alpha) is (sin Z sin alpha, sin Z cos alpha, cos Z), as in sky_model.hpp.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/alias_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace luxtrace {

class DirectionTable {
public:
    static constexpr int kColumns = 360;  // azimuth 0..360 degrees
    static constexpr double kDegree = kPi / 180.0;

    // One cell's integral of a density f(Z, alpha) and the first moments of its position
    // s (0 at the cell's top edge, cos Z = cos(row deg); 1 at its bottom) and a (0 at its
    // first azimuth, 1 at its last), in units of the rule's half widths: the integral over
    // solid angle is integral x mu_half x a_half (half_widths()).
    struct CellIntegral {
        double integral = 0.0, moment_s = 0.0, moment_a = 0.0;
    };
    // The rule over the cell (split = 1), or over split x split sub-cells (for a density
    // with a discontinuity inside the cell).
    template <class F>
    static CellIntegral integrate(int row, int col, const F& f, int split = 1);
    // cos Z at the top and bottom edges of a row.
    static double mu_top(int row) { return std::cos(row * kDegree); }
    static double mu_bottom(int row) { return std::cos((row + 1) * kDegree); }

    // What a cell holds: its weight (the integral over it, any positive scale) and the
    // slopes of its linear densities (slope()).
    struct Cell {
        double weight = 0.0;
        float slope_s = 0.0f, slope_a = 0.0f;
    };
    // Within a cell the density of x in [0, 1] is 1 + k (x - 1/2), whose mean is
    // 1/2 + k / 12: the k that gives the cell's own mean, kept in [-2, 2] where the density
    // stays >= 0.
    static float slope(double mean);
    // The mean position s of a cell's sampled cos Z (0 top, 1 bottom) for its slope.
    static double mean_s(float slope_s) { return 0.5 + static_cast<double>(slope_s) / 12.0; }

    DirectionTable() = default;
    // `rows` rows of 1 degree from the pole, cells row by row. Throws std::invalid_argument
    // when the weights do not sum to a positive finite number.
    DirectionTable(int rows, const std::vector<Cell>& cells);

    // A unit direction in the table's frame; u1, u2 in [0, 1).
    Vec3 sample(double u1, double u2) const;
    // The sum of the weights.
    double total() const { return total_; }
    // The probability of cell (row, column).
    double cell_probability(int row, int column) const;

private:
    AliasTable cells_;
    std::vector<double> mu_;  // cos Z at the rows' edges (rows + 1; the horizon exactly 0)
    std::array<double, kColumns> sin_edge_{}, cos_edge_{};  // of the columns' first azimuths
    double total_ = 0.0;
    std::vector<double> weight_;            // per cell, normalised
    std::vector<float> slope_s_, slope_a_;  // per cell
};

namespace direction_table_detail {
// 4-point Gauss-Legendre on [-1, 1].
inline constexpr std::array<double, 4> kNodes{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                              0.8611363115940526};
inline constexpr std::array<double, 4> kWeights{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                0.3478548451374538};
}  // namespace direction_table_detail

template <class F>
DirectionTable::CellIntegral DirectionTable::integrate(int row, int col, const F& f, int split) {
    using direction_table_detail::kNodes;
    using direction_table_detail::kWeights;
    const double mu_hi = mu_top(row), mu_lo = mu_bottom(row);
    const double mu_mid = 0.5 * (mu_hi + mu_lo), mu_half = 0.5 * (mu_hi - mu_lo);
    const double a_mid = (col + 0.5) * kDegree, a_half = 0.5 * kDegree;
    CellIntegral c;
    if (split <= 1) {
        for (std::size_t i = 0; i < kNodes.size(); ++i) {
            const double mu = mu_mid + mu_half * kNodes[i];
            const double zenith = std::acos(mu);
            for (std::size_t j = 0; j < kNodes.size(); ++j) {
                const double v = kWeights[i] * kWeights[j] * f(zenith, a_mid + a_half * kNodes[j]);
                c.integral += v;
                c.moment_s += v * 0.5 * (1.0 - kNodes[i]);
                c.moment_a += v * 0.5 * (1.0 + kNodes[j]);
            }
        }
        return c;
    }
    const double scale = 1.0 / (static_cast<double>(split) * split);
    for (int si = 0; si < split; ++si)
        for (int sj = 0; sj < split; ++sj)
            for (std::size_t i = 0; i < kNodes.size(); ++i) {
                const double s = (si + 0.5 * (1.0 - kNodes[i])) / split;  // 0 at the top edge
                const double mu = mu_hi - 2.0 * mu_half * s;
                const double zenith = std::acos(std::clamp(mu, -1.0, 1.0));
                for (std::size_t j = 0; j < kNodes.size(); ++j) {
                    const double a = (sj + 0.5 * (1.0 + kNodes[j])) / split;
                    const double v = scale * kWeights[i] * kWeights[j] * f(zenith, a_mid + a_half * (2.0 * a - 1.0));
                    c.integral += v;
                    c.moment_s += v * s;
                    c.moment_a += v * a;
                }
            }
    return c;
}

}  // namespace luxtrace
