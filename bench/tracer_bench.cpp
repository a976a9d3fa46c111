// tracer_bench: how close `luxtrace run`'s photon tracing comes to Embree alone on the
// same rays, the same BVH and the same threads (docs/PERFORMANCE.md).
//
// In one process, on one scene and one EmbreeScene:
//   probe  - the photon tracer traces a few hundred thousand photons and records every
//            ray it hands to Embree (local origin, direction, t_near);
//   replay - rtcIntersect1 on exactly those rays, threads taking chunks of 1024;
//   cosine - rtcIntersect1 on rays leaving random points of the surfaces with cosine
//            directions (the older baseline, a second column);
//   packets - with --packets, the replayed rays through rtcIntersect8 in groups of 8;
//   floor  - with --floor, a minimal analog photon tracer (FloorTracer) against the
//            replay of its own rays: the least any tracer of this kind adds to Embree;
//   tracer - run_simulation, the code `luxtrace run` runs: the work plan, the pausable
//            worker pool, snapshots and reductions at the scene's period, on the same
//            EmbreeScene; its rays are the intersections it made (arrivals + escapes),
//            its time that of its tracing threads (the result file is written after).
// Measurements alternate (replay, cosine, tracer for each thread count, repeats outermost)
// so that other load hits all alike; medians over repeats, and paired ratios (the median
// over repeats of tracer/replay measured back to back). Every tracer run with the same
// seed must give bit-identical tallies whatever the thread count.
//
// Here: the options, the scene and its rays, and the sizing of the runs. rays.hpp (the
// recorded and cosine rays), replay.hpp (Embree alone), floor_tracer.hpp, tracer_run.hpp
// (the production path), measurements.hpp (the timed runs and pairing), report.hpp.
#include "floor_tracer.hpp"
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"
#include "measurements.hpp"
#include "rays.hpp"
#include "report.hpp"
#include "timing.hpp"
#include "tracer_run.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

using namespace luxtrace;
using namespace luxtrace::bench;
namespace fs = std::filesystem;

namespace {

std::vector<int> parse_threads(const std::string& text) {
    std::vector<int> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        int v = 0;
        try {
            v = std::stoi(item);
        } catch (const std::exception&) {
            v = 0;
        }
        if (v < 1) throw InputError("--threads-list: '" + item + "' is not a thread count >= 1");
        out.push_back(v);
    }
    if (out.empty()) throw InputError("--threads-list: empty");
    return out;
}

std::uint64_t count_arg(const std::string& opt, const std::string& text) {
    const auto v = parse_count(text);
    if (!v || *v == 0) throw InputError(opt + ": '" + text + "' is not a positive count");
    return *v;
}

struct Settings {
    std::string scene_file, threads = "1,2", photons = "auto", probe = "auto";
    int repeats = 5;
    double seconds = 1.5;  // auto sizing: length of one single-thread measurement
    std::uint64_t seed = 1;
    bool verbose = false;
    bool packets = false;
    bool floor = false;
    std::string sampler = "random";
};

