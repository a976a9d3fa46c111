#pragma once
// What a run is asked (RunOptions: the command line's overrides and the hooks tests and
// benches use) and what it answers (RunSummary), shared by run_simulation (simulation.hpp)
// and the phases of RunLoop (run_loop.hpp).
#include "luxtrace/io/result_file.hpp"

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {

struct Scene;
class Communicator;
class EmbreeScene;

struct RunOptions {
    int threads = 0;  // per rank; 0 = every core this process may run on
    bool quiet = false;
    std::string restart;  // checkpoint to continue from
    // Set (to the signal number) by the CLI's SIGTERM/SIGUSR1 handler: checkpoint and stop.
    const std::atomic<int>* signal = nullptr;
    // A BVH of this scene built already (benchmarks trace with the one they measure on);
    // null: the run builds its own.
    const EmbreeScene* embree = nullptr;
    // Wall time the caller spent loading the scene (s), for the result's report.
    double load_s = 0.0;
    // A reduction sends the map's counts as 32-bit words while every rank's are below this
    // bound; 0: 2^32 / ranks, so that their sum fits too. Tests lower it to take the
    // 64-bit way.
    std::uint64_t narrow_word_bound = 0;
    // The scene as the command line named it (a TOML file, or Radiance files with their
    // options), for the command a message after a failed write gives; empty: the scene file.
    std::string scene_args;
    // Tests: steps of writing a file after tracing that fail on purpose, "FILE:STEP" items
    // separated by commas (run/write_steps.hpp); empty: none.
    std::string inject_fault;
    // Who shares the final annual post-processing (RunLoop::share_annual_estimates): one
    // part per node, its first rank on all its cores (false, the default; one node: rank 0
    // alone), or (tests, hidden --annual-parts ranks) one part per rank.
    bool annual_parts_per_rank = false;
};

struct RunSummary {
    // 0 finished, 3 stopped early after writing a checkpoint; 2 or 1 when tracing failed
    // on some rank (an InputError, or an internal fault): then nothing was written. After
    // tracing, 4 when a file could not be written and 1 when a write step failed
    // otherwise: `error` then says which, and where the run's tallies are kept.
    int exit_code = 0;
    bool failed = false;
    bool write_failed = false;  // the failure came after tracing, writing (rank 0)
    std::string error;          // this rank's failure, empty if this rank traced fine
    std::string stop_reason;
    std::string checkpoint;  // written checkpoint, if any
    std::string output;
    std::vector<std::string> sensor_tables;  // the points detectors' tables beside the result (io/sensor_table.hpp)
    std::uint64_t photons = 0;
    double elapsed_s = 0.0;
    double tracing_s = 0.0;  // this run's tracing threads, from start until out of work or stopped (max over ranks)
    // The tracing threads' CPU time over their tracing time (WorkerPool::busy_fraction), the least busy rank's.
    double tracing_busy = 0.0;
    double result_write_s = 0.0;  // rank 0: the result's estimates and file (with its sensor tables)
    std::vector<std::pair<std::string, double>> result_steps_s;  // rank 0: its steps' wall seconds (write_steps.hpp)
    std::uint64_t rays = 0;  // intersections in all: surface arrivals + escaped photons (root)
    GlobalEstimate global;
    std::vector<DetectorEstimate> detectors;
};

// Cores this process may run on (its affinity mask), at least 1.
int available_cores();

}  // namespace luxtrace
