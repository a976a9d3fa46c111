#pragma once
// A sky (docs/DAYLIGHT.md): CIE, Perez or uniform luminance over the upper hemisphere, or
// a ground glow below the horizon; each photon starts on the disk perpendicular to its own
// direction that covers the scene.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/sky_directions.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

#include <memory>
#include <optional>
#include <ostream>
#include <string>

namespace luxtrace {

struct SkyLight {
    // Where its photons come from (sky frame), and the sky frame in the scene (site.hpp:
    // t = east, b = north, n = up).
    std::shared_ptr<const SkyDirections> sky;
    Frame horizon{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    std::string description;  // e.g. "CIE type 16", "uniform", "ground glow of light 2 (sun)"
    // The sun's position its luminance distribution is centred on (unused by type 16 and
    // uniform skies).
    double sun_altitude_deg = 0.0, sun_azimuth_deg = 0.0;
    Beam beam;  // the scene's sphere: centre and radius (place())

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return true; }
    double place(const SceneSphere& sphere);
    // Directions drawn in proportion to L: E = (integral of L) x mean of cos x
    // visibility (sky_directions.hpp).
    static constexpr IncidentSampling incident_sampling(int requested) { return {requested, true}; }
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double u1, double u2, int count,
                  IncidentLight& in) const;
    // The luminance seen along `direction` where a ray leaves the scene.
    double luminance_seen_cd_m2(const Vec3& direction) const {
        return sky->luminance_cd_m2(horizon.to_local(direction));
    }
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    std::optional<DaylightReference> daylight() const {
        return DaylightReference{description, sun_altitude_deg, sun_azimuth_deg, 0.0};
    }
    void describe(std::ostream& out, double unobstructed_horizontal_lx) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay SkyLight::emit(double up1, double up2, double ud1, double ud2) const {
    // Travel away from the sky element, starting on the disk that covers the scene's
    // sphere as seen from that direction.
    const Vec3 d = -horizon.to_world(sky->sample(ud1, ud2));
    return {beam.center - 1.01 * beam.radius * d + Frame::around(d).to_world(disk_point_f(beam.radius, up1, up2)), d};
}

}  // namespace luxtrace
