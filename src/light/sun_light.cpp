#include "luxtrace/light/sun_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <cmath>
#include <iomanip>

namespace luxtrace {

double SunLight::place(const SceneSphere& sphere) {
    // Rays up to the disc's half angle off the aim drift sideways by at most 2.02 r tan(a)
    // before they leave the sphere: the disk is that much larger.
    const double half = kSunHalfAngleDeg * kPi / 180.0;
    beam.radius = sphere.radius * (1.0 + 2.1 * std::tan(half));
    beam.center = sphere.center - 1.01 * sphere.radius * aim;
    return illuminance_lx * kPi * beam.radius * beam.radius;
}

bool SunLight::incident(const Vec3&, const Vec3& n, double, double, double, int, IncidentLight& in) const {
    return incident_from_beam(aim, illuminance_lx, n, in);
}

LuminaireView SunLight::view_from(const Vec3&, double) const { return not_a_luminaire(kDaylightIsNotALuminaire); }

void SunLight::describe(std::ostream& out, double unobstructed_horizontal_lx) const {
    out << ", sun at altitude " << std::setprecision(4) << sun_altitude_deg << " deg, azimuth " << sun_azimuth_deg
        << " deg, " << std::setprecision(6) << illuminance_lx << " lx normal, " << std::setprecision(6)
        << unobstructed_horizontal_lx << " lx on the horizontal";
}

}  // namespace luxtrace
