#pragma once
// One `luxtrace run` on one rank, as named phases (the shape of OpenMC's
// openmc_next_batch); run_simulation (simulation.hpp) calls them in this order:
//
//   restore    (constructor) a checkpoint's tallies, traced ranges and history; the work plan
//   trace      the annual grids' direct light by shadow rays (if asked), then the rank's
//              tracing threads start
//   snapshot   they park at chunk boundaries; the store hands over the counts added since
//              the previous reduction, and the rank's ReductionMessage is encoded
//   reduce     each rank receives the sum of the sides it owns, rank 0 also of the
//              detectors; each sums its sides' share of the global estimate
//   decide     rank 0: RunController's Decision
//   broadcast  every rank gets rank 0's Decision
//   checkpoint a periodic checkpoint: the owners' sides gathered on rank 0, which writes;
//              snapshot .. checkpoint repeat until the decision stops the run
//   write      the final reduction; the annual grids' post-processing, on several nodes
//              each node its share; the result file and the final checkpoint (rank 0)
//
// The members are the state the phases share.
#include "luxtrace/annual/direct_coefficients.hpp"
#include "luxtrace/core/word_array.hpp"
#include "luxtrace/estimate/annual_estimate.hpp"
#include "luxtrace/io/annual_series_file.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/decision.hpp"
#include "luxtrace/run/reduction_message.hpp"
#include "luxtrace/run/restart.hpp"
#include "luxtrace/run/run_control.hpp"
#include "luxtrace/run/run_options.hpp"
#include "luxtrace/run/targets.hpp"
#include "luxtrace/run/work_plan.hpp"
#include "luxtrace/run/worker_pool.hpp"
#include "luxtrace/tally/message_packing.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

// How a file's write after tracing went: `error` empty when written; `internal` when a
// step failed other than by the file system.
struct WriteOutcome {
    std::string error;
    bool internal = false;
    bool ok() const { return error.empty(); }
};

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
    // Writes the periodic checkpoint the decision asks for (every rank takes part).
    void checkpoint(const Decision& decision);
    // Stops the threads; unless the decision says the last snapshot is the result, reduces
    // once more, exactly; writes the result (and the checkpoint the decision asks for).
    RunSummary write(const Decision& decision);

