#pragma once
// What the estimates read of the scene's lights, summed per light group: each group's flux
// (a light scene's flux, an annual group's coefficients) and the E_h,ext that daylight
// factors are relative to.
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

// Every light group's flux (lm), per Scene::light_groups.
std::vector<double> light_group_flux_lm(const Scene& scene);
// E_h,ext of daylight factors: the sum over the lights of their unobstructed horizontal
// illuminance, each times its group's weight (empty weights: the plain run, all at 1).
double daylight_reference_lx(const Scene& scene, std::span<const double> weights);

}  // namespace luxtrace
