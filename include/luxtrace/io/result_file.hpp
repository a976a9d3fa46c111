#pragma once
// The result file of SPEC §4 (docs/REFERENCE.md): writing it, and reading a checkpoint's
// state back. The writer's parts are in src/io/result_parts.hpp; readers use ResultReader
// (result_reader.hpp) by HDF5 path or the typed ResultFile (result_data.hpp).
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;

// Version 2 (luxtrace 0.3, issue 13): surface datasets per triangle side, [T, 2, B], with
// /global/sumsq and /global/sigma_lx; version 1 had [T, B] for both sides together.
inline constexpr std::uint64_t kResultFormatVersion = 2;

// One row per reduction (SPEC §4 /history).
struct HistoryRow {
    double time_s = 0.0;
    std::uint64_t photons = 0;
    double sigma_rel_global = 0.0;
    double forecast_s = 0.0;                      // of the first target; NaN if none
    std::vector<double> target_value;             // per target: its error or count
    std::vector<double> target_forecast_s;        // per target: forecast wall time to meet it
    std::vector<double> target_forecast_photons;  // per target: forecast photons to meet it
};

struct RunInfo {
    std::string luxtrace_version;
    std::string scene_file;
    // A bare Radiance model run (root attributes radiance_*): its files, sensors, radius, scale.
    std::vector<std::string> radiance_models;
    std::string radiance_sensors;
    double radiance_sensor_radius_m = 0.0;  // 0: the default
    double radiance_scale = 1.0;
    std::uint64_t seed = 0;
    int ranks = 1;
    int threads_per_rank = 1;
    std::uint64_t photons = 0;
    double flux_per_photon_lm = 0.0;
    double elapsed_s = 0.0;
    // Before tracing: loading the scene and building its BVH (the slowest rank's, s).
    double load_s = 0.0, bvh_build_s = 0.0;
    std::string stop_reason;
    std::string sampler;
    std::uint64_t photon_layout = 0;  // which random numbers a photon draws (tracer.hpp)
    std::uint64_t reductions = 0;
    double reduction_stall_s = 0.0;             // tracing time lost to snapshots (max over ranks)
    double reduction_wait_s = 0.0;              // main thread's wait for reductions (tracing goes on)
    double reduction_work_s = 0.0;              // main thread's packing, summing and estimating (max over ranks)
    double gather_s = 0.0;                      // the map gathered on rank 0 for the result
    double tracing_busy = 0.0;                  // tracing threads' CPU time / tracing time, least busy rank
    std::uint64_t reduction_message_words = 0;  // the longest message a rank sent in a reduction (0: one rank)
    std::uint64_t reduction_message_bytes = 0;  // their bytes (the map's words are 32-bit while they fit)
    std::vector<std::string> target_labels;
    std::vector<double> target_goals;
};

// What a checkpoint adds to a result: the rank-independent state needed to continue.
struct CheckpointData {
    std::vector<std::uint64_t> tallies;  // the whole flat tally array (TallyLayout order)
    std::vector<std::uint64_t> done;     // traced photon ranges, flattened [begin, end) pairs
    std::uint64_t budget = 0;            // photon budget of the run
};

struct CheckpointState {
    std::vector<std::uint64_t> tallies;
    std::vector<std::uint64_t> done;
    std::uint64_t budget = 0;
    std::uint64_t seed = 0;
    std::string sampler;
    std::uint64_t photon_layout = 1;        // files without the attribute were made with layout 1
    std::uint64_t replicates = 0;           // sobol's R; 0 for random (and files before it)
    std::vector<std::string> light_groups;  // empty in files before light groups (one group)
    bool group_maps = true;
    // An annual checkpoint's [annual] direct ("photons" in files before it); empty without
    // [annual].
    std::string annual_direct;
    // ... and its light after a diffuse reflection: "photons" or, with the gather's options
    // (whose table its tallies were counted with), "gather rays R patch P m".
    std::string annual_indirect;  // annual_indirect_tag's form
    std::uint64_t format_version = 1;
    double elapsed_s = 0.0;
    std::uint64_t layout_size = 0, triangles = 0, bands = 0;
    std::vector<HistoryRow> history;
};

// The sealed bytes of a result file (with `checkpoint`, a checkpoint): `tallies`
// rearranged into the file's arrays, and `estimates` (estimate_result on the same tallies)
// as they are. `path` only names the file in messages.
std::vector<char> result_image(const std::filesystem::path& path, const Scene& scene, const TallyLayout& layout,
                               std::span<const std::uint64_t> tallies, const RunInfo& info,
                               const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
                               const CheckpointData* checkpoint = nullptr);

// The sealed bytes of a tally checkpoint: the root attributes, /history and /checkpoint
// alone, nothing computed from the tallies. What a run keeps when its result or full
// checkpoint could not be made (docs/RELIABILITY.md); `--restart` continues from it.
std::vector<char> tally_checkpoint_image(const std::filesystem::path& path, const Scene& scene,
                                         const TallyLayout& layout, const RunInfo& info,
                                         const std::vector<HistoryRow>& history, const CheckpointData& checkpoint);

// Reads a checkpoint (result_image with CheckpointData, or tally_checkpoint_image); throws
// InputError.
// How an annual run gets its light after a diffuse reflection, as a checkpoint records it:
// "photons", or "gather rays R patch P m".
std::string annual_indirect_tag(const std::string& indirect, int gather_rays, double gather_patch_m);
CheckpointState read_checkpoint(const std::filesystem::path& path);

}  // namespace luxtrace
