#include "luxtrace/light/sky_directions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace luxtrace {

namespace {

// 4-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 4> kNodes{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                       0.8611363115940526};
constexpr std::array<double, 4> kWeights{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                         0.3478548451374538};

constexpr double kDegree = kPi / 180.0;

// Within a cell the density of x in [0, 1] is 1 + k (x - 1/2), whose mean is 1/2 + k / 12:
// the k that gives the cell's own mean, kept in [-2, 2] where the density stays >= 0.
float linear_slope(double mean) { return static_cast<float>(std::clamp(12.0 * (mean - 0.5), -2.0, 2.0)); }

// Inverse of the cdf x + k (x^2 - x) / 2 of that density at u, in the form that stays
// accurate as k goes to 0.
double linear_inverse(double k, double u) {
    const double b = 1.0 - 0.5 * k;
    return std::clamp(2.0 * u / (b + std::sqrt(std::max(0.0, b * b + 2.0 * k * u))), 0.0, 1.0);
}

}  // namespace

SkyDirections::SkyDirections(const std::optional<SkyModel>& sky, double zenith_luminance_cd_m2,
                             double ground_luminance_cd_m2) {
    std::vector<double> w(static_cast<std::size_t>(kRows) * kColumns, 0.0);
    slope_s_.assign(w.size(), 0.0f);
    for (int row = 0; row <= kRows; ++row) mu_[static_cast<std::size_t>(row)] = std::cos(row * kDegree);
    mu_[kRows / 2] = 0.0;  // the horizon exactly: no photon of the sky from below it
    mu_[kRows] = -1.0;
    for (int col = 0; col < kColumns; ++col) {
        sin_edge_[static_cast<std::size_t>(col)] = std::sin(col * kDegree);
        cos_edge_[static_cast<std::size_t>(col)] = std::cos(col * kDegree);
    }
    slope_a_.assign(w.size(), 0.0f);
    double horizontal = 0.0;
    for (int row = 0; row < kRows; ++row) {
        // Rows by zenith angle; within a row the rule runs over cos Z, in which solid
        // angle is uniform (dw = d(cos Z) d alpha).
        const double mu_hi = mu_[static_cast<std::size_t>(row)], mu_lo = mu_[static_cast<std::size_t>(row) + 1];
        const double mu_mid = 0.5 * (mu_hi + mu_lo), mu_half = 0.5 * (mu_hi - mu_lo);
        const bool above = row < kRows / 2;
        for (int col = 0; col < kColumns; ++col) {
            const std::size_t cell = static_cast<std::size_t>(row) * kColumns + static_cast<std::size_t>(col);
            if (!above) {
                w[cell] = ground_luminance_cd_m2 * (mu_hi - mu_lo) * kDegree;
                continue;
            }
            if (!sky) continue;
            // The cell's integral and the first moments of its position s (0 at its top
            // edge, 1 at its bottom) and a (0 at its first azimuth, 1 at its last).
            double integral = 0.0, moment_s = 0.0, moment_a = 0.0;
            const double a_mid = (col + 0.5) * kDegree, a_half = 0.5 * kDegree;
            for (std::size_t i = 0; i < kNodes.size(); ++i) {
                const double mu = mu_mid + mu_half * kNodes[i];
                const double zenith = std::acos(mu);
                for (std::size_t j = 0; j < kNodes.size(); ++j) {
                    const double v = kWeights[i] * kWeights[j] *
                                     sky->relative_luminance(zenith, a_mid + a_half * kNodes[j]);
                    integral += v;
                    moment_s += v * 0.5 * (1.0 - kNodes[i]);
                    moment_a += v * 0.5 * (1.0 + kNodes[j]);
                }
            }
            if (integral > 0.0) {
                slope_s_[cell] = linear_slope(moment_s / integral);
                slope_a_[cell] = linear_slope(moment_a / integral);
                // As sampled: the linear density's mean cos Z, the cell's own to the rule's accuracy.
                const double mean_s = 0.5 + static_cast<double>(slope_s_[cell]) / 12.0;
                horizontal += integral * zenith_luminance_cd_m2 * mu_half * a_half * (mu_hi - 2.0 * mu_half * mean_s);
            }
            w[cell] = integral * zenith_luminance_cd_m2 * mu_half * a_half;
        }
    }
    for (double v : w) total_ += v;
    if (!(total_ > 0.0) || !std::isfinite(total_)) throw std::invalid_argument("the sky and ground emit nothing");
    horizontal_lx_ = horizontal;
    cells_ = AliasTable(w);
    for (double& v : w) v /= total_;
    weight_ = std::move(w);
}

Vec3 SkyDirections::sample(double u1, double u2) const {
    const AliasTable::Pick p = cells_.sample(u1);
    const int row = p.cell / kColumns, col = p.cell % kColumns;
    const std::size_t cell = static_cast<std::size_t>(p.cell);
    const double mu_hi = mu_[static_cast<std::size_t>(row)], mu_lo = mu_[static_cast<std::size_t>(row) + 1];
    const double mu = mu_hi + linear_inverse(slope_s_[cell], p.t) * (mu_lo - mu_hi);
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    // sin and cos of the azimuth from the cell's first edge turned by delta < 1 degree
    // (Taylor to delta^7 / 7!, below 1e-16 there): no transcendental call per photon.
    const double delta = linear_inverse(slope_a_[cell], u2) * kDegree, d2 = delta * delta;
    const double cos_d = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0));
    const double sin_d = delta * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0)));
    const double sin_0 = sin_edge_[static_cast<std::size_t>(col)], cos_0 = cos_edge_[static_cast<std::size_t>(col)];
    return {s * (sin_0 * cos_d + cos_0 * sin_d), s * (cos_0 * cos_d - sin_0 * sin_d), mu};
}

double SkyDirections::cell_probability(int row, int column) const {
    return weight_.at(static_cast<std::size_t>(row) * kColumns + static_cast<std::size_t>(column));
}

}  // namespace luxtrace
