// The result's root attributes, /history and /checkpoint: how the run was made and how
// it went.
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

#include <cmath>

namespace luxtrace::result_parts {

using namespace hdf5;

void write_run_info(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                    const RunInfo& info, bool checkpoint) {
    attr(file, "format", checkpoint ? "luxtrace-checkpoint" : "luxtrace-result");
    attr(file, "format_version", kResultFormatVersion);
    attr(file, "luxtrace_version", info.luxtrace_version);
    attr(file, "scene_file", info.scene_file);
    if (scene.radiance_run) {  // a bare Radiance model run: how to load its scene again
        std::vector<std::string> models;
        for (const auto& m : scene.radiance_run->models) models.push_back(m.string());
        attr_strings(file, "radiance_models", models, false);
        if (scene.radiance_run->sensors) attr(file, "radiance_sensors", scene.radiance_run->sensors->string());
        if (scene.radiance_run->sensor_radius_m)
            attr(file, "radiance_sensor_radius_m", *scene.radiance_run->sensor_radius_m);
        attr(file, "radiance_scale", scene.radiance_run->scale);
    }
    attr(file, "scene_name", scene.name);
    attr(file, "seed", info.seed);
    attr(file, "ranks", static_cast<std::uint64_t>(info.ranks));
    attr(file, "threads_per_rank", static_cast<std::uint64_t>(info.threads_per_rank));
    attr(file, "photons", info.photons);
    attr(file, "flux_per_photon_lm", info.flux_per_photon_lm);
    attr(file, "total_flux_lm", scene.lights.total_flux_lm());
    // Values are initial; maintained ones are these times the maintenance factor
    // (flux-weighted over the lights; exact when all lights share one).
    attr(file, "maintenance_factor", scene.lights.maintenance_factor());
    attr(file, "maintenance_factor_uniform", std::uint64_t{scene.lights.maintenance_factor_uniform() ? 1u : 0u});
    attr(file, "elapsed_s", info.elapsed_s);
    attr(file, "load_s", info.load_s);
    attr(file, "bvh_build_s", info.bvh_build_s);
    attr(file, "stop_reason", info.stop_reason);
    attr_strings(file, "bands", scene.bands, false);
    attr(file, "sampler", info.sampler);
    attr(file, "replicates", static_cast<std::uint64_t>(layout.replicates()));  // 0: random
    attr_strings(file, "light_groups", scene.light_groups, false);
    attr(file, "group_maps", std::uint64_t{layout.map_groups() == layout.groups() ? 1u : 0u});
    if (layout.replicates() > 0) {
        std::vector<std::uint64_t> per(layout.replicates());
        for (std::size_t r = 0; r < per.size(); ++r) per[r] = tallies[layout.replicate_photons(r)];
        attr(file, "replicate_photons", per);
    }
    attr(file, "photon_layout", info.photon_layout);
    attr(file, "reductions", info.reductions);
    attr(file, "reduction_stall_s", info.reduction_stall_s);
    attr(file, "reduction_wait_s", info.reduction_wait_s);
    attr(file, "reduction_message_words", info.reduction_message_words);
    attr(file, "reduction_message_bytes", info.reduction_message_bytes);
    attr(file, "reduction_work_s", info.reduction_work_s);
    attr(file, "gather_s", info.gather_s);
    attr(file, "tracing_busy", info.tracing_busy);
    attr(file, "tally_words", static_cast<std::uint64_t>(layout.size()));
}

void write_history(hid_t file, const std::vector<HistoryRow>& history, const RunInfo& info) {
    const Id h = create_group(file, "history", "group /history");
    // Per-target columns: [rows, targets].
    const std::size_t nt = info.target_labels.size();
    std::vector<double> tv, tf, tp;
    for (const HistoryRow& r : history)
        for (std::size_t i = 0; i < nt; ++i) {
            tv.push_back(i < r.target_value.size() ? r.target_value[i] : std::nan(""));
            tf.push_back(i < r.target_forecast_s.size() ? r.target_forecast_s[i] : std::nan(""));
            tp.push_back(i < r.target_forecast_photons.size() ? r.target_forecast_photons[i] : std::nan(""));
        }
    if (nt > 0) {
        dataset(h, "target_value", {history.size(), nt}, tv.data());
        dataset(h, "target_forecast_s", {history.size(), nt}, tf.data());
        dataset(h, "target_forecast_photons", {history.size(), nt}, tp.data());
        attr_strings(h, "target_labels", info.target_labels, false);
        attr(h, "target_goals", info.target_goals);
    }
    std::vector<double> t, s, f;
    std::vector<std::uint64_t> p;
    for (const HistoryRow& r : history) {
        t.push_back(r.time_s);
        p.push_back(r.photons);
        s.push_back(r.sigma_rel_global);
        f.push_back(r.forecast_s);
    }
    const std::vector<hsize_t> dims{history.size()};
    dataset(h, "time_s", dims, t.data());
    dataset(h, "photons", dims, p.data());
    dataset(h, "sigma_rel_global", dims, s.data());
    dataset(h, "forecast_s", dims, f.data());
}

void write_checkpoint(hid_t file, const TallyLayout& layout, const CheckpointData& checkpoint) {
    const Id ck = create_group(file, "checkpoint", "group /checkpoint");
    dataset(ck, "tallies", {checkpoint.tallies.size()}, checkpoint.tallies.data());
    dataset(ck, "done_ranges", {checkpoint.done.size() / 2, 2}, checkpoint.done.data());
    attr(ck, "budget", checkpoint.budget);
    attr(ck, "layout_size", static_cast<std::uint64_t>(layout.size()));
    attr(ck, "triangles", static_cast<std::uint64_t>(layout.triangles()));
    attr(ck, "bands", static_cast<std::uint64_t>(layout.bands()));
}

}  // namespace luxtrace::result_parts
