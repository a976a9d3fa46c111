#pragma once
// A spot: a point emitting uniformly into a cone around its axis.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

struct SpotLight {
    Vec3 position{0.0};
    Frame frame = Frame::around(Vec3(0, 0, -1));  // local +z = the axis
    double cos_half_angle = 1.0;

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return false; }
    static constexpr bool distant() { return false; }
    double intensity_cd(const Vec3& out, double flux_lm) const;
    static constexpr IncidentSampling incident_sampling(int) { return {1, false}; }
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const;
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay SpotLight::emit(double, double, double ud1, double ud2) const {
    return {position, frame.to_world(sample_uniform_cone(cos_half_angle, ud1, ud2))};
}

}  // namespace luxtrace
