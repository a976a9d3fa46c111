#pragma once
// A point light: isotropic, or a luminaire's photometry (IES, EULUMDAT) at its
// photometric centre, its photons starting on the file's luminous opening.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/luminous_opening.hpp"
#include "luxtrace/light/photometry.hpp"
#include "luxtrace/light/photometry_distribution.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

#include <memory>
#include <ostream>

namespace luxtrace {

struct PointLight {
    Vec3 position{0.0};                           // with photometry: the photometric centre
    Frame frame = Frame::around(Vec3(0, 0, -1));  // local +z = photometric axis, +x = C0 (photometry.hpp)
    // With a luminaire's photometry: its direction sampler, and the photometry as read.
    // Intensity toward a direction = photometry->intensity_cd(local) * flux_lm / photometry->flux_lm().
    std::shared_ptr<const PhotometryDistribution> distribution;
    std::shared_ptr<const Photometry> photometry;
    // Where its photons start: the file's luminous opening, or a point (`emission = "point"`).
    LuminousOpening opening;
    // The factors that made the light's flux from the file's (for reports): flux_lm =
    // photometry->flux_lm() x multiplier x lamp_factor x dimming x tilt_factor.
    double multiplier = 1.0, lamp_factor = 1.0, tilt_factor = 1.0;

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    bool draws_position() const { return opening.shape != LuminousOpening::Shape::point; }
    static constexpr bool distant() { return false; }
    // Intensity (cd) toward unit direction `out` (from the light).
    double intensity_cd(const Vec3& out, double flux_lm) const;
    static constexpr IncidentSampling incident_sampling(int) { return {1, false}; }
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const;
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    void describe_photometry(std::ostream& out) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay PointLight::emit(double up1, double up2, double ud1, double ud2) const {
    if (!distribution) return {position, sample_uniform_sphere(ud1, ud2)};
    const Vec3 d = distribution->sample(ud1, ud2);
    Vec3 origin = position;  // where on the opening depends on d (luminous_opening.hpp)
    if (opening.shape != LuminousOpening::Shape::point)
        origin += frame.to_world(sample_opening_point(opening, d, up1, up2));
    return {origin, frame.to_world(d)};
}

}  // namespace luxtrace
