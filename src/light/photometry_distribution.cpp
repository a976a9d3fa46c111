// Emission sampling from a goniometric table; see photometry_distribution.hpp.
#include "luxtrace/light/photometry_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace luxtrace {
namespace {
constexpr double kDeg = kPi / 180.0;
}

PhotometryDistribution::PhotometryDistribution(const Photometry& p, int n_lat, int n_lon) : type_(p.type) {
    if (n_lat < 1 || n_lon < 1) throw std::invalid_argument("PhotometryDistribution: grid size < 1");
    const bool type_c = type_ == PhotometricType::C;
    // Rows: gamma for type C, else the latitude (H for B, V for A), over the table's range.
    const std::vector<double>& lat_angles = type_c || type_ == PhotometricType::A ? p.vertical_deg : p.horizontal_deg;
    const std::vector<double>& lon_angles = type_c || type_ == PhotometricType::A ? p.horizontal_deg : p.vertical_deg;
    const double lat_lo = type_c ? 0.0 : -90.0, lat_hi = type_c ? 180.0 : 90.0;
    const double lat0 = std::clamp(lat_angles.front(), lat_lo, lat_hi) * kDeg;
    const double lat1 = std::clamp(lat_angles.back(), lat_lo, lat_hi) * kDeg;
    n_lat_ = std::max(1, static_cast<int>(std::ceil(n_lat * (lat1 - lat0) / kPi - 1e-9)));
    const double dlat = (lat1 - lat0) / n_lat_;
    if (type_c) {
        symmetry_ = p.symmetry();
        switch (symmetry_) {
        case CPlaneSymmetry::Rotational:
            copies_ = 1;
            lon0_ = 0.0;
            lon_span_ = 2.0 * kPi;
            break;
        case CPlaneSymmetry::Quadrant:
            copies_ = 4;
            lon0_ = 0.0;
            lon_span_ = 0.5 * kPi;
            break;
        case CPlaneSymmetry::Bilateral:
            copies_ = 2;
            lon0_ = 0.0;
            lon_span_ = kPi;
            break;
        case CPlaneSymmetry::Bilateral90:
            copies_ = 2;
            lon0_ = 0.5 * kPi;
            lon_span_ = kPi;
            break;
        case CPlaneSymmetry::Full:
            copies_ = 1;
            lon0_ = 0.0;
            lon_span_ = 2.0 * kPi;
            break;
        }
    } else {
        copies_ = 1;
        lon0_ = lon_angles.front() * kDeg;
        lon_span_ = std::max(lon_angles.back() * kDeg - lon0_, 0.0);
    }
    // Rotational symmetry: the same in every C-plane, so one column.
    n_lon_ = type_c && symmetry_ == CPlaneSymmetry::Rotational
                 ? 1
                 : std::max(1, static_cast<int>(std::ceil(n_lon * lon_span_ / (2.0 * kPi) - 1e-9)));
    const double dlon = lon_span_ / n_lon_;
    edge_.resize(n_lat_ + 1);
    for (int i = 0; i <= n_lat_; ++i) edge_[i] = type_c ? std::cos(lat0 + i * dlat) : std::sin(lat0 + i * dlat);
    if (type_c && lat1 >= kPi) edge_[n_lat_] = -1.0;

    // Cell weight: intensity at the cell centre times the cell's exact solid angle.
    std::vector<double> row_flux(static_cast<std::size_t>(n_lat_), 0.0), cells(static_cast<std::size_t>(n_lon_));
    rows_.reserve(static_cast<std::size_t>(n_lat_));
    for (int i = 0; i < n_lat_; ++i) {
        const double lat = (lat0 + (i + 0.5) * dlat) / kDeg;
        const double solid = std::abs(edge_[i] - edge_[i + 1]) * dlon;
        double sum = 0.0;
        for (int j = 0; j < n_lon_; ++j) {
            const double lon = (lon0_ + (j + 0.5) * dlon) / kDeg;
            double cd = 0.0;
            if (type_c) cd = p.intensity_cd(lat * kDeg, lon * kDeg);
            else if (type_ == PhotometricType::B) cd = p.table_cd(lat, lon);
            else cd = p.table_cd(lon, lat);
            sum += (cells[j] = cd * solid);
        }
        row_flux[i] = sum;
        // A dark row is never chosen; it keeps a uniform table to stay well formed.
        if (!(sum > 0.0)) std::fill(cells.begin(), cells.end(), 1.0);
        rows_.emplace_back(cells);
    }
    double total = 0.0;
    for (double f : row_flux) total += f;
    flux_lm_ = total * copies_;
    if (!(flux_lm_ > 0.0) || !std::isfinite(flux_lm_)) throw std::invalid_argument("PhotometryDistribution: zero flux");
    marginal_ = AliasTable(row_flux);
}

Vec3 PhotometryDistribution::sample(double u1, double u2) const {
    constexpr double kOneMinus = 1.0 - 0x1p-53;
    u1 = std::clamp(u1, 0.0, kOneMinus);
    u2 = std::clamp(u2, 0.0, kOneMinus);
    const auto [i, t1] = marginal_.sample(u1);
    // cos gamma (C) or sin latitude (B, A), uniform within the row.
    const double m = edge_[i] + t1 * (edge_[i + 1] - edge_[i]);
    const double r = std::sqrt(std::max(0.0, 1.0 - m * m));
    // Which copy of the table's C-planes: u2's leading part; the rest of u2 samples c.
    const int copy = std::min(copies_ - 1, static_cast<int>(u2 * copies_));
    const double u_c = std::clamp(u2 * copies_ - copy, 0.0, kOneMinus);
    double lon = 0.0;
    if (type_ == PhotometricType::C && symmetry_ == CPlaneSymmetry::Rotational) {
        lon = 2.0 * kPi * u_c;
    } else {
        const auto [j, t2] = rows_[static_cast<std::size_t>(i)].sample(u_c);
        lon = lon0_ + (j + t2) * (lon_span_ / n_lon_);
        // The copy by the file's mirror planes (Photometry::intensity_cd folds back).
        switch (symmetry_) {
        case CPlaneSymmetry::Quadrant:
            if (copy == 1) lon = kPi - lon;
            else if (copy == 2) lon = kPi + lon;
            else if (copy == 3) lon = 2.0 * kPi - lon;
            break;
        case CPlaneSymmetry::Bilateral:
            if (copy == 1) lon = 2.0 * kPi - lon;
            break;
        case CPlaneSymmetry::Bilateral90:
            if (copy == 1) lon = kPi - lon;  // mirrored about the 90-270 plane
            break;
        default: break;
        }
    }
    // The angle in float (good to 1e-7, as Embree takes directions), renormalised.
    const auto lf = static_cast<float>(lon);
    const double cl = static_cast<double>(std::cos(lf)), sl = static_cast<double>(std::sin(lf));
    switch (type_) {
    case PhotometricType::C: return glm::normalize(Vec3(r * cl, r * sl, m));
    case PhotometricType::B: return glm::normalize(Vec3(m, r * sl, r * cl));  // lon = V, m = sin H
    case PhotometricType::A: return glm::normalize(Vec3(r * sl, m, r * cl));  // lon = H, m = sin V
    }
    return {0.0, 0.0, 1.0};
}

}  // namespace luxtrace