private:
    // The rank's message from the store and the work plan; only while no thread traces.
    void encode_snapshot(bool signalled, bool idle);
    PendingReduce start_reduce();
    void finish_reduce();
    // Each rank's partial sums of the global estimates over its sides; rank 0's globals_.
    void estimate_owned_sides();
    // Rank 0's totals_ get every rank's sides (for the result and checkpoints).
    void gather_map();
    // The final result's annual post-processing shared by the nodes (more than one; or by
    // the ranks, RunOptions::annual_parts_per_rank): rank 0 hands each part's rank its share
    // of each grid's cells (their counts, their direct coefficients and the grid's dark
    // rates), each part runs its blocks on every core, and rank 0 merges the parts into
    // shared_annual_. Any failure leaves shared_annual_ empty, and rank 0's write computes
    // the estimates itself (and says what failed).
    void share_annual_estimates();

    // Rank 0 writes the result or a checkpoint from the reduced message, in named steps
    // (write_steps.hpp); a failure of any kind comes back as its outcome, never as an
    // exception: a run that has traced keeps its tallies (docs/RELIABILITY.md).
    WriteOutcome attempt_write(const std::string& path, double elapsed_s, const std::string& reason,
                               bool as_checkpoint);
    void write_file(const std::string& path, double elapsed_s, const std::string& reason, bool as_checkpoint);
    // The tallies alone (tally_checkpoint_image), when a whole checkpoint cannot be made.
    void write_tally_checkpoint(const std::string& path, double elapsed_s, const std::string& reason);
    static WriteOutcome attempt(const std::function<void()>& write);
    // A checkpoint of the run: whole at the checkpoint's path, else the tallies alone
    // there, else (`beside_result`: the run's last chance) beside the result;
    // latest_checkpoint_ names it.
    WriteOutcome keep_checkpoint(double elapsed_s, const std::string& reason, bool beside_result);
    // What the run has traced: its photon ranges, their count and each photon's flux.
    struct Traced {
        std::vector<PhotonRange> done;
        std::uint64_t photons = 0;
        double e0 = 0.0;
    };
    Traced traced() const;
    // share_annual_estimates' steps for grid `det`, ranges[r] rank r's cells: rank 0 hands
    // every rank its cells' counts (into its totals_) and direct coefficients (`direct` then
    // points at them) and returns the grid's dark rates on every rank; then rank 0 gathers
    // the parts into `out`. A failed step is skipped after (PartAttempt), not thrown.
    struct PartAttempt;
    // Rank 0: the gathered grids' own rays' errors (DirectCoefficients::gather_rel_var) from
    // the tallies so far, e0 the flux per photon.
    void update_gather_errors(double e0);
    AnnualDarkRates share_annual_inputs(std::size_t det, const std::vector<AnnualCellRange>& ranges, const Traced& t,
                                        DirectCoefficients& own_direct, const DirectCoefficients*& direct,
                                        PartAttempt& attempt);
    void gather_annual_part(std::size_t det, const std::vector<AnnualCellRange>& ranges, AnnualGridPart part,
                            const DirectCoefficients* direct, PartAttempt& attempt,
                            std::optional<AnnualDetectorEstimate>& out);
    RunInfo final_info(const Traced& t, double elapsed_s, const std::string& reason) const;
    // Rank 0: where the annual grids' hourly series go while they are made and are read back
    // from for the files (io/annual_series_file.hpp), beside the result; made at first use.
    AnnualSeriesFile& series_file();
    AnnualSeriesSink series_sink();
    AnnualSeriesSource series_source();
    CheckpointData checkpoint_data(const std::vector<PhotonRange>& done) const;
    std::string latest_checkpoint_note() const;
    // "the run's tallies are kept in the checkpoint ...; THEN: luxtrace run ... --restart ...".
    std::string tallies_kept_note(const std::string& then) const;
    void explain_failed_writes(const WriteOutcome& result, const WriteOutcome& checkpoint);
    // Rank 0, after the final reduction: the result and the checkpoint the decision asks
    // for; or, when rank 0's decision failed, the tallies alone in a checkpoint.
    void write_result_and_checkpoint(const Decision& decision, double elapsed);
    void keep_after_decision_fault(double elapsed);

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
    const SurfaceTable surfaces_;  // the tracing threads' view of the scene, built with the BVH
    AnnualDirect annual_direct_;   // rank 0: the annual grids' direct light by shadow rays
    // rank 0: the final result's annual estimates made by every rank, and their wall time
    std::optional<std::vector<std::optional<AnnualDetectorEstimate>>> shared_annual_;
    double shared_annual_s_ = 0.0;
    std::unique_ptr<AnnualSeriesFile> series_file_;
    bool shared_annual_used_ = false;       // the result's annual step took them
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

    // snapshot and reduce (docs/RUN_CONTROL.md, "Reductions"). The store's counts since the
    // previous reduction (delta_) go out without the words zero on every rank
    // (message_packing.hpp): the map's as 32-bit words while they fit, reduce-scattered to
    // the ranks that own its sides; the counters and detectors to rank 0. Each rank keeps
    // the running sums of the words it owns in totals_ (a full-size WordArray of which only
    // those words are ever written); with one rank it owns them all.
    std::span<std::uint64_t> delta_;
    WordArray totals_;
    bool totals_empty_ = true;              // one rank: no reduction has added to totals_ yet
    const std::vector<MessagePart> parts_;  // the sides each rank owns, by rank
    const MessagePart own_;                 // this rank's
    std::vector<std::uint64_t> lit_;        // one bit per side some photon has reached (mask_side_words)
    const GlobalRequests requests_;
    std::vector<std::uint64_t> own_replicate_photons_;  // since the run began (sobol)
    ReductionMessage header_, summed_header_;
    std::vector<std::uint64_t> mask_;
    std::vector<std::size_t> part_counts_;
    std::vector<std::uint32_t> map_send32_, map_recv32_;
    std::vector<std::uint64_t> map_send64_, map_recv64_, tail_send_, tail_recv_;
    std::uint64_t photons_ = 0;
    std::vector<GlobalEstimate> globals_;  // rank 0

    // decide: timing, and the overhead accounting (tracing time lost to pauses, and the
    // main thread's wait for reductions while the workers trace).
    double period_s_;
    double stall_s_ = 0.0, work_s_ = 0.0, wait_s_ = 0.0, write_s_ = 0.0;
    // Runs `wait` (a collective: this rank waits for the others) and counts its time as
    // the reduction's wait, not its work.
    template <class Wait>
    void timed_wait(Wait&& wait) {
        const double t = comm_.wtime();
        wait();
        wait_s_ += comm_.wtime() - t;
    }
    double stall_total_s_ = 0.0, reduce_wait_total_s_ = 0.0, reduce_work_total_s_ = 0.0;
    double decided_elapsed_s_ = 0.0;
    std::uint64_t reductions_ = 0;

    // write: the latest checkpoint this run wrote (rank 0), for messages after a failed write.
    std::string latest_checkpoint_;
    std::string decide_error_;     // rank 0's failed decision, if one failed
    bool result_on_disk_ = false;  // the final result's file is written (what follows may fail)
    std::uint64_t latest_checkpoint_photons_ = 0;

    // Last: its threads use the store, the work and the BVH, and stop before them.
    std::optional<WorkerPool> pool_;
};

}  // namespace luxtrace
