#pragma once
// An area light: a named shape's triangles emitting from their front sides, Lambertian
// and uniform over the area.
#include "luxtrace/light/emitter_surface.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/uniform_sampling.hpp"
#include "luxtrace/material/material.hpp"

#include <ostream>

namespace luxtrace {

struct AreaLight {
    EmitterSurface surface;

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return false; }
    static constexpr IncidentSampling incident_sampling(int requested) { return {requested, true}; }
    // One of `count` stratified samples (incident_light in light.hpp).
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double u1, double u2, int count,
                  IncidentLight& in) const;
    // Uniform luminance M / pi from the front side, M = flux / area.
    double luminance_cd_m2(double flux_lm) const { return flux_lm / (kPi * surface.area_m2); }
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    void describe(std::ostream& out, double) const { out << " from " << surface.area_m2 << " m^2"; }
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay AreaLight::emit(double up1, double up2, double ud1, double ud2) const {
    // A Lambertian direction from the point's front side.
    const SurfacePick s = surface_point(surface, up1, up2);
    return {s.point, sample_cosine_hemisphere(surface.normal[s.triangle], ud1, ud2), surface.scene_triangle[s.triangle],
            s.a, s.b};
}

}  // namespace luxtrace
