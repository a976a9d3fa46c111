#include "luxtrace/light/direction_table.hpp"

#include <algorithm>
#include <stdexcept>

namespace luxtrace {

namespace {

// Inverse of the cdf x + k (x^2 - x) / 2 of the linear density at u, in the form that
// stays accurate as k goes to 0.
double linear_inverse(double k, double u) {
    const double b = 1.0 - 0.5 * k;
    return std::clamp(2.0 * u / (b + std::sqrt(std::max(0.0, b * b + 2.0 * k * u))), 0.0, 1.0);
}

}  // namespace

float DirectionTable::slope(double mean) { return static_cast<float>(std::clamp(12.0 * (mean - 0.5), -2.0, 2.0)); }

DirectionTable::DirectionTable(int rows, const std::vector<Cell>& cells) {
    for (int r = 0; r <= rows; ++r) mu_.push_back(r == 90 ? 0.0 : (r == 180 ? -1.0 : mu_top(r)));
    for (int c = 0; c < kColumns; ++c) {
        sin_edge_[static_cast<std::size_t>(c)] = std::sin(c * kDegree);
        cos_edge_[static_cast<std::size_t>(c)] = std::cos(c * kDegree);
    }
    if (cells.size() != static_cast<std::size_t>(rows) * kColumns)
        throw std::invalid_argument("direction table: " + std::to_string(cells.size()) + " cells for " +
                                    std::to_string(rows) + " rows");
    std::vector<double> w(cells.size());
    slope_s_.resize(cells.size());
    slope_a_.resize(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
        w[c] = cells[c].weight;
        slope_s_[c] = cells[c].slope_s;
        slope_a_[c] = cells[c].slope_a;
    }
    for (double v : w) total_ += v;
    if (!(total_ > 0.0) || !std::isfinite(total_)) throw std::invalid_argument("the table's directions carry nothing");
    cells_ = AliasTable(w);
    for (double& v : w) v /= total_;
    weight_ = std::move(w);
}

Vec3 DirectionTable::sample(double u1, double u2) const {
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

double DirectionTable::cell_probability(int row, int column) const {
    return weight_.at(static_cast<std::size_t>(row) * kColumns + static_cast<std::size_t>(column));
}

}  // namespace luxtrace
