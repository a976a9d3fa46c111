#pragma once
// A directional light: parallel rays of one illuminance from a disk covering the scene.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

struct DirectionalLight {
    Vec3 aim{0.0, 0.0, -1.0};                     // the direction the light travels
    Frame frame = Frame::around(Vec3(0, 0, -1));  // around the aim
    double illuminance_lx = 0.0;                  // on a plane facing the beam
    Beam beam;                                    // set by place()

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return true; }
    // Covers `sphere`, started just outside it; the flux that crosses the disk.
    double place(const SceneSphere& sphere);
    static constexpr IncidentSampling incident_sampling(int) { return {1, false}; }
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const;
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay DirectionalLight::emit(double up1, double up2, double, double) const {
    return {beam.center + frame.to_world(disk_point(beam.radius, up1, up2)), aim};
}

}  // namespace luxtrace
