#include "luxtrace/light/spot_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

double SpotLight::intensity_cd(const Vec3& out, double flux_lm) const {
    if (glm::dot(out, frame.n) < cos_half_angle) return 0.0;
    return flux_lm / (2.0 * kPi * (1.0 - cos_half_angle));
}

bool SpotLight::incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const {
    const Vec3 v = position - p;
    in.distance_m = glm::length(v);
    in.direction = v / in.distance_m;
    const double cos_s = glm::dot(n, in.direction);
    if (!(in.distance_m > 0.0) || cos_s <= 0.0) return false;
    const double i_cd = intensity_cd(-in.direction, flux_lm);
    if (!(i_cd > 0.0)) return false;
    in.distant = false;
    in.end = position;
    in.end_margin = 1.0;
    in.illuminance_lx = i_cd * cos_s / (in.distance_m * in.distance_m);
    return true;
}

LuminaireView SpotLight::view_from(const Vec3&, double) const {
    LuminaireView v;
    v.placed = true;
    v.position = position;
    v.why_not = "it has no luminous area (only a point light with a photometric file's luminous opening has one)";
    return v;
}

}  // namespace luxtrace
