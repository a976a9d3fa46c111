#include "luxtrace/light/portal.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace luxtrace {

Frame Portal::frame_for(const Vec3& outward, const Frame& horizon) {
    const Vec3 up = horizon.n;
    const Vec3 in_plane = up - glm::dot(up, outward) * outward;
    const double len = glm::length(in_plane);
    // Horizontal openings: azimuth 0 to the north, as the sky's own table.
    const Vec3 b = len > 1e-9 ? in_plane / len : glm::normalize(horizon.b - glm::dot(horizon.b, outward) * outward);
    return {glm::cross(b, outward), b, outward};  // t = b x n, as east = north x up
}

PortalSky::PortalSky(const SkyLuminance& luminance, const Frame& horizon, const Frame& portal) : portal_(portal) {
    constexpr int kRows = 90;
    constexpr int kSplit = 8;
    const int columns = DirectionTable::kColumns;
    std::vector<DirectionTable::Cell> cells(static_cast<std::size_t>(kRows) * columns);
    const double a_half = 0.5 * DirectionTable::kDegree;
    // The sky frame's height of the portal frame's direction (Z, alpha).
    auto local = [&](double zenith, double azimuth) {
        const double s = std::sin(zenith);
        return Vec3(s * std::sin(azimuth), s * std::cos(azimuth), std::cos(zenith));
    };
    auto to_sky = [&](const Vec3& w) { return horizon.to_local(portal.to_world(w)); };
    auto density = [&](double zenith, double azimuth) {
        return luminance(to_sky(local(zenith, azimuth))) * std::cos(zenith);
    };
    double total = 0.0;
    for (int row = 0; row < kRows; ++row) {
        const double mu_hi = DirectionTable::mu_top(row), mu_lo = DirectionTable::mu_bottom(row);
        const double mu_half = 0.5 * (mu_hi - mu_lo);
        for (int col = 0; col < columns; ++col) {
            // Does the sky's horizon cross the cell (not just touch its edge)?
            bool above = false, below = false;
            for (const double z : {row * DirectionTable::kDegree, (row + 1) * DirectionTable::kDegree})
                for (const double a : {col * DirectionTable::kDegree, (col + 1) * DirectionTable::kDegree}) {
                    const double h = to_sky(local(z, a)).z;
                    above = above || h > 1e-9;
                    below = below || h < -1e-9;
                }
            const DirectionTable::CellIntegral in = DirectionTable::integrate(row, col, density,
                                                                              above && below ? kSplit : 1);
            DirectionTable::Cell& c = cells[static_cast<std::size_t>(row) * columns + static_cast<std::size_t>(col)];
            if (in.integral > 0.0) {
                c.slope_s = DirectionTable::slope(in.moment_s / in.integral);
                c.slope_a = DirectionTable::slope(in.moment_a / in.integral);
            }
            c.weight = in.integral * mu_half * a_half;
            total += c.weight;
        }
    }
    if (total > 0.0 && std::isfinite(total)) {
        table_ = DirectionTable(kRows, cells);
        illuminance_lx_ = table_.total();
    }
}

}  // namespace luxtrace
