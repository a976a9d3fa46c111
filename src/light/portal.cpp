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

Light light_through_portal(const Light& light, const std::shared_ptr<const Portal>& portal) {
    Light l = light;
    l.portal = portal;
    l.label = light.label + " through portal '" + portal->name + "'";
    const double area = portal->surface.area_m2;
    if (light.type == LightType::sky_patch) {
        // The disk around the opening (Light::emit_through_portal_disk).
        const EmitterSurface& s = portal->surface;
        Vec3 centroid(0.0);
        for (std::size_t i = 0; i < s.p0.size(); ++i) {
            const double share = s.cdf[i] - (i == 0 ? 0.0 : s.cdf[i - 1]);
            centroid += share * (s.p0[i] + (s.e1[i] + s.e2[i]) / 3.0);
        }
        double radius = 0.0;
        for (std::size_t i = 0; i < s.p0.size(); ++i)
            for (const Vec3& v : {s.p0[i], s.p0[i] + s.e1[i], s.p0[i] + s.e2[i]})
                radius = std::max(radius, glm::length(v - centroid));
        l.beam_center = centroid;
        l.beam_radius = radius * (1.0 + 1e-9) + 1e-12;
        // Does any of the patch face the opening's outside? cos(theta) is linear in the
        // direction, so between the points of a 5 x 5 grid it changes by less than the
        // grid's angular step (< 0.1 rad for any patch): a patch is dropped only when it lies
        // behind the opening by more than that everywhere.
        bool faces = false;
        for (int im = 0; im <= 4; ++im)
            for (int ia = 0; ia <= 4; ++ia) {
                const double mu = light.patch.mu_lo + 0.25 * im * (light.patch.mu_hi - light.patch.mu_lo);
                const double az = light.patch.az_lo_rad + 0.25 * ia * light.patch.az_width_rad;
                const double c = std::sqrt(std::max(0.0, 1.0 - mu * mu));
                faces = faces || glm::dot(light.horizon.to_world(Vec3(c * std::sin(az), c * std::cos(az), mu)),
                                          portal->outward) > -0.1;
            }
        l.flux_lm = faces ? light.patch_luminance_cd_m2 * light.patch.solid_angle_sr() * kPi * l.beam_radius *
                                l.beam_radius
                          : 0.0;
    } else if (light.type == LightType::sun) {
        // Directions from the disc as without the portal; E_n A cos(theta_sun).
        l.flux_lm = light.illuminance_lx * area * std::max(0.0, -glm::dot(light.aim, portal->outward));
    } else {
        auto sky = std::make_shared<const PortalSky>(light.sky->luminance(), light.horizon, portal->frame);
        l.flux_lm = sky->illuminance_lx() * area;
        l.portal_sky = std::move(sky);
    }
    return l;
}

}  // namespace luxtrace
