#pragma once
// Rank 0's side of the run: after every reduction it evaluates the targets, extends the
// history, forecasts when each target will be met, and decides whether to stop, to
// write a checkpoint, and when to reduce next.
#include "luxtrace/forecast/forecast.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/run/decision.hpp"
#include "luxtrace/run/targets.hpp"

#include <iosfwd>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
struct RunConfig;

struct ReductionInput {
    // The reduced tallies. With `globals` given, only the words after the surface map are
    // read (a distributed reduction leaves the map with the ranks that own its sides).
    std::span<const std::uint64_t> tallies;
    // The global estimates of global_requests(scene), in its order; empty: computed here
    // from the whole map in `tallies`.
    std::span<const GlobalEstimate> globals;
    std::uint64_t photons = 0;     // photons traced in all, including earlier runs
    double elapsed_s = 0.0;        // wall time of this run so far
    double tracing_start_s = 0.0;  // elapsed_s when tracing began (after the BVH build)
    bool all_ranks_idle = false;   // the photon budget is spent
    bool signalled = false;        // SIGTERM / SIGUSR1 seen by some rank
    double stall_s = 0.0;          // tracing time lost to the reduction's pause
    double work_s = 0.0;           // the main thread's work on the reduction (taken from tracing)
    double write_s = 0.0;          // time of the latest checkpoint write
    // The annual grids' direct coefficients by shadow rays (annual targets), or none.
    const AnnualDirect* annual_direct = nullptr;
};

class RunController {
public:
    // With reductions at photon counts, the longest wait for one (seconds).
    static constexpr double kPhotonPeriodBound_s = 3600.0;
    // The shortest period a forecast may ask for, and the bounds of report_every_s.
    static constexpr double kMinPeriod_s = 0.05;
    static constexpr double kMaxReportPeriod_s = 60.0;
    // The first reduction's period: report_every_s (kDefaultReportEvery_s when 0) within
    // the bounds, or kPhotonPeriodBound_s with reductions at photon counts.
    static double initial_period_s(const RunConfig& run);
    // `previous`: history of the run being continued (times since its start).
    RunController(const Scene& scene, const TallyLayout& layout, std::vector<HistoryRow> previous,
                  double previous_elapsed_s, std::uint64_t previous_photons);

    // The rules in order: a target met, the budget traced, a signal (checkpoint, exit 3),
    // the time limit (exit 3 with a checkpoint while error targets are unmet), a periodic
    // checkpoint; the next period from the stalls and the forecasts.
    Decision after_reduction(const ReductionInput& in);
    const std::vector<HistoryRow>& history() const { return history_; }
    void fill_run_info(RunInfo& info) const;
    // One progress line: elapsed, photons, rate, every target's error, goal, forecast.
    std::string progress_line() const;

private:
    Decision decide(const ReductionInput& in);
    // What a reduction tells: the global estimates (when the input has none), the photon
    // rate, the targets' states and forecasts, and the history row they make.
    std::vector<GlobalEstimate> estimate_globals(const ReductionInput& in, double e0) const;
    void measure_rate(const ReductionInput& in);
    HistoryRow evaluate_targets(const ReductionInput& in, double e0, std::span<const GlobalEstimate> globals);
    void extend_history(const ReductionInput& in, HistoryRow row);
    // When to reduce next: the period, at least 100 times the recent stalls (stall_bound_s),
    // shortened to a target's forecast.
    double stall_bound_s(const ReductionInput& in);
    double next_period_s(const ReductionInput& in);
    // The stop rules, in the order decide applies them; each says whether it stopped the run.
    bool stop_at_met_target(Decision& d) const;
    static bool stop_at_traced_budget(const ReductionInput& in, Decision& d);
    static bool stop_at_signal(const ReductionInput& in, Decision& d);
    bool stop_before_time_limit(const ReductionInput& in, Decision& d) const;  // else bounds next_period_s
    void checkpoint_when_due(const ReductionInput& in, Decision& d);

    const Scene& scene_;
    const TallyLayout& layout_;
    std::vector<HistoryRow> history_;                // stored: whole run including earlier parts
    std::vector<std::vector<HistoryPoint>> points_;  // per target, this part only
    std::vector<HistoryPoint> rate_points_;          // (time, photons) of this part only
    double time_offset_s_;
    std::uint64_t photon_offset_;
    double last_checkpoint_s_ = 0.0;
    double period_s_;
    std::vector<double> recent_stalls_;
    GlobalRequests requests_;
    GlobalEstimate global_;
    std::vector<TargetStatus> status_;
    std::vector<Forecast> forecast_;
    double rate_ = 0.0;
    double elapsed_s_ = 0.0;
    std::uint64_t photons_ = 0;
};

}  // namespace luxtrace
