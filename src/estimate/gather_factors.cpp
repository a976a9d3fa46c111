#include "luxtrace/estimate/gather_factors.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace luxtrace {

namespace {

constexpr std::size_t R = kGatherRegions;

// Row i, column j <= i of a packed lower triangle.
constexpr std::size_t lower(std::size_t i, std::size_t j) { return i * (i + 1) / 2 + j; }

}  // namespace

void gather_group_factor(std::span<const double> sums, std::span<const double> products, double photons,
                         std::span<double> factor) {
    const double inv_n = photons > 0.0 ? 1.0 / photons : 0.0;
    std::array<std::array<double, R>, R> cov{}, l{};
    double largest = 0.0;
    for (std::size_t i = 0; i < R; ++i)
        for (std::size_t j = i; j < R; ++j) {
            cov[i][j] = cov[j][i] = products[TallyLayout::gather_pair(i, j)] - sums[i] * sums[j] * inv_n;
            if (i == j) largest = std::max(largest, cov[i][i]);
        }
    // Cholesky, a pivot that adds nothing new (below 1e-12 of the largest variance) dropped.
    std::array<bool, R> kept{};
    for (std::size_t j = 0; j < R; ++j) {
        double d = cov[j][j];
        for (std::size_t k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
        if (!(d > 1e-12 * largest)) continue;
        kept[j] = true;
        l[j][j] = std::sqrt(d);
        for (std::size_t i = j + 1; i < R; ++i) {
            double s = cov[i][j];
            for (std::size_t k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
            l[i][j] = s / l[j][j];
        }
    }
    // M = L^-1 by forward substitution, the dropped rows zero.
    std::array<std::array<double, R>, R> m{};
    for (std::size_t i = 0; i < R; ++i) {
        if (!kept[i]) continue;
        for (std::size_t j = 0; j <= i; ++j) {
            double s = i == j ? 1.0 : 0.0;
            for (std::size_t k = j; k < i; ++k) s -= l[i][k] * m[k][j];
            m[i][j] = s / l[i][i];
        }
    }
    for (std::size_t i = 0; i < R; ++i) {
        factor[i] = sums[i];
        for (std::size_t j = 0; j <= i; ++j) factor[R + lower(i, j)] = m[i][j];
    }
}

void gather_cell_loadings(std::span<const double> factor, double y, double sd, std::span<const double> x,
                          double photons, std::span<float> a) {
    const double inv_n = photons > 0.0 ? 1.0 / photons : 0.0;
    std::array<double, R> cov{}, load{};
    for (std::size_t r = 0; r < R; ++r) cov[r] = x[r] - y * factor[r] * inv_n;
    double norm2 = 0.0;
    for (std::size_t i = 0; i < R; ++i) {
        double s = 0.0;
        for (std::size_t j = 0; j <= i; ++j) s += factor[R + lower(i, j)] * cov[j];
        load[i] = sd > 0.0 ? s / sd : 0.0;
        norm2 += load[i] * load[i];
    }
    // The rounding of the tallies' scaled products can carry |a| a little past 1.
    const double shrink = norm2 > 1.0 ? 1.0 / std::sqrt(norm2) : 1.0;
    for (std::size_t r = 0; r < R; ++r) a[r] = static_cast<float>(load[r] * shrink);
}

}  // namespace luxtrace
