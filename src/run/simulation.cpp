#include "luxtrace/run/simulation.hpp"

#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <sched.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ostream>
#include <thread>

#ifndef LUXTRACE_VERSION
#define LUXTRACE_VERSION "unknown"
#endif

namespace luxtrace {

int available_cores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
    return std::max(1u, std::thread::hardware_concurrency());
}

namespace {

// Progress for people: one line refreshed in place on a terminal, plain lines in a log.
void report_progress(std::ostream& out, bool tty, double t, std::uint64_t done, std::uint64_t total) {
    const double rate = t > 0.0 ? static_cast<double>(done) / t : 0.0;
    char line[160];
    std::snprintf(line, sizeof line, "  %7.1f s  %14llu / %llu photons (%5.1f%%)  %.3g photons/s", t,
                  static_cast<unsigned long long>(done), static_cast<unsigned long long>(total),
                  100.0 * static_cast<double>(done) / static_cast<double>(total), rate);
    if (tty) out << '\r' << line << std::flush;
    else out << line << '\n' << std::flush;
}

}  // namespace

RunSummary run_simulation(const Scene& scene, const Communicator& comm, const RunOptions& opt, std::ostream& out) {
    const RunConfig& run = scene.run;
    const int threads = opt.threads > 0 ? opt.threads : available_cores();
    const double t0 = comm.wtime();
    EmbreeScene embree(scene);
    TallyStore store{TallyLayout(scene)};

    // Fixed budget: rank r traces photon indices [N r / R, N (r+1) / R). Which rank traces
    // a photon does not matter for the tallies: its random numbers depend on k only.
    const std::uint64_t n = run.photons;
    const auto share = [&](int r) {
        // floor(n r / R) without overflow: n = q R + rem.
        const auto ranks = static_cast<std::uint64_t>(comm.size()), rr = static_cast<std::uint64_t>(r);
        return (n / ranks) * rr + (n % ranks) * rr / ranks;
    };
    TraceOptions topt;
    topt.seed = run.seed;
    topt.sampler = run.sampler;
    topt.threads = threads;
    std::atomic<std::uint64_t> done{0};
    const bool show = comm.is_root() && !opt.quiet && run.report_every_s > 0.0;
    const bool tty = show && ::isatty(STDOUT_FILENO) != 0;
    {
        std::jthread tracing([&] {
            trace_photons(scene, embree, store, share(comm.rank()), share(comm.rank() + 1), topt, &done);
        });
        if (show) {
            const std::uint64_t mine = share(1) - share(0);
            auto next_report = std::chrono::steady_clock::now() + std::chrono::duration<double>(run.report_every_s);
            while (done.load() < mine) {
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
                if (std::chrono::steady_clock::now() >= next_report) {
                    // Rank 0 sees only its own progress; the others trace as many.
                    report_progress(out, tty, comm.wtime() - t0, done.load() * comm.size(), n);
                    next_report += std::chrono::duration<double>(run.report_every_s);
                }
            }
            if (tty) out << '\n';
        }
    }
    comm.reduce_sum_to_root(store.data());
    const double elapsed = comm.allreduce_max(comm.wtime() - t0);

    RunSummary summary;
    summary.output = run.output;
    summary.photons = n;
    summary.elapsed_s = elapsed;
    if (!comm.is_root()) return summary;

    const double e0 = scene.lights.total_flux_lm() / static_cast<double>(n);
    const std::span<const std::uint64_t> data(store.data());
    summary.global = estimate_global(store.layout(), data, scene.triangle_area_m2, e0);
    for (std::size_t d = 0; d < scene.detectors.size(); ++d)
        summary.detectors.push_back(estimate_detector(scene.detectors[d], d, store.layout(), data, e0, n));
    RunInfo info;
    info.luxtrace_version = LUXTRACE_VERSION;
    info.scene_file = std::filesystem::absolute(scene.file).string();
    info.seed = run.seed;
    info.ranks = comm.size();
    info.threads_per_rank = threads;
    info.photons = n;
    info.flux_per_photon_lm = e0;
    info.elapsed_s = elapsed;
    info.stop_reason = "photons";
    info.sampler = run.sampler;
    const std::vector<HistoryRow> history{{elapsed, n, summary.global.sigma_rel_quadratic, 0.0}};
    write_result(run.output, scene, store.layout(), store.data(), info, summary.global, summary.detectors, history);
    return summary;
}

void print_result_summary(const ResultReader& r, std::ostream& out) {
    const auto flags = out.flags();
    const std::uint64_t photons = r.attr_u64("/", "photons");
    const double elapsed = r.attr_f64("/", "elapsed_s");
    out << "scene          " << r.attr_str("/", "scene_file") << '\n'
        << "luxtrace       " << r.attr_str("/", "luxtrace_version") << ", sampler "
        << r.attr_str("/", "sampler") << ", seed " << r.attr_u64("/", "seed") << '\n'
        << "run            " << r.attr_u64("/", "ranks") << " rank(s) x " << r.attr_u64("/", "threads_per_rank")
        << " thread(s), stopped by: " << r.attr_str("/", "stop_reason") << '\n'
        << "photons        " << photons << " in " << std::fixed << std::setprecision(2) << elapsed << " s ("
        << std::scientific << std::setprecision(3) << (elapsed > 0 ? photons / elapsed : 0.0) << " photons/s)\n";
    out << std::defaultfloat << std::setprecision(6);
    out << "flux           " << r.attr_f64("/", "total_flux_lm") << " lm, " << r.attr_f64("/", "flux_per_photon_lm")
        << " lm per photon\n";
    out << std::fixed << std::setprecision(2);
    out << "global map     mean " << r.attr_f64("/global", "mean_arithmetic_lx") << " lx, RMS error "
        << r.attr_f64("/global", "sigma_lx") << " lx, relative "
        << 100.0 * r.attr_f64("/global", "sigma_rel_arithmetic") << " % (arithmetic), "
        << 100.0 * r.attr_f64("/global", "sigma_rel_quadratic") << " % (quadratic)\n";
    for (const std::string& name : r.children("/detectors")) {
        const std::string g = "/detectors/" + name;
        const std::string units = r.attr_str(g, "units");
        out << "detector " << std::left << std::setw(14) << name << std::right << " " << r.attr_str(g, "type")
            << ", mean " << std::setprecision(2) << r.attr_f64(g, "mean_value") << " " << units << " +- "
            << 100.0 * r.attr_f64(g, "mean_sigma_rel") << " %, per-cell error "
            << 100.0 * r.attr_f64(g, "sigma_rel_arithmetic") << " % (eq. 9), "
            << r.attr_u64(g, "photons_received") << " photons received\n";
    }
    out.flags(flags);
}

}  // namespace luxtrace
