#include "luxtrace/run/restart.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/scene/run_config.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <algorithm>

namespace luxtrace {

namespace {
// A few groups by name; an annual run's thousands as their count, the first and the last.
std::string group_list(const std::vector<std::string>& groups) {
    if (groups.size() <= 8) return comma_list(groups);
    return std::to_string(groups.size()) + " (" + groups[0] + ", " + groups[1] + ", ..., " + groups.back() + ")";
}
}  // namespace

RestartState restore_checkpoint(const std::string& path, const RunConfig& run, const TallyLayout& layout,
                                const std::vector<std::string>& light_groups, const std::string& annual_indirect) {
    CheckpointState ck = read_checkpoint(path);
    if (ck.format_version != kResultFormatVersion)
        throw InputError(path + ": the checkpoint has result format " + std::to_string(ck.format_version) +
                         ", this luxtrace writes format " + std::to_string(kResultFormatVersion) +
                         " (both sides of every triangle counted apart); continue it with the luxtrace that wrote "
                         "it, or start anew");
    if (ck.sampler == run.sampler && ck.replicates != layout.replicates())
        throw InputError(path + ": the checkpoint was made with " + std::to_string(ck.replicates) +
                         " replicates; restart with the same (drop --replicates)");
    // Annual grids count the photons' direct arrivals or leave them to shadow rays: the
    // counts of one way do not continue the other's.
    if (!ck.annual_direct.empty() && (ck.annual_direct == "shadow_rays") != layout.any_direct_apart())
        throw InputError(path + ": the checkpoint was made with [annual] direct = \"" + ck.annual_direct +
                         "\"; restart with the same");
    // A gathered grid's counts hold the weights of one gather table.
    if (!annual_indirect.empty() && !ck.annual_indirect.empty() && ck.annual_indirect != annual_indirect)
        throw InputError(path + ": the checkpoint was made with [annual] indirect = " + ck.annual_indirect +
                         ", this scene asks " + annual_indirect + "; restart with the same");
    // Light groups keep their counts apart: a checkpoint continues only with the same ones.
    const std::vector<std::string> ck_groups = ck.light_groups.empty() ? std::vector<std::string>{"default"}
                                                                       : ck.light_groups;
    const bool ck_shared = ck_groups.size() > 1 && !ck.group_maps;
    const bool shared = layout.groups() > 1 && layout.map_groups() == 1;
    if (ck_groups.size() != layout.groups() || (!ck.light_groups.empty() && ck.light_groups != light_groups) ||
        ck_shared != shared)
        throw InputError(path + ": the checkpoint keeps the light groups " + group_list(ck_groups) +
                         (ck_shared ? " (one surface map for all)" : "") + ", this scene has " +
                         group_list(light_groups) + (shared ? " (one surface map for all)" : "") +
                         ": restart with the light groups and [run] group_maps the checkpoint was made with" +
                         (ck.annual_direct.empty() ? "" : " (an annual run's: its sky, [annual] sun_group_days)"));
    // A sobol checkpoint of luxtrace 0.3: the same scene, but no replicate maps per side.
    if (layout.replicates() > 0 && ck.triangles == layout.triangles() && ck.bands == layout.bands() &&
        ck.layout_size + layout.sides() * layout.map_columns() * layout.replicates() == layout.size())
        throw InputError(path + ": the checkpoint was made by a luxtrace whose sobol runs kept no replicate maps "
                                "per triangle side (before 0.4); continue it with that version, or start anew");
    if (ck.layout_size != layout.size() || ck.triangles != layout.triangles() || ck.bands != layout.bands())
        throw InputError(path + ": the checkpoint was made for another scene (" + std::to_string(ck.triangles) +
                         " triangles, " + std::to_string(ck.bands) + " bands; this scene has " +
                         std::to_string(layout.triangles()) + " and " + std::to_string(layout.bands()) + ")");
    if (ck.photon_layout != kPhotonLayout)
        throw InputError(path +
                         ": the checkpoint was made by a luxtrace whose photons draw their random "
                         "numbers differently (photon layout " +
                         std::to_string(ck.photon_layout) + ", this one " + std::to_string(kPhotonLayout) +
                         "); continue it with that version or start anew");
    if (ck.seed != run.seed || ck.sampler != run.sampler)
        throw InputError(path + ": the checkpoint used seed " + std::to_string(ck.seed) + " and sampler " + ck.sampler +
                         "; restart with the same (drop --seed/--sampler)");
    RestartState s;
    for (std::size_t i = 0; i + 1 < ck.done.size(); i += 2) s.done.push_back({ck.done[i], ck.done[i + 1]});
    // A restart may set a new budget (--photons), but not one below photons it holds.
    std::uint64_t highest = 0;
    for (const PhotonRange& r : s.done) highest = std::max(highest, r.end);
    if (run.photons < highest)
        throw InputError("--photons: the checkpoint " + path + " already holds photons up to index " +
                         std::to_string(highest - 1) + "; the budget must be at least " + std::to_string(highest));
    s.tallies = std::move(ck.tallies);
    s.history = std::move(ck.history);
    s.elapsed_s = ck.elapsed_s;
    return s;
}

}  // namespace luxtrace
