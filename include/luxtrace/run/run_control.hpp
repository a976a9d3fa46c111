#pragma once
// Rank 0's side of the run: after every reduction it evaluates the targets, extends the
// history, forecasts when each target will be met, and decides whether to stop, to
// write a checkpoint, and when to reduce next.
#include "luxtrace/forecast/forecast.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/run/targets.hpp"

#include <iosfwd>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;

struct Decision {
    bool stop = false;
    bool checkpoint = false;
    int exit_code = 0;
    double next_period_s = 1.0;
    std::string reason;
};

struct ReductionInput {
    std::span<const std::uint64_t> tallies;
    std::uint64_t photons = 0;    // photons traced in all, including earlier runs
    double elapsed_s = 0.0;       // wall time of this run so far
    bool all_ranks_idle = false;  // the photon budget is spent
    bool signalled = false;       // SIGTERM / SIGUSR1 seen by some rank
    double stall_s = 0.0;         // tracing time lost per reduction (pause + copy)
    double write_s = 0.0;         // time of the latest checkpoint write
};

class RunController {
public:
    // With reductions at photon counts, the longest wait for one (seconds).
    static constexpr double kPhotonPeriodBound_s = 3600.0;
    // The shortest period a forecast may ask for.
    static constexpr double kMinPeriod_s = 0.05;
    // `previous`: history of the run being continued (times since its start).
    RunController(const Scene& scene, const TallyLayout& layout, std::vector<HistoryRow> previous,
                  double previous_elapsed_s, std::uint64_t previous_photons);

    Decision after_reduction(const ReductionInput& in);
    // Estimates and target states of the latest reduction.
    const GlobalEstimate& global() const { return global_; }
    const std::vector<TargetStatus>& targets() const { return status_; }
    const std::vector<Forecast>& forecasts() const { return forecast_; }
    const std::vector<HistoryRow>& history() const { return history_; }
    void fill_run_info(RunInfo& info) const;
    // One progress line: elapsed, photons, rate, every target's error, goal, forecast.
    std::string progress_line() const;

private:
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
    GlobalEstimate global_;
    std::vector<TargetStatus> status_;
    std::vector<Forecast> forecast_;
    double rate_ = 0.0;
    double elapsed_s_ = 0.0;
    std::uint64_t photons_ = 0;
};

}  // namespace luxtrace
