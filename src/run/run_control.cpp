#include "luxtrace/run/run_control.hpp"

#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace luxtrace {

RunController::RunController(const Scene& scene, const TallyLayout& layout, std::vector<HistoryRow> previous,
                             double previous_elapsed_s, std::uint64_t previous_photons)
    : scene_(scene), layout_(layout), history_(std::move(previous)), points_(scene.run.targets.size()),
      time_offset_s_(previous_elapsed_s), photon_offset_(previous_photons), period_s_(initial_period_s(scene.run)),
      requests_(global_requests(scene)) {}

double RunController::initial_period_s(const RunConfig& run) {
    // Reductions come at photon counts; the period only bounds the wait (time limit).
    if (run.report_every_photons > 0) return kPhotonPeriodBound_s;
    return std::clamp(run.report_every_s > 0.0 ? run.report_every_s : kDefaultReportEvery_s, kMinPeriod_s,
                      kMaxReportPeriod_s);
}

Decision RunController::after_reduction(const ReductionInput& in) {
    Decision d = decide(in);
    // With reductions at photon counts, a run that ends there (a target met, the budget
    // traced) keeps exactly that snapshot's photons: the threads' chunks beyond it depend
    // on timing, and the result must not (README: the same on any machine). A snapshot
    // taken with every rank out of work holds every photon already: no second copy of the
    // tallies is needed either.
    d.result_is_snapshot = (scene_.run.report_every_photons > 0 || in.all_ranks_idle) && d.stop && d.exit_code == 0 &&
                           !d.checkpoint;
    return d;
}

Decision RunController::decide(const ReductionInput& in) {
    photons_ = in.photons;
    elapsed_s_ = in.elapsed_s;
    const double e0 = in.photons > 0 ? scene_.lights.total_flux_lm() / static_cast<double>(in.photons) : 0.0;
    const std::vector<GlobalEstimate> computed = in.globals.empty() ? estimate_globals(in, e0)
                                                                    : std::vector<GlobalEstimate>{};
    const std::span<const GlobalEstimate> globals = in.globals.empty() ? computed : in.globals;
    global_ = globals[0];
    measure_rate(in);
    extend_history(in, evaluate_targets(in, e0, globals));
    Decision d;
    d.next_period_s = next_period_s(in);
    // The stop rules in order: the first that applies decides.
    if (stop_at_met_target(d)) return d;
    if (stop_at_traced_budget(in, d)) return d;
    if (stop_at_signal(in, d)) return d;
    if (stop_before_time_limit(in, d)) return d;
    checkpoint_when_due(in, d);
    return d;
}

std::vector<GlobalEstimate> RunController::estimate_globals(const ReductionInput& in, double e0) const {
    std::vector<GlobalEstimate> computed;
    for (const std::vector<double>& w : requests_.weights)
        computed.push_back(
            estimate_global(WeightedTallies(layout_, in.tallies, w), scene_.triangle_area_m2, e0, in.photons));
    return computed;
}

void RunController::measure_rate(const ReductionInput& in) {
    // The photon rate is the tracing's: its first point is where tracing began, not where
    // the run's clock started (the BVH of a large scene takes seconds to build).
    if (rate_points_.empty() && in.tracing_start_s > 0.0 && in.tracing_start_s < in.elapsed_s)
        rate_points_.push_back({in.tracing_start_s, 0.0, 0.0});
    rate_points_.push_back({in.elapsed_s, static_cast<double>(in.photons - photon_offset_), 0.0});
    rate_ = photon_rate(rate_points_);
}

HistoryRow RunController::evaluate_targets(const ReductionInput& in, double e0,
                                           std::span<const GlobalEstimate> globals) {
    const RunConfig& run = scene_.run;
    status_.clear();
    forecast_.clear();
    HistoryRow
        row{time_offset_s_ + in.elapsed_s, in.photons, global_.target_sigma_rel(false), std::nan(""), {}, {}, {}};
    for (std::size_t i = 0; i < run.targets.size(); ++i) {
        status_.push_back(evaluate_target(run.targets[i], scene_, layout_, in.tallies, e0, in.photons,
                                          globals[requests_.of_target[i]],
                                          in.annual_direct != nullptr ? *in.annual_direct : AnnualDirect{}));
        const TargetStatus& s = status_.back();
        // Forecasts use this part of the run only: rates differ between parts.
        if (in.photons > photon_offset_ && std::isfinite(s.value))
            points_[i].push_back({in.elapsed_s, static_cast<double>(in.photons), s.value});
        // sobol errors may fall faster than 1/sqrt(N): fit the exponent (docs/QMC.md).
        Forecast f = s.kind == TargetKind::photons_received ? forecast_count(points_[i], s.goal, rate_)
                     : layout_.replicates() > 0             ? forecast_error_fitted(points_[i], s.goal, rate_)
                                                            : forecast_error(points_[i], s.goal, rate_);
        forecast_.push_back(f);
        row.target_value.push_back(s.value);
        row.target_forecast_s.push_back(f.valid ? time_offset_s_ + f.time_s : std::nan(""));
        row.target_forecast_photons.push_back(f.valid ? f.photons_needed : std::nan(""));
    }
    if (!row.target_forecast_s.empty()) row.forecast_s = row.target_forecast_s.front();
    return row;
}

