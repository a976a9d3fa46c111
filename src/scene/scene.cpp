#include "luxtrace/scene/scene.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/tracer/gather_patches.hpp"

#include <algorithm>

namespace luxtrace {

double Scene::total_area_m2() const {
    double s = 0.0;
    for (double a : triangle_area_m2) s += a;
    return s;
}

double Scene::ray_epsilon_m() const {
    // Embree works relative to the scene's centre (EmbreeScene), so the scene's size,
    // not its distance from the origin, sets the precision.
    return 2e-6 * std::max(glm::length(bounds_max - bounds_min), 1e-3);
}

namespace {
std::vector<int> cells_of(const Scene& scene) {
    std::vector<int> cells;
    for (const Detector& d : scene.detectors) cells.push_back(d.cells());
    return cells;
}

TallyDims dims_of(const Scene& scene) {
    TallyDims d;
    d.bands = scene.bands.size();
    d.groups = scene.light_groups.size();
    d.map_groups = scene.run.group_maps ? d.groups : 1;
    d.replicates = scene.run.sampler == "sobol" ? scene.run.replicates : 0;
    d.direct_scores = scene.annual.has_value();
    if (scene.annual && scene.annual->options.shadow_rays())
        for (const Detector& det : scene.detectors) d.direct_apart.push_back(annual_grid(det) ? 1 : 0);
    if (scene.annual && scene.annual->options.gathers()) {
        d.gathered = d.direct_apart;
        d.gather_sites = 2 * GatherPatches(scene, scene.annual->options.gather_patch_m).count();
    }
    return d;
}
}  // namespace

TallyLayout tally_layout(const Scene& scene) { return {scene.triangle_count(), dims_of(scene), cells_of(scene)}; }

}  // namespace luxtrace
