#pragma once
// One `luxtrace run`: trace this rank's share of the photon budget with its threads,
// reduce the tallies to rank 0, estimate the errors and write the result file. The phases
// are RunLoop's (run_loop.hpp).
#include "luxtrace/run/run_options.hpp"

#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
class Communicator;
class EmbreeScene;

// Runs the simulation described by `scene` (its `run` table already holds the
// command-line overrides). Rank 0 prints progress and the summary to `out`.
RunSummary run_simulation(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out);

}  // namespace luxtrace
