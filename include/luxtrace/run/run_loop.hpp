#pragma once
// One `luxtrace run` on one rank, as named phases (the shape of OpenMC's
// openmc_next_batch); run_simulation (simulation.hpp) calls them in this order:
//
//   restore    (constructor) a checkpoint's tallies, traced ranges and history; the work plan
//   trace      the rank's tracing threads start
//   snapshot   they park at chunk boundaries; the rank's ReductionMessage is encoded
//   reduce     rank 0 receives the sum of the messages
//   decide     rank 0: RunController's Decision, and a periodic checkpoint
//   broadcast  every rank gets rank 0's Decision; snapshot .. broadcast repeat until it stops
//   write      the final reduction, the result file and the final checkpoint (rank 0)
//
// The members are the state the phases share.
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/decision.hpp"
#include "luxtrace/run/restart.hpp"
#include "luxtrace/run/run_control.hpp"
#include "luxtrace/run/simulation.hpp"
#include "luxtrace/run/work_plan.hpp"
#include "luxtrace/run/worker_pool.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

class RunLoop {
public:
    // restore: reads the checkpoint opt.restart (if any) and plans the work; builds the BVH
    // unless opt.embree holds one. Throws InputError when the checkpoint does not fit.
    RunLoop(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out);
    RunLoop(const RunLoop&) = delete;
    RunLoop& operator=(const RunLoop&) = delete;

    // Where the run will write, checked on rank 0 before any photon is traced: an
    // InputError on every rank if it cannot.
    void check_writable();
    void trace();
    // Returns when the next reduction is due: its period passed, the rank's fence reached,
    // its work done, a tracing fault, or a signal.
    void wait_for_reduction();
    void snapshot();
    void reduce();
    // Rank 0's decision on the reduced message (other ranks: a default one, not used).
    Decision decide();
    // Rank 0's decision, on every rank.
    Decision broadcast(const Decision& decision);
    // Stops the threads; unless the decision says the last snapshot is the result, reduces
    // once more, exactly; writes the result (and the checkpoint the decision asks for).
    RunSummary write(const Decision& decision);

private:
    // The rank's message from the store and the work plan; only while no thread traces.
    void encode_snapshot(bool signalled, bool idle);
    PendingReduce start_reduce();
    void finish_reduce();
    // Rank 0: the result or a checkpoint from the reduced message; a failure to write the
    // file comes back as its message (empty: written).
    std::string attempt_write(const std::string& path, double elapsed_s, const std::string& reason, bool as_checkpoint);
    void write_file(const std::string& path, double elapsed_s, const std::string& reason, bool as_checkpoint);
    std::string latest_checkpoint_note() const;
    void explain_failed_writes(const std::string& result_err, const std::string& checkpoint_err);

    const Scene& scene_;
    const RunConfig& run_;
    const Communicator& comm_;
    const RunOptions& opt_;
    std::ostream& out_;
    const double t0_;  // this part's start
    const int ranks_;
    const int threads_;
    const TallyLayout layout_;
    TallyStore store_;

    // restore
    RestartState restored_;  // its tallies are in the store (rank 0) and dropped here
    const WorkPlan plan_;
    RankWork work_;
    std::optional<EmbreeScene> own_embree_;
    const EmbreeScene& embree_;
    std::optional<RunController> control_;  // rank 0
    const std::string checkpoint_path_;
    const bool show_;  // rank 0 prints progress lines
    const bool tty_;   // ... overwriting one line on a terminal
    RunInfo info_;
    RunSummary summary_;

    // trace: reductions at photon counts move each rank's fence by its share.
    const std::uint64_t fence_step_;
    std::uint64_t fence_ = 0;
    double trace0_ = 0.0;

    // snapshot and reduce: with one rank the sum is the snapshot itself, and the two
    // buffers swap (one copy of the tallies besides the store, not two: 80 MB on a million
    // triangles, and as many page faults at the first reduction). With several ranks the
    // message leaves out the words zero on every rank (message_packing.hpp): a closed room's
    // walls send their lit side only, an annual run the detector blocks some photon has
    // reached, and rank 0 restores the full message.
    std::vector<std::uint64_t> snapshot_, reduced_;
    std::vector<std::uint64_t> mask_, packed_, packed_reduced_;  // message_packing.hpp

    // decide: timing, and the overhead accounting (tracing time lost to pauses, and the
    // main thread's wait for reductions while the workers trace).
    double period_s_;
    double stall_s_ = 0.0, write_s_ = 0.0;
    double stall_total_s_ = 0.0, reduce_total_s_ = 0.0;
    std::uint64_t reductions_ = 0;

    // write: the latest checkpoint this run wrote (rank 0), for messages after a failed write.
    std::string latest_checkpoint_;
    std::uint64_t latest_checkpoint_photons_ = 0;

    // Last: its threads use the store, the work and the BVH, and stop before them.
    std::optional<WorkerPool> pool_;
};

}  // namespace luxtrace
