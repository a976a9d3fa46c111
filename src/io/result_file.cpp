#include "luxtrace/io/result_file.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/file_seal.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace luxtrace {

namespace result_parts {

void write_all(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
               const RunInfo& info, const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
               const CheckpointData* checkpoint) {
    write_run_info(file, scene, layout, tallies, info, checkpoint != nullptr);
    write_mesh(file, scene);
    write_surface_map(file, scene, layout, tallies, estimates);
    write_detectors(file, scene, layout, tallies, estimates);
    write_observers(file, scene, layout, tallies, estimates);
    // An annual run's groups are its sky patches and suns: /annual holds them.
    if (!scene.annual) write_light_groups(file, scene, layout, tallies);
    write_light_scenes(file, scene, estimates);
    if (!scene.annual) write_daylight(file, scene);
    write_annual(file, scene, layout, tallies, estimates);
    write_history(file, history, info);
    if (checkpoint != nullptr) write_checkpoint(file, layout, *checkpoint);
}

void write_tally_checkpoint(hid_t file, const Scene& scene, const TallyLayout& layout, const RunInfo& info,
                            const std::vector<HistoryRow>& history, const CheckpointData& checkpoint) {
    write_run_info(file, scene, layout, checkpoint.tallies, info, true);
    write_history(file, history, info);
    write_checkpoint(file, layout, checkpoint);
}

}  // namespace result_parts

namespace {

// The first kSealBytes are kept for luxtrace's seal (file_seal.hpp).
std::vector<char> sealed_image(const std::filesystem::path& path, const std::function<void(hid_t)>& fill) {
    std::vector<char> image = hdf5::file_image(path, kSealBytes, fill);
    seal_image(image);
    return image;
}

}  // namespace

std::vector<char> result_image(const std::filesystem::path& path, const Scene& scene, const TallyLayout& layout,
                               std::span<const std::uint64_t> tallies, const RunInfo& info,
                               const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
                               const CheckpointData* checkpoint) {
    return sealed_image(path, [&](hid_t file) {
        result_parts::write_all(file, scene, layout, tallies, info, estimates, history, checkpoint);
    });
}

std::vector<char> tally_checkpoint_image(const std::filesystem::path& path, const Scene& scene,
                                         const TallyLayout& layout, const RunInfo& info,
                                         const std::vector<HistoryRow>& history, const CheckpointData& checkpoint) {
    return sealed_image(path, [&](hid_t file) {
        result_parts::write_tally_checkpoint(file, scene, layout, info, history, checkpoint);
    });
}

std::string annual_indirect_tag(const std::string& indirect, int gather_rays, double gather_patch_m) {
    if (indirect != "gather") return indirect;
    std::ostringstream o;
    o << "gather rays " << gather_rays << " patch " << gather_patch_m << " m";
    return o.str();
}

CheckpointState read_checkpoint(const std::filesystem::path& path) {
    const ResultReader r(path);
    const std::string where = path.string() + ": ";
    if (r.attr_str("/", "format") != "luxtrace-checkpoint" || !r.has("/checkpoint"))
        throw InputError(where + "not a luxtrace checkpoint (it is a result file; restart needs a checkpoint)");
    // Unsealed checkpoints come from luxtrace 0.1, whose photons drew other random numbers.
    if (!r.sealed())
        throw InputError(where +
                         "this checkpoint has no luxtrace seal: it was written by luxtrace 0.1 (photon layout 1); "
                         "continue it with that version or start anew");
    CheckpointState s;
    try {
        s.tallies = r.u64("/checkpoint/tallies");
        s.done = r.u64("/checkpoint/done_ranges");
        s.budget = r.attr_u64("/checkpoint", "budget");
        s.layout_size = r.attr_u64("/checkpoint", "layout_size");
        s.triangles = r.attr_u64("/checkpoint", "triangles");
        s.bands = r.attr_u64("/checkpoint", "bands");
        s.seed = r.attr_u64("/", "seed");
        s.sampler = r.attr_str("/", "sampler");
        if (r.has_attr("/", "photon_layout")) s.photon_layout = r.attr_u64("/", "photon_layout");
        if (r.has_attr("/", "replicates")) s.replicates = r.attr_u64("/", "replicates");
        if (r.has_attr("/", "light_groups")) s.light_groups = r.attr_strs("/", "light_groups");
        if (r.has_attr("/", "group_maps")) s.group_maps = r.attr_u64("/", "group_maps") != 0;
        if (r.has("/annual")) {
            s.annual_direct = r.has_attr("/annual", "direct") ? r.attr_str("/annual", "direct") : "photons";
            const std::string indirect = r.has_attr("/annual", "indirect") ? r.attr_str("/annual", "indirect")
                                                                           : "photons";
            s.annual_indirect = indirect == "gather"
                                    ? annual_indirect_tag(indirect,
                                                          static_cast<int>(r.attr_u64("/annual", "gather_rays")),
                                                          r.attr_f64("/annual", "gather_patch_m"))
                                    : indirect;
        }
        s.format_version = r.attr_u64("/", "format_version");
        s.elapsed_s = r.attr_f64("/", "elapsed_s");
        const auto t = r.f64("/history/time_s");
        const auto p = r.u64("/history/photons");
        const auto g = r.f64("/history/sigma_rel_global");
        const auto f = r.f64("/history/forecast_s");
        if (p.size() != t.size() || g.size() != t.size() || f.size() != t.size())
            throw InputError(where + "the /history columns differ in length");
        std::vector<std::size_t> shape;
        std::vector<double> tv, tf, tp;
        if (r.has("/history/target_value")) {
            tv = r.f64("/history/target_value", &shape);
            tf = r.f64("/history/target_forecast_s");
            if (r.has("/history/target_forecast_photons")) tp = r.f64("/history/target_forecast_photons");
            if (shape.size() != 2 || shape[0] != t.size() || tf.size() != tv.size() ||
                (!tp.empty() && tp.size() != tv.size()))
                throw InputError(where + "the /history target columns do not match its rows");
        }
        const std::size_t nt = shape.size() == 2 ? shape[1] : 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            HistoryRow row{t[i], p[i], g[i], f[i], {}, {}, {}};
            for (std::size_t j = 0; j < nt; ++j) {
                row.target_value.push_back(tv[i * nt + j]);
                row.target_forecast_s.push_back(tf[i * nt + j]);
                row.target_forecast_photons.push_back(tp.empty() ? std::nan("") : tp[i * nt + j]);
            }
            s.history.push_back(std::move(row));
        }
    } catch (const InputError& e) {
        throw InputError(std::string(e.what()) + " (damaged checkpoint)");
    }
    if (s.tallies.size() != s.layout_size || s.done.size() % 2 != 0)
        throw InputError(where + "damaged checkpoint: inconsistent sizes");
    for (std::size_t i = 0; i < s.done.size(); i += 2)
        if (s.done[i] > s.done[i + 1])
            throw InputError(where + "damaged checkpoint: photon range " + std::to_string(s.done[i]) + ".." +
                             std::to_string(s.done[i + 1]) + " runs backwards");
    return s;
}

}  // namespace luxtrace
