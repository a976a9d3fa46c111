#pragma once
// What a light is asked, as values: the photon it emits, the light it sends to a point
// (for a shadow ray), how it looks to an eye, and its daylight reference. Every kind
// (light.hpp) answers with these.
#include "luxtrace/core/math.hpp"

#include <limits>
#include <string>

namespace luxtrace {

struct EmittedRay {
    Vec3 origin;
    Vec3 direction;
    int emitter_triangle = -1;                // area lights: the scene triangle the photon leaves from,
    double emitter_u = 0.0, emitter_v = 0.0;  // and the point's barycentrics on it (as Embree's)
    // Which side of the emitter triangle the photon leaves from: +1 its front, -1 its back.
    // A portal photon starts outside the opening and checks its way back to the sky.
    int emitter_side = 1;
    bool through_portal = false;
    // A sky patch's photon aimed past its portal (SkyPatchLight through a PortalLight): it
    // carries its share of the flux but never enters the scene.
    bool missed = false;
};

// One sample of the light arriving at a point p from a light, for a shadow ray: the
// renderer's direct light, and the direct light at a sensor. The mean over samples of
// `illuminance_lx` times the visibility along `direction` is the illuminance the light
// gives a surface at p with the normal the sample was drawn for.
struct IncidentLight {
    Vec3 direction{0.0};  // unit, from p toward the light
    // How far the shadow ray goes: to `end` (a light's point; the ray stops short of an
    // emitting surface by `end_margin` ray epsilons, or passes a portal's pane by
    // -end_margin), or to infinity for a distant light.
    bool distant = true;
    Vec3 end{0.0};
    double end_margin = 0.0;
    double distance_m = std::numeric_limits<double>::infinity();  // from p to `end`
    // Through a portal: the sky must also be seen from the opening's point outward.
    bool beyond_opening = false;
    Vec3 opening_outward{0.0};
    // Per sample, already divided by the sample's density and by the number of samples
    // the kind asked for (incident_samples).
    double illuminance_lx = 0.0;
};

// The light a point source at `position` sends to p on a surface of normal n: the inverse
// square law from its intensity toward p, intensity_cd(direction from the source).
template <class Intensity>
bool incident_from_point(const Vec3& position, const Vec3& p, const Vec3& n, Intensity intensity_cd,
                         IncidentLight& in) {
    const Vec3 v = position - p;
    in.distance_m = glm::length(v);
    in.direction = v / in.distance_m;
    const double cos_s = glm::dot(n, in.direction);
    if (!(in.distance_m > 0.0) || cos_s <= 0.0) return false;
    const double i_cd = intensity_cd(-in.direction);
    if (!(i_cd > 0.0)) return false;
    in.distant = false;
    in.end = position;
    in.end_margin = 1.0;
    in.illuminance_lx = i_cd * cos_s / (in.distance_m * in.distance_m);
    return true;
}

// The light a beam of illuminance_lx (normal to it) travelling along `aim` sends to a
// surface of normal n: Lambert's cosine, from infinity.
inline bool incident_from_beam(const Vec3& aim, double illuminance_lx, const Vec3& n, IncidentLight& in) {
    const double cos_s = -glm::dot(n, aim);
    if (cos_s <= 0.0) return false;
    in.direction = -aim;
    in.illuminance_lx = illuminance_lx * cos_s;
    return true;
}

// How the light arriving at a point is sampled: not at all (count 0), by one fixed sample
// (point lights, beams), or by `count` stratified random ones (areas, skies).
struct IncidentSampling {
    int count = 0;
    bool random = false;
};

// A light as an eye sees it (CIE 117's terms for UGR, glare/observer.hpp): its luminous
// area's centre, intensity toward the eye, projected area, mean luminance and solid angle.
struct LuminaireView {
    bool luminous = false;  // it has a luminous area the eye sees
    // Where it stands in the field, if anywhere (area lights: the emitter's centre, also
    // when its front faces away; point and spot lights: their position).
    bool placed = false;
    // Whether, without a luminous area, it still stands in the field at `position` (an
    // area light whose front faces away), rather than being left out as behind the eye.
    bool field_test_when_dark = false;
    Vec3 position{0.0};
    double distance_m = 0.0, intensity_cd = 0.0, projected_area_m2 = 0.0, luminance_cd_m2 = 0.0, solid_angle_sr = 0.0;
    std::string why_not;  // when not luminous: why it cannot enter a glare sum
};

// How a light without a luminous area looks to an eye: not at all, and why.
inline LuminaireView not_a_luminaire(const char* why_not) {
    LuminaireView v;
    v.why_not = why_not;
    return v;
}
inline constexpr const char* kDaylightIsNotALuminaire = "daylight is not a luminaire (CIE 117 rates luminaires)";

// A daylight source's reference (docs/DAYLIGHT.md): its model, the sun's position it uses
// and, for the sun, its direct normal illuminance.
struct DaylightReference {
    std::string model;  // "sun", or the sky's description ("CIE type 16", "Perez (...)")
    double sun_altitude_deg = 0.0, sun_azimuth_deg = 0.0;
    double direct_normal_lx = 0.0;
};

// The disk a distant light's photons start on: covering the scene's bounding sphere as
// seen from the light (light.hpp: Light::place).
struct Beam {
    Vec3 center{0.0};
    double radius = 0.0;
};

// The sphere a beam must cover: around the box [lo, hi], a little larger.
struct SceneSphere {
    Vec3 center{0.0};
    double radius = 0.0;
    static SceneSphere around(const Vec3& lo, const Vec3& hi) {
        return {0.5 * (lo + hi), 0.5 * glm::length(hi - lo) * 1.001 + 1e-6};
    }
};

}  // namespace luxtrace
