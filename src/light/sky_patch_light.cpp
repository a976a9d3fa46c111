#include "luxtrace/light/sky_patch_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

Vec3 SkyPatchLight::sky_direction(double u1, double u2) const {
    const double mu = patch.mu_lo + u1 * (patch.mu_hi - patch.mu_lo);
    const double az = patch.az_lo_rad + u2 * patch.az_width_rad;
    const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
    return horizon.to_world(Vec3(s * std::sin(az), s * std::cos(az), mu));
}

EmittedRay SkyPatchLight::emit(double up1, double up2, double ud1, double ud2) const {
    const Vec3 d = travel_direction(ud1, ud2);
    return {beam.center - 1.01 * beam.radius * d + Frame::around(d).to_world(disk_point_f(beam.radius, up1, up2)), d};
}

double SkyPatchLight::place(const SceneSphere& sphere) {
    beam.radius = sphere.radius;
    beam.center = sphere.center;
    return luminance_cd_m2 * patch.solid_angle_sr() * kPi * sphere.radius * sphere.radius;
}

LuminaireView SkyPatchLight::view_from(const Vec3&, double) const {
    LuminaireView v;
    v.why_not = "daylight is not a luminaire (CIE 117 rates luminaires)";
    return v;
}

}  // namespace luxtrace
