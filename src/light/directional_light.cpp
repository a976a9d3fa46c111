#include "luxtrace/light/directional_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

namespace luxtrace {

double DirectionalLight::place(const SceneSphere& sphere) {
    beam.radius = sphere.radius;
    beam.center = sphere.center - 1.01 * sphere.radius * aim;
    return illuminance_lx * kPi * sphere.radius * sphere.radius;
}

bool DirectionalLight::incident(const Vec3&, const Vec3& n, double, double, double, int, IncidentLight& in) const {
    return incident_from_beam(aim, illuminance_lx, n, in);
}

LuminaireView DirectionalLight::view_from(const Vec3&, double) const {
    return not_a_luminaire("a directional beam is not a luminaire (CIE 117 rates luminaires)");
}

}  // namespace luxtrace