void RunController::extend_history(const ReductionInput& in, HistoryRow row) {
    // A restart that adds no photons (it writes the result a checkpoint holds, issue 35)
    // adds no row: the history is the one the interrupted run would have written.
    const bool nothing_new = in.photons == photon_offset_ && !history_.empty() && history_.back().photons == in.photons;
    if (!nothing_new) history_.push_back(std::move(row));
}

double RunController::stall_bound_s(const ReductionInput& in) {
    // Keep the tracing time reductions take under 1% of the run (issue 26). A stall can be
    // inflated by a descheduled thread on a busy machine: use the median of the last five.
    recent_stalls_.push_back(in.stall_s + in.work_s);
    if (recent_stalls_.size() > 5) recent_stalls_.erase(recent_stalls_.begin());
    std::vector<double> sorted = recent_stalls_;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    return 100.0 * sorted[sorted.size() / 2];
}

double RunController::next_period_s(const ReductionInput& in) {
    const double min_period_s = stall_bound_s(in);
    if (scene_.run.report_every_photons == 0) period_s_ = std::max(period_s_, min_period_s);
    double next = period_s_;
    // When a target's forecast falls before the next reduction, reduce then instead: the
    // run stops close to the moment the target is met, not up to a period later. (Not
    // with reductions at photon counts, whose schedule is fixed.)
    if (scene_.run.report_every_photons == 0)
        for (const Forecast& f : forecast_)
            if (f.valid && f.time_s > in.elapsed_s)
                next = std::min(next, std::max({kMinPeriod_s, min_period_s, 1.02 * (f.time_s - in.elapsed_s)}));
    return next;
}

bool RunController::stop_at_met_target(Decision& d) const {
    for (const TargetStatus& s : status_)
        if (s.met) {
            d.stop = true;
            d.reason = "target " + s.label;
            return true;
        }
    return false;
}

bool RunController::stop_at_traced_budget(const ReductionInput& in, Decision& d) {
    if (!in.all_ranks_idle) return false;
    d.stop = true;
    d.reason = "photons";
    return true;
}

bool RunController::stop_at_signal(const ReductionInput& in, Decision& d) {
    if (!in.signalled) return false;
    d.stop = d.checkpoint = true;
    d.exit_code = 3;
    d.reason = "signal";
    return true;
}

bool RunController::stop_before_time_limit(const ReductionInput& in, Decision& d) const {
    const RunConfig& run = scene_.run;
    if (!(run.time_limit_s > 0.0)) return false;
    // Stop in time to write the result before the wall-time limit. When error targets
    // are still unmet, the run is unfinished work: checkpoint and exit 3 to be resumed.
    const double margin_s = 2.0 * in.write_s + 0.25;  // time to write the result
    if (in.elapsed_s + margin_s + 0.05 >= run.time_limit_s) {
        d.stop = true;
        d.reason = "time_limit";
        const bool error_targets_unmet = std::any_of(status_.begin(), status_.end(), [](const TargetStatus& s) {
            return s.kind != TargetKind::photons_received;
        });
        if (error_targets_unmet) {
            d.checkpoint = true;
            d.exit_code = 3;
        }
        return true;
    }
    // The next reduction comes no later than the last moment to stop.
    d.next_period_s = std::min(d.next_period_s, run.time_limit_s - margin_s - in.elapsed_s);
    return false;
}

void RunController::checkpoint_when_due(const ReductionInput& in, Decision& d) {
    const RunConfig& run = scene_.run;
    if (run.checkpoint_every_s > 0.0 && in.elapsed_s - last_checkpoint_s_ >= run.checkpoint_every_s) {
        d.checkpoint = true;
        last_checkpoint_s_ = in.elapsed_s;
    }
}

void RunController::fill_run_info(RunInfo& info) const {
    for (std::size_t i = 0; i < status_.size(); ++i) {
        info.target_labels.push_back(status_[i].label);
        info.target_goals.push_back(status_[i].goal);
    }
    if (status_.empty())
        for (const Target& t : scene_.run.targets) {
            info.target_labels.push_back(t.on);
            info.target_goals.push_back(t.relative_error + t.absolute_error + t.photons_received);
        }
}

std::string RunController::progress_line() const {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%8.1f s %12.4g photons %10.3g/s  global %.2f%%", time_offset_s_ + elapsed_s_,
                  static_cast<double>(photons_), rate_, 100.0 * global_.target_sigma_rel(false));
    std::string line = buf;
    for (std::size_t i = 0; i < status_.size(); ++i) {
        const TargetStatus& s = status_[i];
        if (s.kind == TargetKind::photons_received)
            std::snprintf(buf, sizeof buf, " | %s %.4g -> %.4g", s.label.c_str(), s.value, s.goal);
        else if (s.kind == TargetKind::relative_error)
            std::snprintf(buf, sizeof buf, " | %s %.3f%% -> %.3f%%", s.label.c_str(), 100.0 * s.value, 100.0 * s.goal);
        else std::snprintf(buf, sizeof buf, " | %s %.4g -> %.4g", s.label.c_str(), s.value, s.goal);
        line += buf;
        const Forecast& f = forecast_[i];
        if (s.met) line += " met";
        else if (f.valid) {
            std::snprintf(buf, sizeof buf, " in %.0f s", std::max(0.0, f.time_s - elapsed_s_));
            line += buf;
        }
    }
    return line;
}

}  // namespace luxtrace
