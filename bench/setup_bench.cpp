// setup_bench: what a large scene costs before its first photon (docs/SCALING.md "Setup
// time of ten million triangles"): loading the scene, and Embree's BVH under each build
// option against the speed of the BVH it gives.
//
// In one process: the scene is loaded --repeats times (timed); the tracer's own rays are
// recorded once on the BVH the scene itself gets (BvhOptions::of); then, repeats outermost and the options
// in turn (so that other load on the machine hits all alike), each option's EmbreeScene is
// built (wall time; CPU time: cpu / wall is how many cores the build used, and the share of
// it spent by threads other than the caller; the resident memory it added) and the recorded
// rays are replayed through it on --threads threads (rtcIntersect1, as the tracer calls
// it). An option that finds another number of hits than the first is named. With
// --tracer-photons, the production tracer (run_simulation, tracer_run.hpp) also runs that
// many photons on each BVH, timed over its tracing (the result file is written after).
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "rays.hpp"
#include "replay.hpp"
#include "timing.hpp"
#include "tracer_run.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using namespace luxtrace;
using namespace luxtrace::bench;

namespace {

struct Option {
    const char* name;
    BvhOptions bvh;
};

const std::vector<Option>& options() {
    static const std::vector<Option> all{
        {"high", {RTC_BUILD_QUALITY_HIGH, RTC_BUILD_QUALITY_MEDIUM, false}},
        {"medium", {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_MEDIUM, false}},
        {"low/low", {RTC_BUILD_QUALITY_LOW, RTC_BUILD_QUALITY_LOW, false}},
        {"low/medium", {RTC_BUILD_QUALITY_LOW, RTC_BUILD_QUALITY_MEDIUM, false}},
        {"high+compact", {RTC_BUILD_QUALITY_HIGH, RTC_BUILD_QUALITY_MEDIUM, true}},
        {"medium+compact", {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_MEDIUM, true}},
    };
    return all;
}

// Resident set of this process in bytes (/proc/self/statm's second field, in pages).
double resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    double size = 0.0, resident = 0.0;
    statm >> size >> resident;
    return resident * double(::sysconf(_SC_PAGESIZE));
}

struct Samples {
    std::vector<double> build_s, build_cpu_s, cpu_ratio, other_threads, added_mb, rays_per_s, rays_per_cpu_s,
        photons_per_s;
};

void print_row(const char* name, const Samples& s) {
    auto range = [](const std::vector<double>& v, const char* fmt, double scale) {
        char buf[96];
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        std::snprintf(buf, sizeof buf, fmt, median(v) * scale, *lo * scale, *hi * scale);
        return std::string(buf);
    };
    std::printf("%-15s %-19s %-19s %-19s %-19s %-6.2f %-6.0f %.0f\n", name,
                range(s.build_s, "%.2f [%.2f..%.2f]", 1.0).c_str(),
                range(s.build_cpu_s, "%.2f [%.2f..%.2f]", 1.0).c_str(),
                range(s.rays_per_s, "%.2f [%.2f..%.2f]", 1e-6).c_str(),
                range(s.rays_per_cpu_s, "%.2f [%.2f..%.2f]", 1e-6).c_str(), median(s.cpu_ratio),
                100.0 * median(s.other_threads), median(s.added_mb));
    if (!s.photons_per_s.empty())
        std::printf("%-15s tracer: %s photons/s\n", "", range(s.photons_per_s, "%.3g [%.3g..%.3g]", 1.0).c_str());
}

struct Settings {
    std::string file, photons = "200k", tracer_photons = "0", only;
    int repeats = 3, threads = 2;
};

