#include "luxtrace/light/directional_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

double DirectionalLight::place(const SceneSphere& sphere) {
    beam.radius = sphere.radius;
    beam.center = sphere.center - 1.01 * sphere.radius * aim;
    return illuminance_lx * kPi * sphere.radius * sphere.radius;
}

bool DirectionalLight::incident(const Vec3&, const Vec3& n, double, double, double, int, IncidentLight& in) const {
    const double cos_s = -glm::dot(n, aim);
    if (cos_s <= 0.0) return false;
    in.direction = -aim;
    in.illuminance_lx = illuminance_lx * cos_s;
    return true;
}

LuminaireView DirectionalLight::view_from(const Vec3&, double) const {
    LuminaireView v;
    v.why_not = "a directional beam is not a luminaire (CIE 117 rates luminaires)";
    return v;
}

}  // namespace luxtrace
