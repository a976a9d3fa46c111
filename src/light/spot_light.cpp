#include "luxtrace/light/spot_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

double SpotLight::intensity_cd(const Vec3& out, double flux_lm) const {
    if (glm::dot(out, frame.n) < cos_half_angle) return 0.0;
    return flux_lm / (2.0 * kPi * (1.0 - cos_half_angle));
}

bool SpotLight::incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const {
    return incident_from_point(
        position, p, n, [&](const Vec3& out) { return intensity_cd(out, flux_lm); }, in);
}

LuminaireView SpotLight::view_from(const Vec3&, double) const {
    LuminaireView v;
    v.placed = true;
    v.position = position;
    v.why_not = "it has no luminous area (only a point light with a photometric file's luminous opening has one)";
    return v;
}

}  // namespace luxtrace
