#pragma once
// A sky patch (annual daylight, docs/ANNUAL.md): uniform luminance over one patch of the
// sky (light/sky_patches.hpp), directions uniform in solid angle, photons from the disk
// covering the scene perpendicular to their direction, as a sky's.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

// The patch in the sky frame: sin(altitude) in [mu_lo, mu_hi], azimuth (clockwise from
// north) from az_lo_rad over az_width_rad.
struct SkyPatchBounds {
    double mu_lo = 0.0, mu_hi = 1.0, az_lo_rad = 0.0, az_width_rad = 2.0 * kPi;
    double solid_angle_sr() const { return (mu_hi - mu_lo) * az_width_rad; }
};

struct SkyPatchLight {
    SkyPatchBounds patch;
    double luminance_cd_m2 = 0.0;
    Frame horizon{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};  // the sky frame (site.hpp)
    Beam beam;                                                   // the scene's sphere (place())

    // Toward the sky: sin(altitude) and azimuth uniform over the patch at (u1, u2).
    Vec3 sky_direction(double u1, double u2) const;
    // The direction of travel, away from the patch.
    Vec3 travel_direction(double u1, double u2) const { return -sky_direction(u1, u2); }
    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return true; }
    double place(const SceneSphere& sphere);
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    // `render` draws no patch sky: no incident light, no daylight reference.
};

// Inline: the tracer emits every photon through here (Light::emit).
inline Vec3 SkyPatchLight::sky_direction(double u1, double u2) const {
    const double mu = patch.mu_lo + u1 * (patch.mu_hi - patch.mu_lo);
    const double az = patch.az_lo_rad + u2 * patch.az_width_rad;
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return horizon.to_world(Vec3(s * std::sin(az), s * std::cos(az), mu));
}

inline EmittedRay SkyPatchLight::emit(double up1, double up2, double ud1, double ud2) const {
    const Vec3 d = travel_direction(ud1, ud2);
    return {beam.center - 1.01 * beam.radius * d + Frame::around(d).to_world(disk_point_f(beam.radius, up1, up2)), d};
}

}  // namespace luxtrace
