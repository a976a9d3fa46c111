#pragma once
// Surface materials and their analog scattering: at each arrival a photon of band b is
// reflected, transmitted or absorbed with the material's probabilities for that band,
// so every tally stays an integer count (SPEC §3).
#include "luxtrace/core/math.hpp"
#include "luxtrace/material/glazing.hpp"
#include "luxtrace/material/ward_lobe.hpp"

#include <memory>
#include <string>
#include <vector>

namespace luxtrace {

enum class MaterialType { diffuse, mirror, glass, general, black, glazing };

struct Material {
    std::string name;
    MaterialType type = MaterialType::diffuse;
    // Per-band probabilities (one entry per scene band). For `diffuse` only
    // diffuse_reflectance is used, for `mirror` only specular_reflectance; `general`
    // uses all four (thin surface, specular transmission goes straight through).
    std::vector<double> diffuse_reflectance;
    std::vector<double> specular_reflectance;
    std::vector<double> diffuse_transmittance;
    std::vector<double> specular_transmittance;
    // mirror, general: the specular reflection's roughness (Radiance's, the rms facet
    // slope alpha of ward_lobe.hpp). 0 reflects as a mirror; above 0 into the glossy lobe,
    // which `lobe` holds (make it with set_roughness), shared by every copy.
    double roughness = 0.0;
    std::shared_ptr<const WardLobe> lobe;
    // glass: refractive index (Fresnel at each interface) and the probability that a
    // refracted photon survives the crossing (1 = clear glass).
    // glazing: the same two fields hold the pane's refractive index and its normal
    // transmittance per band (empty for a maker's table).
    double ior = 1.5;
    std::vector<double> transmittance;
    // glazing: R and T against the angle of incidence, one curve per band (glazing.hpp),
    // shared by every copy of the material.
    std::shared_ptr<const std::vector<GlazingCurve>> glazing;

    // Sets `roughness` in [0, WardLobe::kMaxRoughness] and the lobe it needs (none for 0).
    void set_roughness(double alpha);
};

enum class ScatterEvent {
    absorbed,
    diffuse_reflection,
    specular_reflection,
    diffuse_transmission,
    specular_transmission,
    refraction
};

// A glossy reflection is reported as specular_reflection (its direction is the lobe's).
struct Scattered {
    ScatterEvent event = ScatterEvent::absorbed;
    Vec3 direction{0.0};
    // +1: the photon leaves on the side it came from; -1: it crosses the surface.
    int side = 1;
};

// Unpolarised Fresnel reflectance of a dielectric interface. cos_i > 0 is the cosine
// of incidence, eta = n_incident / n_transmitted. Returns 1 for total internal reflection.
double fresnel_dielectric(double cos_i, double eta);

// Cosine-weighted direction on the hemisphere around n (Malley's method).
Vec3 sample_cosine_hemisphere(const Vec3& n, double u1, double u2);

// One material in one band, flattened for the tracing path: the event thresholds as
// cumulative probabilities (u_event below `diffuse_reflection` reflects diffusely, below
// `specular_reflection` specularly, and so on; above the last one the photon is
// absorbed), for glass its index and the survival of a crossing, for glazing its curve,
// for a rough specular reflection its lobe (both owned by the Material, which must
// outlive the model).
struct ScatterModel {
    MaterialType type = MaterialType::black;
    double diffuse_reflection = 0.0, specular_reflection = 0.0;
    double diffuse_transmission = 0.0, specular_transmission = 0.0;
    double ior = 1.5, transmittance = 1.0;
    const GlazingCurve* glazing = nullptr;
    const WardLobe* lobe = nullptr;
};
ScatterModel scatter_model(const Material& m, int band);

// Scatter a photon travelling along unit `dir` that hit a surface with unit geometric
// normal `ng` (either orientation: the front side is where ng points). u_event picks the
// event, (u1, u2) its direction. Glass is entered from the front side.
Scattered scatter(const ScatterModel& m, const Vec3& dir, const Vec3& ng, double u_event, double u1, double u2);
// The same for a photon of `band` on material `m`.
inline Scattered scatter(const Material& m, int band, const Vec3& dir, const Vec3& ng, double u_event, double u1,
                         double u2) {
    return scatter(scatter_model(m, band), dir, ng, u_event, u1, u2);
}

// Probability that a photon of `band` hitting the material at normal incidence survives
// (used for checks and warnings, not for tracing).
double albedo(const Material& m, int band);

}  // namespace luxtrace
