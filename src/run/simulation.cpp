#include "luxtrace/run/simulation.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/run_control.hpp"
#include "luxtrace/run/work_plan.hpp"
#include "luxtrace/run/worker_pool.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <ostream>
#include <thread>

#ifndef LUXTRACE_VERSION
#define LUXTRACE_VERSION "unknown"
#endif

namespace luxtrace {

namespace {

bool is_input_error(const std::exception_ptr& e) {
    try {
        std::rethrow_exception(e);
    } catch (const InputError&) {
        return true;
    } catch (...) {
        return false;
    }
}

std::string describe(const std::exception_ptr& e) {
    try {
        std::rethrow_exception(e);
    } catch (const std::exception& x) {
        return x.what();
    } catch (...) {
        return "unknown exception";
    }
}

}  // namespace

int available_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
    return std::max(1u, std::thread::hardware_concurrency());
}

RunSummary run_simulation(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out) {
    const RunConfig& run = scene.run;
    const int threads = opt.threads > 0 ? opt.threads : available_cores();
    const double t0 = comm.wtime();
    const TallyLayout layout(scene);
    TallyStore store(layout);
    const int R = comm.size();

    // Continue a checkpoint: its counts enter once (on rank 0), its traced ranges are skipped.
    std::vector<PhotonRange> done_before;
    std::vector<HistoryRow> history_before;
    double elapsed_before = 0.0;
    if (!opt.restart.empty()) {
        const CheckpointState ck = read_checkpoint(opt.restart);
        if (ck.format_version != kResultFormatVersion)
            throw InputError(opt.restart + ": the checkpoint has result format " + std::to_string(ck.format_version) +
                             ", this luxtrace writes format " + std::to_string(kResultFormatVersion) +
                             " (both sides of every triangle counted apart); continue it with the luxtrace that wrote "
                             "it, or start anew");
        if (ck.sampler == run.sampler && ck.replicates != layout.replicates())
            throw InputError(opt.restart + ": the checkpoint was made with " + std::to_string(ck.replicates) +
                             " replicates; restart with the same (drop --replicates)");
        if (ck.layout_size != layout.size() || ck.triangles != layout.triangles() || ck.bands != layout.bands())
            throw InputError(opt.restart + ": the checkpoint was made for another scene (" +
                             std::to_string(ck.triangles) + " triangles, " + std::to_string(ck.bands) +
                             " bands; this scene has " + std::to_string(layout.triangles()) + " and " +
                             std::to_string(layout.bands()) + ")");
        if (ck.photon_layout != kPhotonLayout)
            throw InputError(opt.restart +
                             ": the checkpoint was made by a luxtrace whose photons draw their random "
                             "numbers differently (photon layout " +
                             std::to_string(ck.photon_layout) + ", this one " + std::to_string(kPhotonLayout) +
                             "); continue it with that version or start anew");
        if (ck.seed != run.seed || ck.sampler != run.sampler)
            throw InputError(opt.restart + ": the checkpoint used seed " + std::to_string(ck.seed) + " and sampler " +
                             ck.sampler + "; restart with the same (drop --seed/--sampler)");
        if (comm.is_root()) store.assign(ck.tallies);
        for (std::size_t i = 0; i + 1 < ck.done.size(); i += 2) done_before.push_back({ck.done[i], ck.done[i + 1]});
        // A restart may set a new budget (--photons), but not one below photons it holds.
        std::uint64_t highest = 0;
        for (const PhotonRange& r : done_before) highest = std::max(highest, r.end);
        if (run.photons < highest)
            throw InputError("--photons: the checkpoint " + opt.restart + " already holds photons up to index " +
                             std::to_string(highest - 1) + "; the budget must be at least " + std::to_string(highest));
        history_before = ck.history;
        elapsed_before = ck.elapsed_s;
    }
    // Items of at most 1M photons, at least 8 per rank when the budget is small.
    const std::uint64_t block = std::clamp<std::uint64_t>(run.photons / (8 * static_cast<std::uint64_t>(R)) + 1,
                                                          std::uint64_t{4096}, std::uint64_t{1} << 20);
    const WorkPlan plan(done_before, run.photons, block, R);
    const std::uint64_t photons_before = plan.previously_done_count();
    RankWork work(plan, comm.rank());
    std::optional<EmbreeScene> own_embree;
    const EmbreeScene& embree = opt.embree != nullptr ? *opt.embree : own_embree.emplace(scene);

    TraceOptions topt;
    topt.seed = run.seed;
    topt.sampler = run.sampler;
    topt.replicates = run.replicates;
    topt.threads = threads;
    topt.chunk = 256;  // pause latency: a thread finishes its chunk before parking

    // The reduced message: the tallies, then per-rank progress and control flags.
    const std::size_t S = layout.size();
    // Faults: ranks whose tracing threads threw an InputError / anything else.
    const std::size_t kSignal = S + 2 * R, kIdle = kSignal + 1, kInputFault = kIdle + 1, kInternalFault = kIdle + 2;
    std::vector<std::uint64_t> snapshot(S + 2 * R + 4, 0), reduced;
    std::optional<RunController> control;
    if (comm.is_root()) control.emplace(scene, layout, history_before, elapsed_before, photons_before);
    const bool show = comm.is_root() && !opt.quiet;
    const std::string checkpoint_path = run.checkpoint.empty() ? run.output + ".checkpoint.h5" : run.checkpoint;

    RunSummary summary;
    summary.output = run.output;
    RunInfo info;
    info.luxtrace_version = LUXTRACE_VERSION;
    info.scene_file = std::filesystem::absolute(scene.file).string();
    info.seed = run.seed;
    info.ranks = R;
    info.threads_per_rank = threads;
    info.sampler = run.sampler;
    info.photon_layout = kPhotonLayout;

    // Root: the done ranges and photon count described by a reduced message.
    auto done_ranges_of = [&](const std::vector<std::uint64_t>& msg) {
        std::vector<RankProgress> progress(static_cast<std::size_t>(R));
        for (int r = 0; r < R; ++r) progress[r] = {msg[S + 2 * r], msg[S + 2 * r + 1]};
        return plan.done_ranges(progress);
    };
    auto write = [&](const std::string& path, const std::vector<std::uint64_t>& msg, double elapsed,
                     const std::string& reason, bool as_checkpoint) {
        const std::vector<PhotonRange> done = done_ranges_of(msg);
        const std::uint64_t n = count_photons(done);
        const std::vector<std::uint64_t> tallies(msg.begin(), msg.begin() + static_cast<std::ptrdiff_t>(S));
        const double e0 = n > 0 ? scene.lights.total_flux_lm() / static_cast<double>(n) : 0.0;
        const GlobalEstimate g = estimate_global(layout, tallies, scene.triangle_area_m2, e0, n);
        std::vector<DetectorEstimate> dets;
        for (std::size_t d = 0; d < scene.detectors.size(); ++d)
            dets.push_back(estimate_detector(scene.detectors[d], d, layout, tallies, e0, n));
        RunInfo i = info;
        i.photons = n;
        i.flux_per_photon_lm = e0;
        i.elapsed_s = elapsed_before + elapsed;
        i.stop_reason = reason;
        control->fill_run_info(i);
        CheckpointData ck;
        if (as_checkpoint) {
            ck.tallies = tallies;
            for (const PhotonRange& r : done) ck.done.insert(ck.done.end(), {r.begin, r.end});
            ck.budget = run.photons;
        }
        write_result(path, scene, layout, tallies, i, g, dets, control->history(), as_checkpoint ? &ck : nullptr);
        summary.photons = n;
        summary.global = g;
        summary.detectors = dets;
    };

    // The latest checkpoint written by this run (root only), for messages after a failed write.
    std::string latest_checkpoint;
    std::uint64_t latest_checkpoint_photons = 0;
    auto latest_checkpoint_note = [&]() -> std::string {
        if (latest_checkpoint.empty()) return "no checkpoint of this run was written before";
        return "the latest checkpoint " + latest_checkpoint + " (" + std::to_string(latest_checkpoint_photons) +
               " photons) is kept";
    };
    // write(), turning a failure to write the file into its message (empty: written).
    auto attempt_write = [&](const std::string& path, const std::vector<std::uint64_t>& msg, double elapsed,
                             const std::string& reason, bool as_checkpoint) -> std::string {
        try {
            write(path, msg, elapsed, reason, as_checkpoint);
        } catch (const IoError& e) {
            return e.what();
        }
        if (as_checkpoint) {
            latest_checkpoint = path;
            latest_checkpoint_photons = summary.photons;
        }
        return {};
    };
    // Where the run will write, checked before any photon is traced (bad input: exit 2).
    std::vector<double> writable{1.0};
    std::string not_writable;
    if (comm.is_root()) {
        try {
            check_writable(run.output, "result file");
            check_writable(checkpoint_path, "checkpoint");
        } catch (const IoError& e) {
            not_writable = e.what();
            writable[0] = 0.0;
        }
    }
    comm.broadcast(writable);
    if (writable[0] == 0.0) throw InputError(not_writable);

    // Reductions at photon counts: each rank stops handing out photons at its share of
    // the next count, and the snapshot is taken when all its threads have parked there.
    const std::uint64_t fence_step = run.report_every_photons > 0
                                         ? std::max<std::uint64_t>(1, (run.report_every_photons + R - 1) / R)
                                         : 0;
    std::uint64_t fence = fence_step;
    if (fence_step > 0) work.set_fence(fence);
    const double trace0 = comm.wtime();
    WorkerPool pool(scene, embree, store, work, topt);
    // The message: this rank's tallies, its progress and its flags. Call only while no
    // thread traces (paused or stopped), so the copy and the progress agree exactly.
    auto fill_snapshot = [&](bool signalled, bool idle) {
        // One rank: the previous reduction's buffer comes back (start_reduce).
        if (snapshot.empty()) snapshot.swap(reduced);
        std::copy(store.data().begin(), store.data().end(), snapshot.begin());
        std::fill(snapshot.begin() + static_cast<std::ptrdiff_t>(S), snapshot.end(), 0);
        const RankProgress p = work.progress();
        snapshot[S + 2 * comm.rank()] = p.items_done;
        snapshot[S + 2 * comm.rank() + 1] = p.prefix;
        snapshot[kSignal] = signalled ? 1 : 0;
        snapshot[kIdle] = idle ? 1 : 0;
        if (pool.failed()) snapshot[is_input_error(pool.error()) ? kInputFault : kInternalFault] = 1;
    };
    auto take_snapshot = [&] {
        // Threads park at chunk boundaries with their buffers flushed.
        pool.pause();
        fill_snapshot(opt.signal != nullptr && opt.signal->load() != 0, pool.exhausted());
        if (fence_step > 0) work.set_fence(fence += fence_step);
        pool.resume();
    };
    // With several ranks the message leaves out the sides no rank has hit yet (tally.hpp):
    // a closed room's walls send their lit side only. Rank 0 restores the full message.
    std::vector<std::uint64_t> side_mask, packed, packed_reduced;
    auto start_reduce = [&]() -> PendingReduce {
        if (R == 1) {
            // One rank: the sum is the snapshot itself. Its buffer becomes `reduced`,
            // and returns to be the next snapshot once the root is done with it: one copy
            // of the tallies besides the store, not two (80 MB on a million triangles,
            // and as many page faults at the first reduction).
            reduced.swap(snapshot);
            return PendingReduce::completed();
        }
        side_mask = lit_side_mask(layout, snapshot);
        comm.allreduce_or(side_mask);
        pack_lit_sides(layout, side_mask, snapshot, packed);
        info.reduction_message_words = packed.size();
        return comm.ireduce_sum_to_root(packed, packed_reduced);
    };
    auto finish_reduce = [&] {
        if (R == 1 || !comm.is_root()) return;
        reduced.resize(snapshot.size());
        unpack_lit_sides(layout, side_mask, packed_reduced, reduced);
    };
    const bool tty = show && ::isatty(STDOUT_FILENO) != 0 && std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr;

    double period = fence_step > 0 ? RunController::kPhotonPeriodBound_s
                                   : std::clamp(run.report_every_s > 0.0 ? run.report_every_s : 2.0, 0.05, 60.0);
    double stall_s = 0.0, write_s = 0.0;
    // Overhead accounting: tracing time lost to pauses, and the main thread's wait for
    // reductions (the workers trace meanwhile).
    double stall_total_s = 0.0, reduce_total_s = 0.0;
    std::uint64_t reductions = 0;
    // stop, checkpoint, exit code, next period, and whether the result is this very
    // reduction's snapshot (below).
    std::vector<double> decision(5, 0.0);
    while (true) {
        const double due = comm.wtime() + period;
        while (comm.wtime() < due && !pool.exhausted() && !pool.failed() &&
               !(opt.signal != nullptr && opt.signal->load() != 0) && !(fence_step > 0 && work.fence_reached()))
            pool.wait_for_park(std::min(0.005, std::max(0.0, due - comm.wtime())));
        const double s0 = comm.wtime();
        take_snapshot();
        stall_s = comm.wtime() - s0;
        stall_total_s += stall_s;
        ++reductions;
        const double r0 = comm.wtime();
        PendingReduce pending = start_reduce();
        while (!pending.test()) std::this_thread::sleep_for(std::chrono::microseconds(500));
        finish_reduce();
        reduce_total_s += comm.wtime() - r0;
        if (comm.is_root() && (reduced[kInputFault] > 0 || reduced[kInternalFault] > 0)) {
            // A rank could not trace: its tallies are incomplete, nothing is written.
            decision = {1.0, 0.0, reduced[kInternalFault] > 0 ? 1.0 : 2.0, period, 0.0};
            summary.stop_reason = "error";
        } else if (comm.is_root()) {
            ReductionInput in;
            in.tallies = std::span<const std::uint64_t>(reduced.data(), S);
            in.photons = count_photons(done_ranges_of(reduced));
            in.elapsed_s = comm.wtime() - t0;
            in.all_ranks_idle = reduced[kIdle] == static_cast<std::uint64_t>(R);
            in.signalled = reduced[kSignal] > 0;
            in.stall_s = stall_s;
            in.write_s = write_s;
            const Decision d = control->after_reduction(in);
            if (show) {
                out << (tty ? "\r" : "") << control->progress_line() << (tty ? "\033[K" : "\n") << std::flush;
            }
            // With reductions at photon counts, a run that ends there (a target met, the
            // budget traced) keeps exactly that snapshot's photons: the threads' chunks
            // beyond it depend on timing, and the result must not (README: the same on any
            // machine). A snapshot taken with every rank out of work holds every photon
            // already: no second copy of the tallies is needed either.
            const bool keep_snapshot = (fence_step > 0 || in.all_ranks_idle) && d.stop && d.exit_code == 0 &&
                                       !d.checkpoint;
            decision = {d.stop ? 1.0 : 0.0, d.checkpoint ? 1.0 : 0.0, static_cast<double>(d.exit_code), d.next_period_s,
                        keep_snapshot ? 1.0 : 0.0};
            summary.stop_reason = d.reason;
            // A periodic checkpoint comes from this exact snapshot; a final one (exit 3)
            // from the final reduction below, which holds more photons.
            if (d.checkpoint && !d.stop) {
                const double w0 = comm.wtime();
                // A failed periodic checkpoint leaves the previous one intact: warn, go on.
                if (const std::string err = attempt_write(checkpoint_path, reduced, in.elapsed_s, "checkpoint", true);
                    !err.empty())
                    std::cerr << "luxtrace: warning: checkpoint not written: " << err << "; "
                              << latest_checkpoint_note() << "; the run goes on\n"
                              << std::flush;
                write_s = comm.wtime() - w0;
            }
        }
        comm.broadcast(decision);
        period = decision[3];
        if (decision[0] != 0.0) break;
    }
    if (tty) out << '\n';
    // Final exact reduction: the threads finish their chunks and flush.
    pool.stop();
    summary.tracing_s = comm.allreduce_max(comm.wtime() - trace0);
    if (decision[2] == 1.0 || decision[2] == 2.0) {
        summary.exit_code = static_cast<int>(decision[2]);
        summary.failed = true;
        if (pool.failed()) summary.error = describe(pool.error());
        return summary;
    }
    if (decision[4] == 0.0) {
        fill_snapshot(false, false);
        start_reduce().wait();
        finish_reduce();
    }
    const double elapsed = comm.allreduce_max(comm.wtime() - t0);
    info.reductions = reductions;
    info.reduction_stall_s = comm.allreduce_max(stall_total_s);
    info.reduction_wait_s = comm.allreduce_max(reduce_total_s);
    summary.elapsed_s = elapsed_before + elapsed;
    summary.exit_code = static_cast<int>(decision[2]);
    std::vector<double> reason_code{0.0};
    std::vector<double> final_code{static_cast<double>(summary.exit_code)};
    if (comm.is_root()) {
        // Each intersection ends in an arrival on a triangle or in an escape.
        summary.rays = reduced[layout.counter(TallyLayout::kEscaped)];
        for (std::size_t i = 0; i < layout.sides(); ++i)
            for (std::size_t b = 0; b < layout.bands(); ++b)
                summary.rays += reduced[layout.side_slot(i, b, TallyLayout::kCountOdd)] +
                                reduced[layout.side_slot(i, b, TallyLayout::kCountEven)];
        const std::string result_err = attempt_write(run.output, reduced, elapsed, summary.stop_reason, false);
        // A result that cannot be written: keep the tallies in a checkpoint instead.
        std::string ck_err;
        if (summary.exit_code == 3 || decision[1] != 0.0 || !result_err.empty())
            ck_err = attempt_write(checkpoint_path, reduced, elapsed, summary.stop_reason, true);
        if (ck_err.empty() && (summary.exit_code == 3 || decision[1] != 0.0 || !result_err.empty()))
            summary.checkpoint = checkpoint_path;
        if (!result_err.empty() || !ck_err.empty()) {
            summary.exit_code = kExitWriteFailed;
            summary.failed = true;
            const std::string restart = "luxtrace run " + scene.file.string() + " --restart ";
            if (!result_err.empty()) {
                summary.error = "the result was not written: " + result_err + "\n";
                if (ck_err.empty())
                    summary.error += "luxtrace: the run's tallies (" + std::to_string(summary.photons) +
                                     " photons) are kept in the checkpoint " + checkpoint_path +
                                     "; write the result from it with: " + restart + checkpoint_path +
                                     " [--output OTHER.h5]";
                else
                    summary.error += "luxtrace: the checkpoint was not written either: " + ck_err +
                                     "\nluxtrace: " + latest_checkpoint_note();
            } else {
                summary.error = "the result " + run.output +
                                " was written, but the checkpoint to continue from was not: " + ck_err +
                                "\nluxtrace: " + latest_checkpoint_note();
            }
        }
        final_code[0] = summary.exit_code;
    }
    // Every rank ends with rank 0's verdict on the writes.
    comm.broadcast(final_code);
    summary.exit_code = static_cast<int>(final_code[0]);
    summary.failed = summary.failed || summary.exit_code == kExitWriteFailed;
    return summary;
}

}  // namespace luxtrace
