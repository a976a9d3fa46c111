#include "luxtrace/light/sky_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <iomanip>

namespace luxtrace {

double SkyLight::place(const SceneSphere& sphere) {
    beam.radius = sphere.radius;
    beam.center = sphere.center;
    return sky->luminance_integral_cd_m2_sr() * kPi * sphere.radius * sphere.radius;
}

bool SkyLight::incident(const Vec3&, const Vec3& n, double, double u1, double u2, int count, IncidentLight& in) const {
    in.direction = horizon.to_world(sky->sample(u1, u2));
    const double cos_s = glm::dot(n, in.direction);
    if (!(cos_s > 0.0)) return false;
    in.illuminance_lx = sky->luminance_integral_cd_m2_sr() / count * cos_s;
    return true;
}

LuminaireView SkyLight::view_from(const Vec3&, double) const { return not_a_luminaire(kDaylightIsNotALuminaire); }

void SkyLight::describe(std::ostream& out, double unobstructed_horizontal_lx) const {
    out << ", " << description;
    if (!(unobstructed_horizontal_lx > 0.0)) return;  // a ground glow
    if (description != "CIE type 16")
        out << ", sun at altitude " << std::setprecision(4) << sun_altitude_deg << " deg, azimuth " << sun_azimuth_deg
            << " deg";
    out << ", " << std::setprecision(6) << unobstructed_horizontal_lx << " lx on the horizontal";
}

}  // namespace luxtrace
