#include "luxtrace/estimate/estimate_scene.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

std::vector<double> light_group_flux_lm(const Scene& scene) {
    std::vector<double> flux(scene.light_groups.size(), 0.0);
    for (const Light& l : scene.lights.lights()) flux[l.group] += l.flux_lm;
    return flux;
}

double daylight_reference_lx(const Scene& scene, std::span<const double> weights) {
    double e = 0.0;
    for (const Light& l : scene.lights.lights())
        e += (weights.empty() ? 1.0 : weights[l.group]) * l.unobstructed_horizontal_lx;
    return e;
}

}  // namespace luxtrace
