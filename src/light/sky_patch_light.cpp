#include "luxtrace/light/sky_patch_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

double SkyPatchLight::place(const SceneSphere& sphere) {
    beam.radius = sphere.radius;
    beam.center = sphere.center;
    return luminance_cd_m2 * patch.solid_angle_sr() * kPi * sphere.radius * sphere.radius;
}

LuminaireView SkyPatchLight::view_from(const Vec3&, double) const { return not_a_luminaire(kDaylightIsNotALuminaire); }

}  // namespace luxtrace
