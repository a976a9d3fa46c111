#include "luxtrace/estimate/estimate_scene.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

EstimateScene estimate_scene(const Scene& scene) {
    EstimateScene s;
    s.triangle_area_m2 = scene.triangle_area_m2;
    s.bands = scene.bands.size();
    s.detectors = scene.detectors;
    s.observers = scene.observers;
    for (const Light& l : scene.lights.lights()) {
        s.light_group.push_back(l.group);
        // Electric light gives none: leaving it out leaves the sum as it is.
        if (l.unobstructed_horizontal_lx != 0.0) s.daylight.push_back({l.group, l.unobstructed_horizontal_lx});
    }
    s.group_flux_lm = light_group_flux_lm(scene);
    s.maintenance_factor = scene.lights.maintenance_factor();
    s.maintenance_factor_uniform = scene.lights.maintenance_factor_uniform();
    return s;
}

std::vector<double> light_group_flux_lm(const Scene& scene) {
    std::vector<double> flux(scene.light_groups.size(), 0.0);
    for (const Light& l : scene.lights.lights()) flux[l.group] += l.flux_lm;
    return flux;
}

double daylight_reference_lx(const EstimateScene& scene, std::span<const double> weights) {
    double e = 0.0;
    for (const DaylightSource& d : scene.daylight)
        e += (weights.empty() ? 1.0 : weights[d.group]) * d.unobstructed_horizontal_lx;
    return e;
}

}  // namespace luxtrace