int run(const Settings& set, const Communicator& comm) {
    const std::string& file = set.file;
    const std::string& photons_text = set.photons;
    const int repeats = set.repeats, threads = set.threads;
    const auto tracer_photons = parse_count(set.tracer_photons);
    if (!tracer_photons) throw InputError("--tracer-photons: '" + set.tracer_photons + "' is not a count");
    const auto photons = parse_count(photons_text);
    if (!photons || *photons == 0) throw InputError("--photons: '" + photons_text + "' is not a positive count");
    if (repeats < 1) throw InputError("--repeats: must be at least 1");
    std::vector<double> load_s;
    Scene scene;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        scene = load_scene(file);
        load_s.push_back(seconds_since(t0));
    }
    std::vector<RecordedRay> rays;
    {
        const EmbreeScene embree(scene);
        rays = record_tracer_rays(scene, embree, *photons, scene.run.seed);
    }
    std::printf("scene %s: %zu triangles; load %.2f s [%.2f..%.2f] (%d repeats); %zu rays of %llu photons "
                "replayed on %d threads\n\n",
                file.c_str(), scene.triangle_count(), median(load_s), *std::min_element(load_s.begin(), load_s.end()),
                *std::max_element(load_s.begin(), load_s.end()), repeats, rays.size(),
                static_cast<unsigned long long>(*photons), threads);
    std::vector<Samples> samples(options().size());
    std::vector<std::uint64_t> hits(options().size(), 0);
    for (int r = 0; r < repeats; ++r)
        for (std::size_t o = 0; o < options().size(); ++o) {
            if (!set.only.empty() &&
                ("," + set.only + ",").find(std::string(",") + options()[o].name + ",") == std::string::npos)
                continue;
            const double rss0 = resident_bytes(), c0 = process_cpu_seconds(), m0 = thread_cpu_seconds();
            const auto t0 = Clock::now();
            const EmbreeScene embree(scene, options()[o].bvh);
            const double wall = seconds_since(t0), cpu = process_cpu_seconds() - c0;
            samples[o].build_s.push_back(wall);
            samples[o].build_cpu_s.push_back(cpu);
            samples[o].cpu_ratio.push_back(cpu / wall);
            samples[o].other_threads.push_back(1.0 - (thread_cpu_seconds() - m0) / cpu);
            samples[o].added_mb.push_back((resident_bytes() - rss0) / 1e6);
            const Timed t = replay(embree, rays, threads);
            samples[o].rays_per_s.push_back(double(t.rays) / t.seconds);
            samples[o].rays_per_cpu_s.push_back(double(t.rays) / t.cpu_seconds);
            if (r > 0 && t.hits != hits[o]) throw std::runtime_error("the hits changed between repeats");
            if (*tracer_photons > 0) {
                const auto out = std::filesystem::temp_directory_path() /
                                 ("luxtrace_setup_bench_" + std::to_string(::getpid()) + ".h5");
                const Timed p = run_tracer(scene, embree, comm, *tracer_photons, threads, out, nullptr);
                samples[o].photons_per_s.push_back(double(*tracer_photons) / p.seconds);
                std::filesystem::remove(out);
            }
            hits[o] = t.hits;
        }
    for (std::size_t o = 1; o < options().size(); ++o)
        if (hits[o] != hits[0] && hits[o] != 0 && hits[0] != 0)
            std::printf("note: %s finds %llu hits, %s %llu\n", options()[o].name,
                        static_cast<unsigned long long>(hits[o]), options()[0].name,
                        static_cast<unsigned long long>(hits[0]));
    std::printf("%-15s %-19s %-19s %-19s %-19s %-6s %-6s %s\n", "option", "build wall s", "build CPU s", "Mrays/s wall",
                "Mrays/CPU-s", "cpu/wl", "%other", "MB");
    for (std::size_t o = 0; o < options().size(); ++o)
        if (!samples[o].build_s.empty()) print_row(options()[o].name, samples[o]);
    std::printf("\nmedians [min..max] over %d repeats. Mrays: the replay's rays per wall second and per CPU second\n"
                "(the latter less sensitive to other load). cpu/wl, %%other, MB (medians): the build's CPU time\n"
                "over its wall time, the share of that CPU time spent by threads other than the caller\n"
                "(Embree's TBB workers), and the resident memory it added.\n",
                repeats);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);  // run_simulation reduces through it (one rank)
    CLI::App app{"setup_bench: a scene's load time and Embree's BVH build options against the BVH's speed"};
    Settings set;
    app.add_option("scene", set.file, "scene file (TOML)")->required();
    app.add_option("--repeats", set.repeats, "loads and builds of each option")->capture_default_str();
    app.add_option("--threads", set.threads, "threads of the replay and the tracer")->capture_default_str();
    app.add_option("--photons", set.photons, "photons whose rays are replayed")->capture_default_str();
    app.add_option("--tracer-photons", set.tracer_photons,
                   "photons of a production tracer run on each BVH (0: none; its tracing time is timed)")
        ->capture_default_str();
    app.add_option("--options", set.only, "comma-separated option names (default: all)");
    CLI11_PARSE(app, argc, argv);
    try {
        return run(set, comm);
    } catch (const InputError& e) {
        std::cerr << "setup_bench: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "setup_bench: error: " << e.what() << "\n";
        return 1;
    }
}
