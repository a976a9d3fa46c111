#include "luxtrace/tracer/probe.hpp"

#include "luxtrace/sampler/sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <cstdio>

namespace luxtrace {

std::vector<std::string> probe_scene(const Scene& scene, const EmbreeScene& embree, int rays) {
    std::vector<std::string> warnings;
    PhiloxSampler sampler(0x9e3779b9u);
    const double eps = scene.ray_epsilon_m();
    for (std::size_t li = 0; li < scene.lights.lights().size(); ++li) {
        const Light& l = scene.lights.lights()[li];
        int black = 0, escaped = 0;
        for (int k = 0; k < rays; ++k) {
            sampler.start_photon(static_cast<std::uint64_t>(k));
            const double a = sampler.next(), b = sampler.next(), c = sampler.next(), d = sampler.next();
            EmittedRay r = l.emit(a, b, c, d);
            if (r.emitter_triangle >= 0) r.origin += eps * scene.triangle_normal[static_cast<std::size_t>(r.emitter_triangle)];
            const Hit h = embree.intersect(r.origin, r.direction);
            if (!h.found) { ++escaped; continue; }
            if (scene.materials[scene.triangle_material[h.triangle]].type == MaterialType::black) ++black;
        }
        char buf[256];
        if (black == rays) {
            std::snprintf(buf, sizeof buf, "%s: every probe ray hits a black surface first: its photons are all absorbed at the first hit (is it inside a closed black box?)", l.label.c_str());
            warnings.emplace_back(buf);
        } else if (escaped == rays && l.type != LightType::directional) {
            std::snprintf(buf, sizeof buf, "%s: no probe ray hits any surface: its light leaves the scene", l.label.c_str());
            warnings.emplace_back(buf);
        } else if (escaped > rays / 2 && l.type != LightType::directional) {
            std::snprintf(buf, sizeof buf, "%s: %.0f%% of probe rays leave the scene without hitting a surface", l.label.c_str(), 100.0 * escaped / rays);
            warnings.emplace_back(buf);
        }
    }
    for (const Detector& d : scene.detectors) {
        const Vec3 lo = scene.bounds_min - Vec3(1e-3), hi = scene.bounds_max + Vec3(1e-3);
        if (glm::any(glm::lessThan(d.center, lo)) || glm::any(glm::greaterThan(d.center, hi)))
            warnings.push_back("detector '" + d.name + "': its centre lies outside the scene's bounding box");
    }
    std::vector<bool> used(scene.materials.size(), false);
    for (std::uint32_t m : scene.triangle_material) used[m] = true;
    for (std::size_t m = 0; m < used.size(); ++m)
        if (!used[m]) warnings.push_back("material '" + scene.materials[m].name + "' is not used by any triangle");
    return warnings;
}

}  // namespace luxtrace
