// The result's light groups (/light_groups/NAME: each group's own counts, from which any
// combination is recombined after the run) and light scenes (/light_scenes/NAME: each
// [[light_scene]]'s estimates). Issue 22; docs/REFERENCE.md §4.
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {

void write_group_surface(hid_t g, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data,
                         std::size_t group) {
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    constexpr std::size_t kS = TallyLayout::kSides;
    const std::vector<hsize_t> dims{T, kS, B};
    auto slot = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        return data[L.surface(t, side, b, s, group)];
    };
    const std::pair<const char*, TallyLayout::SurfaceSlot> slots[] = {{"count_odd", TallyLayout::kCountOdd},
                                                                      {"count_even", TallyLayout::kCountEven},
                                                                      {"direct_odd", TallyLayout::kDirectOdd},
                                                                      {"direct_even", TallyLayout::kDirectEven}};
    std::vector<std::uint64_t> buf(T * kS * B);
    for (const auto& [name, s] : slots) {
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b) buf[(t * kS + side) * B + b] = slot(t, side, b, s);
        dataset(g, name, dims, buf.data());
    }
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b)
                buf[(t * kS + side) * B + b] = slot(t, side, b, TallyLayout::kCountOdd) +
                                               slot(t, side, b, TallyLayout::kCountEven) +
                                               slot(t, side, b, TallyLayout::kRepeats);
    dataset(g, "sumsq", dims, buf.data());
    if (const std::size_t R = L.replicates(); R > 0) {
        std::vector<std::uint64_t> rep(T * kS * B * R);
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b)
                    for (std::size_t r = 0; r < R; ++r)
                        rep[((t * kS + side) * B + b) * R + r] =
                            data[L.map_replicate(L.side_index(t, side), L.map_column(b, group), r)];
        dataset(g, "replicate_count", {T, kS, B, R}, rep.data());
    }
}

void write_group_detector(hid_t parent, const Detector& d, std::size_t di, std::size_t B, const TallyLayout& L,
                          const std::vector<std::uint64_t>& data, std::size_t group) {
    const Id g = create_group(parent, d.name, "group detectors/" + d.name);
    const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
    std::vector<std::uint64_t> n(d.cells() * B), q(d.cells() * B);
    for (int c = 0; c < d.cells(); ++c)
        for (std::size_t b = 0; b < B; ++b) {
            n[c * B + b] = data[L.detector_n(di, c, b, group)];
            q[c * B + b] = data[L.detector_q(di, c, b, group)];
        }
    dataset(g, "count", dims, n.data());
    dataset(g, "sumsq", dims, q.data());
    attr(g, "photons_received", data[L.detector_received(di, group)]);
    attr(g, "total_count", data[L.detector_total_n(di, group)]);
    attr(g, "total_sumsq", data[L.detector_total_q(di, group)]);
    if (const std::size_t R = L.replicates(); R > 0) {
        std::vector<std::uint64_t> rn(R * d.cells() * B), rt(R);
        for (std::size_t r = 0; r < R; ++r) {
            rt[r] = data[L.detector_replicate_total_n(di, r, group)];
            for (int c = 0; c < d.cells(); ++c)
                for (std::size_t b = 0; b < B; ++b)
                    rn[(r * d.cells() + c) * B + b] = data[L.detector_replicate_n(di, r, c, b, group)];
        }
        dataset(g, "replicate_count", {R, static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B}, rn.data());
        attr(g, "replicate_total", rt);
    }
}

void write_scene_global(hid_t parent, const Scene& scene, const ResultEstimates& est) {
    const Id glob = create_group(parent, "global", "group light_scenes/NAME/global");
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    constexpr std::size_t kS = TallyLayout::kSides;
    const SurfaceMaps& m = est.surface;
    dataset(glob, "illuminance", {T, kS, B}, m.illuminance_lx.data());
    dataset(glob, "illuminance_direct", {T, kS, B}, m.illuminance_direct_lx.data());
    dataset(glob, "odd_even_difference_lx", {T, kS}, m.odd_even_difference_lx.data());
    dataset(glob, "sigma_lx", {T, kS}, m.sigma_lx.data());
    if (!m.replicate_sigma_lx.empty()) dataset(glob, "replicate_sigma_lx", {T, kS}, m.replicate_sigma_lx.data());
    const GlobalEstimate& g = est.global;
    attr(glob, "sigma_lx", g.sigma_lx);
    attr(glob, "sigma_rel_arithmetic", g.sigma_rel_arithmetic);
    attr(glob, "sigma_rel_quadratic", g.sigma_rel_quadratic);
    attr(glob, "moment_sigma_lx", g.moment_sigma_lx);
    attr(glob, "moment_sigma_rel_arithmetic", g.moment_sigma_rel_arithmetic);
    attr(glob, "moment_sigma_rel_quadratic", g.moment_sigma_rel_quadratic);
    if (!m.replicate_sigma_lx.empty()) {
        attr(glob, "replicate_sigma_lx", g.replicate_sigma_lx);
        attr(glob, "replicate_sigma_rel_arithmetic", g.replicate_sigma_rel_arithmetic);
        attr(glob, "replicate_sigma_rel_quadratic", g.replicate_sigma_rel_quadratic);
    }
    attr(glob, "error_estimator", g.estimator_name());
    attr(glob, "lit_area_m2", g.lit_area_m2);
    attr(glob, "lit_sides", g.lit_sides);
    attr(glob, "mean_arithmetic_lx", g.mean_arithmetic_lx);
    attr(glob, "mean_quadratic_lx", g.mean_quadratic_lx);
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
        attr(g, "sigma_rel_arithmetic", e.sigma_rel_arithmetic);
        attr(g, "sigma_rel_quadratic", e.sigma_rel_quadratic);
        attr(g, "mean_arithmetic", e.mean_arithmetic);
        attr(g, "mean_quadratic", e.mean_quadratic);
        attr(g, "photons_received", e.photons_received);
        attr(g, "mean_value", e.mean_value);
        attr(g, "mean_sigma_rel", e.mean_sigma_rel);
        write_task_areas(g, d, e.metrics, est.maintained_metrics[di]);
    }
}

void write_scene_observers(hid_t parent, const Scene& scene, const ResultEstimates& est) {
    if (scene.observers.empty()) return;
    const Id obs = create_group(parent, "observers", "group light_scenes/NAME/observers");
    for (std::size_t oi = 0; oi < scene.observers.size(); ++oi) {
        const UgrEstimate& u = est.observers[oi].ugr;
        const Id g = create_group(obs, scene.observers[oi].name, "group light_scenes/NAME/observers/OBS");
        attr(g, "ugr", u.ugr);
        attr(g, "ugr_sigma", u.ugr_sigma);
        if (const std::optional<double>& m = est.observers[oi].ugr_maintained) attr(g, "ugr_maintained", *m);
        attr(g, "background_luminance_cd_m2", u.background_luminance_cd_m2);
        attr(g, "indirect_vertical_illuminance_lx", u.indirect_illuminance_lx);
        attr(g, "indirect_vertical_illuminance_sigma_rel", u.indirect_sigma_rel);
    }
}

}  // namespace

void write_light_groups(hid_t file, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data) {
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
        if (L.map_groups() == L.groups()) write_group_surface(g, scene, L, data, lg);
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
