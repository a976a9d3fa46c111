#pragma once
// The sun (docs/DAYLIGHT.md): rays spread evenly over the solar disc, from a disk covering
// the scene; `illuminance_lx` is the direct normal illuminance.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

#include <optional>
#include <ostream>

namespace luxtrace {

// The solar disc seen from the Earth: 0.533 degrees across.
inline constexpr double kSunHalfAngleDeg = 0.2665;

struct SunLight {
    Vec3 aim{0.0, 0.0, -1.0};                     // the direction of travel from the sun's centre
    Frame frame = Frame::around(Vec3(0, 0, -1));  // around the aim
    double cos_half_angle = 1.0;                  // the solar disc's
    double illuminance_lx = 0.0;                  // direct normal; 0 below the horizon
    double sun_altitude_deg = 0.0, sun_azimuth_deg = 0.0;
    Frame horizon{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};  // the sky frame (site.hpp)
    Beam beam;                                                   // set by place()

    // A direction of travel, uniform over the disc.
    inline Vec3 travel_direction(double u1, double u2) const;
    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return true; }
    double place(const SceneSphere& sphere);
    // A picture stands the disc by its centre.
    static constexpr IncidentSampling incident_sampling(int) { return {1, false}; }
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const;
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    std::optional<DaylightReference> daylight() const {
        return DaylightReference{"sun", sun_altitude_deg, sun_azimuth_deg, illuminance_lx};
    }
    // Below the horizon it emits nothing, and says so.
    bool may_be_dark(double) const { return illuminance_lx == 0.0; }
    void describe(std::ostream& out, double unobstructed_horizontal_lx) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline Vec3 SunLight::travel_direction(double u1, double u2) const {
    return frame.to_world(sample_uniform_cone(cos_half_angle, u1, u2));
}

inline EmittedRay SunLight::emit(double up1, double up2, double ud1, double ud2) const {
    return {beam.center + frame.to_world(disk_point(beam.radius, up1, up2)), travel_direction(ud1, ud2)};
}

}  // namespace luxtrace
