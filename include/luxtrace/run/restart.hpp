#pragma once
// Continuing a checkpoint (`luxtrace run --restart`): what it holds, checked against the
// scene and the run settings about to continue it. Its counts enter the new run once (on
// rank 0), its traced ranges are skipped, its history goes on.
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/run/work_plan.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

struct RunConfig;

struct RestartState {
    std::vector<std::uint64_t> tallies;  // the flat tally array (TallyLayout order)
    std::vector<PhotonRange> done;       // photons traced already
    std::vector<HistoryRow> history;     // times since the first part's start
    double elapsed_s = 0.0;              // wall time of the earlier parts
};

// Reads the checkpoint `path` and checks that `run` (seed, sampler, replicates, budget)
// and `layout` can continue it; throws InputError naming what differs.
// `light_groups`: the scene's (Scene::light_groups), which the checkpoint's must match;
// `annual_indirect`: the scene's annual_indirect_tag (io/result_file.hpp), empty without
// [annual].
RestartState restore_checkpoint(const std::string& path, const RunConfig& run, const TallyLayout& layout,
                                const std::vector<std::string>& light_groups, const std::string& annual_indirect = {});

}  // namespace luxtrace
