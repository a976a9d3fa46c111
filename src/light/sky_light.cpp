#include "luxtrace/light/sky_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <iomanip>

namespace luxtrace {

EmittedRay SkyLight::emit(double up1, double up2, double ud1, double ud2) const {
    // Travel away from the sky element, starting on the disk that covers the scene's
    // sphere as seen from that direction.
    const Vec3 d = -horizon.to_world(sky->sample(ud1, ud2));
    return {beam.center - 1.01 * beam.radius * d + Frame::around(d).to_world(disk_point_f(beam.radius, up1, up2)), d};
}

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

LuminaireView SkyLight::view_from(const Vec3&, double) const {
    LuminaireView v;
    v.why_not = "daylight is not a luminaire (CIE 117 rates luminaires)";
    return v;
}

void SkyLight::describe(std::ostream& out, double unobstructed_horizontal_lx) const {
    out << ", " << description;
    if (!(unobstructed_horizontal_lx > 0.0)) return;  // a ground glow
    if (description != "CIE type 16")
        out << ", sun at altitude " << std::setprecision(4) << sun_altitude_deg << " deg, azimuth " << sun_azimuth_deg
            << " deg";
    out << ", " << std::setprecision(6) << unobstructed_horizontal_lx << " lx on the horizontal";
}

}  // namespace luxtrace
