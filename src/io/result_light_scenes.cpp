// The result's light groups (/light_groups/NAME: each group's own counts, from which any
// combination is recombined after the run) and light scenes (/light_scenes/NAME: each
// [[light_scene]]'s estimates). Issue 22; docs/REFERENCE.md §4.
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {

void write_group_detector(hid_t parent, const Detector& d, std::size_t di, std::size_t B, const TallyLayout& L,
                          std::span<const std::uint64_t> data, std::size_t group) {
    const Id g = create_group(parent, d.name, "group detectors/" + d.name);
    write_detector_counts(g, d, di, B, L, data, group, group + 1);
    attr(g, "photons_received", data[L.detector_received(di, group)]);
    attr(g, "total_count", data[L.detector_total_n(di, group)]);
    attr(g, "total_sumsq", data[L.detector_total_q(di, group)]);
}

void write_scene_global(hid_t parent, const Scene& scene, const ResultEstimates& est) {
    const Id glob = create_group(parent, "global", "group light_scenes/NAME/global");
    write_surface_estimates(glob, scene, est.surface, est.global);
}

void write_scene_detectors(hid_t parent, const Scene& scene, const ResultEstimates& est) {
    const Id dets = create_group(parent, "detectors", "group light_scenes/NAME/detectors");
    const std::size_t B = scene.bands.size();
    for (std::size_t di = 0; di < scene.detectors.size(); ++di) {
        const Detector& d = scene.detectors[di];
        if (d.observer >= 0) continue;
        const DetectorEstimate& e = est.detectors[di];
        const Id g = create_group(dets, d.name, "group light_scenes/NAME/detectors/" + d.name);
        const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
        dataset(g, "value", dims, e.value.data());
        dataset(g, "sigma_rel", dims, e.sigma_rel.data());
        attr(g, "units", d.units());
        write_detector_summary(g, e);
        write_daylight_map(g, d, est.daylight[di]);
        write_task_areas(g, d, e.metrics, est.maintained_metrics[di], est.daylight[di]);
    }
}

void write_scene_observers(hid_t parent, const Scene& scene, const ResultEstimates& est) {
    if (scene.observers.empty()) return;
    const Id obs = create_group(parent, "observers", "group light_scenes/NAME/observers");
    for (std::size_t oi = 0; oi < scene.observers.size(); ++oi) {
        const Id g = create_group(obs, scene.observers[oi].name, "group light_scenes/NAME/observers/OBS");
        write_ugr(g, est.observers[oi]);
    }
}

}  // namespace

void write_light_groups(hid_t file, const Scene& scene, const TallyLayout& L, std::span<const std::uint64_t> data) {
    if (L.groups() < 2) return;
    const Id groups = create_group(file, "light_groups", "group /light_groups");
    const std::size_t B = scene.bands.size();
    std::vector<std::uint64_t> lights(L.groups(), 0);
    for (const Light& l : scene.lights.lights()) ++lights[l.group];
    const std::vector<double> flux = light_group_flux_lm(scene);
    for (std::size_t lg = 0; lg < L.groups(); ++lg) {
        const std::string& name = scene.light_groups[lg];
        const Id g = create_group(groups, name, "group /light_groups/" + name);
        attr(g, "index", static_cast<std::uint64_t>(lg));
        attr(g, "flux_lm", flux[lg]);
        attr(g, "lights", lights[lg]);
        if (L.map_groups() == L.groups()) write_surface_counts(g, scene, L, data, lg, lg + 1);
        const Id dets = create_group(g, "detectors", "group /light_groups/" + name + "/detectors");
        for (std::size_t di = 0; di < scene.detectors.size(); ++di)
            write_group_detector(dets, scene.detectors[di], di, B, L, data, lg);
    }
}

void write_light_scenes(hid_t file, const Scene& scene, const ResultEstimates& est) {
    if (est.light_scenes.empty()) return;
    const Id scenes = create_group(file, "light_scenes", "group /light_scenes");
    for (const LightSceneEstimates& ls : est.light_scenes) {
        const Id g = create_group(scenes, ls.name, "group /light_scenes/" + ls.name);
        attr(g, "weights", ls.weights);
        attr(g, "flux_lm", ls.flux_lm);
        attr(g, "surface_map", std::uint64_t{ls.surface_available ? 1u : 0u});
        if (ls.surface_available) write_scene_global(g, scene, ls.estimates);
        write_scene_detectors(g, scene, ls.estimates);
        write_scene_observers(g, scene, ls.estimates);
    }
}

}  // namespace luxtrace::result_parts