int run(const Settings& set, const Communicator& comm) {
    const std::vector<int> thread_counts = parse_threads(set.threads);
    if (set.repeats < 1) throw InputError("--repeats: must be at least 1");
    if (!(set.seconds > 0.0)) throw InputError("--seconds: must be positive");
    if (set.photons != "auto") count_arg("--photons", set.photons);
    if (set.probe != "auto") count_arg("--probe-photons", set.probe);

    auto t0 = Clock::now();
    Scene scene = load_scene(set.scene_file);
    scene.run.sampler = set.sampler;  // --sampler: the tracer runs' sampler
    const double t_load = seconds_since(t0);
    t0 = Clock::now();
    const EmbreeScene embree(scene);
    const double t_build = seconds_since(t0);
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_bench_" + std::to_string(::getpid()));
    fs::create_directories(dir);

    // Warm-up and sizing: a short probe gives the tracer's rate and rays per photon.
    constexpr std::uint64_t kWarm = 20000;
    t0 = Clock::now();
    const std::vector<RecordedRay> warm = record_tracer_rays(scene, embree, kWarm, set.seed + 7);
    const double warm_s = seconds_since(t0);
    const double rays_per_photon = double(warm.size()) / double(kWarm);
    std::uint64_t photons = 0;
    if (set.photons == "auto") {
        // The recording probe is slow and cold (a third of the tracer's rate on the million
        // room), so it only sizes a trial run of a third of the time on the production
        // path, whose rate sizes the measured runs: each then lasts about --seconds.
        const double probe_rate = double(kWarm) / warm_s;
        const std::uint64_t trial = std::max<std::uint64_t>(kWarm, std::uint64_t(probe_rate * set.seconds));
        const Timed t = run_tracer(scene, embree, comm, trial, 1, dir / "trial.h5", nullptr);
        photons = std::max<std::uint64_t>(kWarm, std::uint64_t(double(trial) / t.seconds * set.seconds));
    } else {
        photons = count_arg("--photons", set.photons);
    }
    // The replayed rays: those of the first photons the tracer runs trace (about the same
    // number of rays as a tracer run, so one replay takes about as long as the raw rate
    // allows for them).
    const std::uint64_t probe = set.probe == "auto" ? photons : count_arg("--probe-photons", set.probe);
    t0 = Clock::now();
    std::vector<RecordedRay> rays = record_tracer_rays(scene, embree, probe, scene.run.seed);
    std::vector<RecordedRay> cosine = make_cosine_rays(scene, embree, rays.size(), set.seed);
    const double t_gen = seconds_since(t0);
    // --floor: the floor tracer's own rays, recorded on one thread, replayed like the tracer's.
    const SurfaceTable surfaces(scene, embree);
    std::vector<RecordedRay> floor_rays;
    if (set.floor) {
        FloorTracer floor(scene, embree, surfaces, scene.run.seed);
        std::vector<std::uint32_t> counts(scene.triangle_count(), 0);
        floor.trace(0, photons, counts, &floor_rays);
    }
    sampler_kind(scene.run.sampler);  // refuses an unknown name
    std::printf("sampler %s\n", scene.run.sampler.c_str());
    std::printf("scene %s: %zu triangles, %zu lights, %zu detectors, max_bounces %d\n", set.scene_file.c_str(),
                scene.triangle_count(), scene.lights.lights().size(), scene.detectors.size(), scene.run.max_bounces);
    std::printf("load %.2f s, BVH build %.2f s; %llu photons per tracer run (seed %llu); replay: the %zu rays of "
                "its first %llu photons (%.3f rays/photon), recorded in %.2f s with the cosine rays\n",
                t_load, t_build, static_cast<unsigned long long>(photons),
                static_cast<unsigned long long>(scene.run.seed), rays.size(), static_cast<unsigned long long>(probe),
                rays_per_photon, t_gen);
    std::printf("%d repeats, medians [min..max]\n\n", set.repeats);

    MeasurePlan plan;
    plan.thread_counts = thread_counts;
    plan.repeats = set.repeats;
    plan.photons = photons;
    plan.packets = set.packets;
    plan.floor = set.floor;
    plan.verbose = set.verbose;
    plan.dir = dir;
    const std::size_t floor_ray_count = floor_rays.size();
    const Measurements m = measure(scene, embree, surfaces, comm,
                                   BenchRays{std::move(rays), std::move(cosine), std::move(floor_rays)}, plan);
    fs::remove_all(dir);
    print_report(m, plan, floor_ray_count);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);  // run_simulation reduces through it (one rank)
    CLI::App app{"tracer_bench: luxtrace run's ray rate against Embree alone on the same rays"};
    Settings set;
    app.add_option("scene", set.scene_file, "scene file (TOML)")->required();
    app.add_option("--threads-list", set.threads, "comma-separated thread counts")->capture_default_str();
    app.add_option("--photons", set.photons, "photons per tracer run, or auto")->capture_default_str();
    app.add_option("--probe-photons", set.probe, "photons whose rays are replayed, or auto (= --photons)")
        ->capture_default_str();
    app.add_option("--repeats", set.repeats, "measurements per thread count")->capture_default_str();
    app.add_option("--seconds", set.seconds, "auto: single-thread length of one measurement")->capture_default_str();
    app.add_option("--seed", set.seed, "seed of the cosine rays")->capture_default_str();
    app.add_flag("--verbose", set.verbose, "print every measurement");
    app.add_flag("--packets", set.packets, "also replay the rays through rtcIntersect8 in groups of 8");
    app.add_option("--sampler", set.sampler, "the tracer's sampler: random or sobol")->capture_default_str();
    app.add_flag("--floor", set.floor, "also time the floor: a minimal analog photon tracer, against its own rays");
    CLI11_PARSE(app, argc, argv);
    try {
        return run(set, comm);
    } catch (const InputError& e) {
        std::cerr << "tracer_bench: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "tracer_bench: error: " << e.what() << "\n";
        return 1;
    }
}
