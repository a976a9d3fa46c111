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
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/simulation.hpp"
#include "luxtrace/sampler/sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <embree3/rtcore.h>
#include <CLI/CLI.hpp>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

using namespace luxtrace;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the whole process: CPU / (wall x threads) well below 1 means other
// processes took the cores during a measurement.
double process_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The tracer's own rays: photons [0, n) traced by one PhotonTracer with recording on.
std::vector<RecordedRay> record_tracer_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                            std::uint64_t seed) {
    const TallyLayout layout(scene);
    TallyStore store(layout);
    std::vector<RecordedRay> rays;
    {
        const SurfaceTable surfaces(scene, embree);
        PhotonTracer tracer(scene, embree, surfaces, store.layout(),
                            PhotonSampler(sampler_kind(scene.run.sampler), seed));
        TallyBuffer buffer(store);
        tracer.record_rays(&rays);
        tracer.trace(0, n, buffer);
    }
    return rays;
}

// Rays leaving the surfaces as diffusely reflected photons would: an area-weighted
// triangle, a uniform point in it, a cosine direction about its normal (the baseline of
// the first version of this benchmark).
std::vector<RecordedRay> make_cosine_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                          std::uint64_t seed) {
    std::vector<double> cdf(scene.triangle_count());
    double sum = 0.0;
    for (std::size_t t = 0; t < cdf.size(); ++t) cdf[t] = (sum += scene.triangle_area_m2[t]);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<RecordedRay> rays(n);
    for (RecordedRay& r : rays) {
        const auto it = std::upper_bound(cdf.begin(), cdf.end(), uni(rng) * sum);
        const auto t = static_cast<unsigned>(
            std::min<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), cdf.size() - 1));
        const double s = std::sqrt(uni(rng)), u2 = uni(rng);
        const SurfacePoint sp = point_on_triangle(embree.local_vertex(scene.triangles[t].x),
                                                  embree.local_vertex(scene.triangles[t].y),
                                                  embree.local_vertex(scene.triangles[t].z), float(u2 * s),
                                                  float(s - u2 * s), embree.self_hit_margin(t));
        const Vec3& normal = scene.triangle_normal[t];
        const double d1 = uni(rng), d2 = uni(rng);
        r = {spawn_origin(sp, Vec3f(normal), embree.self_hit_margin(t)),
             Vec3f(sample_cosine_hemisphere(normal, d1, d2)), 0.0f};
    }
    return rays;
}

// The floor (--floor): what no analog photon tracer can leave out around Embree, and
// nothing more, to tell how far above Embree's own time any tracer of this kind must be
// on these scenes. Like the tracer it keeps 8 photons in flight per thread and draws
// their Philox blocks together; per photon one isotropic ray from the first light's
// position; per arrival one count on the triangle (a plain per-thread array), absorption
// with the band-0 reflectance of the triangle's material, a cosine direction about the
// normal on the incoming side, and the hit point moved off the surface by the triangle's
// margin. All float; no bands, detectors, odd/even maps, edge test or tally buffer.
class FloorTracer {
public:
    FloorTracer(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, std::uint64_t seed)
        : embree_(embree), surfaces_(surfaces), sampler_(seed),
          light_(embree.to_local(scene.lights.lights().front().emit(0.5, 0.5, 0.5, 0.5).origin)),
          max_bounces_(scene.run.max_bounces) {
        for (const Material& m : scene.materials) {
            const ScatterModel sm = scatter_model(m, 0);
            reflectance_.push_back(static_cast<float>(sm.diffuse_reflection + sm.specular_reflection));
        }
    }

    // Photons [first, last); returns the rays cast.
    std::uint64_t trace(std::uint64_t first, std::uint64_t last, std::vector<std::uint32_t>& counts,
                        std::vector<RecordedRay>* record) {
        struct P {
            std::uint64_t k = 0;
            std::uint32_t bounce = 0;
            Vec3f o, d;
            Hit hit;
        };
        constexpr int kN = PhotonTracer::kInFlight;
        constexpr std::uint64_t kDone = UINT64_MAX;
        P flight[kN];
        std::uint64_t ks[kN], next = first, rays = 0;
        std::uint32_t bs[kN];
        PhiloxSampler::Block u[kN];
        int fresh[kN], n_fresh = 0, active = 0;
        auto begin = [&](int i) {
            flight[i].k = next++;
            flight[i].bounce = 0;
            fresh[n_fresh++] = i;
        };
        // The photons started since the last draw take their block 0 together.
        auto emit_fresh = [&] {
            for (int j = 0; j < n_fresh; ++j) {
                ks[j] = flight[fresh[j]].k;
                bs[j] = 0;
            }
            sampler_.blocks(ks, bs, static_cast<std::size_t>(n_fresh), u);
            for (int j = 0; j < n_fresh; ++j) {
                P& p = flight[fresh[j]];
                const float z = 1.0f - 2.0f * to_float(u[j][0]), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
                const float phi = 6.2831853f * to_float(u[j][1]);
                p.o = light_;
                p.d = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
            }
            n_fresh = 0;
        };
        while (active < kN && next < last) begin(active++);
        emit_fresh();
        while (active > 0) {
            for (int i = 0; i < active; ++i) {
                P& p = flight[i];
                if (record != nullptr) record->push_back({p.o, p.d, 0.0f});
                p.hit = embree_.intersect_local(p.o, p.d);
                if (p.hit.found) __builtin_prefetch(&surfaces_.triangle(p.hit.triangle));
                ks[i] = p.k;
                bs[i] = 2 + p.bounce;
            }
            rays += static_cast<std::uint64_t>(active);
            sampler_.blocks(ks, bs, static_cast<std::size_t>(active), u);
            for (int i = 0; i < active; ++i) {
                P& p = flight[i];
                bool alive = p.hit.found;
                if (alive) {
                    ++counts[p.hit.triangle];
                    const TriangleRecord& t = surfaces_.triangle(p.hit.triangle);
                    alive = to_float(u[i][0]) < reflectance_[t.material] &&
                            ++p.bounce < static_cast<std::uint32_t>(max_bounces_);
                    if (alive) {
                        // Cosine direction in the frame of Frame::around (math.hpp), in float.
                        const Vec3f n = glm::dot(p.d, t.normal) < 0.0f ? t.normal : -t.normal;
                        const float r2 = to_float(u[i][1]), r = std::sqrt(r2), phi = 6.2831853f * to_float(u[i][2]);
                        const float sign = std::copysign(1.0f, n.z), a = -1.0f / (sign + n.z), b = n.x * n.y * a;
                        const Vec3f tx(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
                        const Vec3f ty(b, sign + n.y * n.y * a, -n.y);
                        // Off the surface by a few margins: not leak-proof like spawn_origin,
                        // and not meant to be; the floor's own rays are what it is timed against.
                        p.o = p.o + p.hit.t * p.d + 4.0f * t.margin * n;
                        p.d = r * std::cos(phi) * tx + r * std::sin(phi) * ty +
                              std::sqrt(std::max(0.0f, 1.0f - r2)) * n;
                    }
                }
                if (!alive) {
                    if (next < last) begin(i);
                    else p.k = kDone;
                }
            }
            emit_fresh();
            for (int i = 0; i < active;) {
                if (flight[i].k == kDone) flight[i] = flight[--active];
                else ++i;
            }
        }
        return rays;
    }

private:
    static float to_float(std::uint32_t w) { return (static_cast<float>(w >> 8) + 0.5f) * 0x1p-24f; }

    const EmbreeScene& embree_;
    const SurfaceTable& surfaces_;
    PhiloxSampler sampler_;
    Vec3f light_;
    int max_bounces_;
    std::vector<float> reflectance_;
};

struct Timed {
    double seconds = 0.0, cpu_seconds = 0.0;
    std::uint64_t rays = 0, hits = 0;
};

// Runs `worker` on `threads` threads (the calling one among them) and times the whole:
// wall and process CPU seconds.
template <class Worker>
Timed run_on_threads(int threads, const Worker& worker) {
    const auto t0 = Clock::now();
    const double c0 = process_cpu_seconds();
    {
        std::vector<std::jthread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
        worker();
    }
    return {seconds_since(t0), process_cpu_seconds() - c0, 0, 0};
}

// Runs `hits_in(first, last)` over every chunk of 1024 rays, `threads` threads taking
// chunks from one counter (as the tracer's threads take photons); times the whole.
template <class Chunk>
Timed on_threads(std::size_t rays, int threads, const Chunk& hits_in) {
    constexpr std::size_t kChunk = 1024;  // a multiple of 8, for the packets
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> hits{0};
    auto worker = [&] {
        std::uint64_t mine = 0;
        for (std::size_t first; (first = next.fetch_add(kChunk)) < rays;)
            mine += hits_in(first, std::min(rays, first + kChunk));
        hits += mine;
    };
    Timed t = run_on_threads(threads, worker);
    t.rays = rays;
    t.hits = hits.load();
    return t;
}

// rtcIntersect1 on every ray through EmbreeScene::intersect_local, the call the tracer
// makes (same context, same ray set-up).
Timed replay(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads) {
    return on_threads(rays.size(), threads, [&](std::size_t first, std::size_t last) {
        std::uint64_t hits = 0;
        for (std::size_t i = first; i < last; ++i)
            hits += embree.intersect_local(rays[i].origin, rays[i].direction, rays[i].t_near).found;
        return hits;
    });
}

// rtcIntersect8 on groups of 8 consecutive rays (the last group masked): the packet the
// tracer could form, since its consecutive calls come from its 8 photons in flight in
// turn. `--packets` only: an upper bound on what packets of those photons could give.
Timed replay_packets(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads) {
    const RTCScene handle = embree.handle();
    return on_threads(rays.size(), threads, [&](std::size_t first, std::size_t last) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        alignas(32) RTCRayHit8 rh;
        alignas(32) int valid[8];
        std::uint64_t hits = 0;
        for (std::size_t g = first; g < last; g += 8) {
            for (std::size_t k = 0; k < 8; ++k) {
                const bool on = g + k < last;
                valid[k] = on ? -1 : 0;
                const RecordedRay& r = rays[on ? g + k : g];
                rh.ray.org_x[k] = r.origin.x;
                rh.ray.org_y[k] = r.origin.y;
                rh.ray.org_z[k] = r.origin.z;
                rh.ray.dir_x[k] = r.direction.x;
                rh.ray.dir_y[k] = r.direction.y;
                rh.ray.dir_z[k] = r.direction.z;
                rh.ray.tnear[k] = r.t_near;
                rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
                rh.ray.time[k] = 0.0f;
                rh.ray.mask[k] = 0xFFFFFFFFu;
                rh.ray.id[k] = 0;
                rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, handle, &ctx, &rh);
            for (std::size_t k = 0; k < 8; ++k) hits += valid[k] != 0 && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        }
        return hits;
    });
}

// The floor tracer on `threads` threads taking chunks of photons from one counter; every
// thread keeps its own counts. `arrivals` gets the sum of all counts (the same for any
// thread count, as every photon's path depends only on its index).
Timed run_floor(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, std::uint64_t photons,
                int threads, std::uint64_t* arrivals) {
    constexpr std::uint64_t kChunk = 256;
    std::atomic<std::uint64_t> next{0}, rays{0}, counted{0};
    auto worker = [&] {
        FloorTracer floor(scene, embree, surfaces, scene.run.seed);
        std::vector<std::uint32_t> counts(scene.triangle_count(), 0);
        std::uint64_t mine = 0;
        for (std::uint64_t first; (first = next.fetch_add(kChunk)) < photons;)
            mine += floor.trace(first, std::min(photons, first + kChunk), counts, nullptr);
        rays += mine;
        std::uint64_t sum = 0;
        for (std::uint32_t c : counts) sum += c;
        counted += sum;
    };
    Timed t = run_on_threads(threads, worker);
    *arrivals = counted.load();
    t.rays = rays.load();
    return t;
}

// FNV-1a over every tally of a result: equal checksums mean identical counts.
std::uint64_t tally_checksum(const fs::path& result) {
    const ResultReader r(result);
    std::vector<std::string> names;
    for (const char* n : {"count_odd", "count_even", "direct_odd", "direct_even"})
        names.push_back(std::string("/global/") + n);
    for (const std::string& d : r.children("/detectors"))
        for (const char* n : {"count", "sumsq"}) names.push_back("/detectors/" + d + "/" + n);
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const std::string& n : names)
        for (std::uint64_t v : r.u64(n))
            for (int i = 0; i < 8; ++i) h = (h ^ ((v >> (8 * i)) & 0xFFu)) * 0x100000001b3ull;
    return h;
}

// The production path on `photons` photons and `threads` threads.
Timed run_tracer(const Scene& base, const EmbreeScene& embree, const Communicator& comm, std::uint64_t photons,
                 int threads, const fs::path& out, std::uint64_t* checksum) {
    Scene scene = base;
    scene.run.photons = photons;
    scene.run.targets.clear();  // a fixed budget: every run does the same work
    scene.run.time_limit_s = 0.0;
    scene.run.checkpoint_every_s = 0.0;
    scene.run.output = out.string();
    RunOptions opt;
    opt.threads = threads;
    opt.quiet = true;
    opt.embree = &embree;
    std::ostringstream sink;
    const double c0 = process_cpu_seconds();
    const auto t0 = Clock::now();
    const RunSummary s = run_simulation(scene, comm, opt, sink);
    const double wall = seconds_since(t0), cpu = process_cpu_seconds() - c0;
    if (s.failed || s.photons != photons) throw std::runtime_error("the tracer run failed: " + s.error);
    if (checksum != nullptr) *checksum = tally_checksum(out);
    // CPU share over the whole call (it includes writing the result, single-threaded).
    return {s.tracing_s, cpu * s.tracing_s / wall, s.rays, 0};
}

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

struct Series {
    std::vector<double> replay, cosine, tracer, paired, busy, packets;
    std::vector<double> floor, floor_replay, floor_paired;
};

int run(const Settings& set, const Communicator& comm) {
    const std::vector<int> thread_counts = parse_threads(set.threads);
    if (set.repeats < 1) throw InputError("--repeats: must be at least 1");
    if (!(set.seconds > 0.0)) throw InputError("--seconds: must be positive");
    if (set.photons != "auto") count_arg("--photons", set.photons);
    if (set.probe != "auto") count_arg("--probe-photons", set.probe);

    auto t0 = Clock::now();
    Scene scene = load_scene(set.scene_file);
    scene.run.sampler = set.sampler;  // the tracer's; sobol before the CLI offers it (issue 11)
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
        // path, whose rate sizes the measured runs. Sized by the probe alone they were a
        // third as long as --seconds, and a run's fixed costs weighed three times more.
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
    const std::vector<RecordedRay> rays = record_tracer_rays(scene, embree, probe, scene.run.seed);
    const std::vector<RecordedRay> cosine = make_cosine_rays(scene, embree, rays.size(), set.seed);
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

    std::vector<Series> series(thread_counts.size());
    std::uint64_t reference = 0, tracer_rays = 0;
    bool have_reference = false;
    for (int rep = 0; rep < set.repeats; ++rep)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
            const int threads = thread_counts[ti];
            Series& se = series[ti];
            const Timed r = replay(embree, rays, threads);
            const Timed c = replay(embree, cosine, threads);
            if (set.packets) {
                const Timed p = replay_packets(embree, rays, threads);
                if (p.hits != r.hits)
                    throw std::runtime_error("rtcIntersect8 and rtcIntersect1 disagree on the replayed rays");
                se.packets.push_back(double(p.rays) / p.seconds / (double(r.rays) / r.seconds));
            }
            if (set.floor) {
                const Timed fr = replay(embree, floor_rays, threads);
                std::uint64_t arrivals = 0;
                const Timed f = run_floor(scene, embree, surfaces, photons, threads, &arrivals);
                if (f.rays != floor_rays.size() || arrivals != fr.hits)
                    throw std::runtime_error("the floor tracer's rays differ between runs");
                se.floor.push_back(double(f.rays) / f.seconds);
                se.floor_replay.push_back(double(fr.rays) / fr.seconds);
                se.floor_paired.push_back(se.floor.back() / se.floor_replay.back());
            }
            std::uint64_t sum = 0;
            const Timed t = run_tracer(scene, embree, comm, photons, threads, dir / "bench.h5", &sum);
            se.replay.push_back(double(r.rays) / r.seconds);
            se.cosine.push_back(double(c.rays) / c.seconds);
            se.tracer.push_back(double(t.rays) / t.seconds);
            se.paired.push_back(se.tracer.back() / se.replay.back());
            se.busy.push_back(r.cpu_seconds / (r.seconds * threads));
            se.busy.push_back(t.cpu_seconds / (t.seconds * threads));
            if (set.verbose)
                std::printf("  repeat %d threads %d: replay %.3f, cosine %.3f, tracer %.3f Mrays/s (%.2f s)\n", rep,
                            threads, se.replay.back() * 1e-6, se.cosine.back() * 1e-6, se.tracer.back() * 1e-6,
                            t.seconds);
            if (!have_reference) {
                reference = sum;
                tracer_rays = t.rays;
                have_reference = true;
            } else if (sum != reference || t.rays != tracer_rays) {
                throw std::runtime_error("tracer tallies differ between runs with the same seed");
            }
        }
    fs::remove_all(dir);

    std::printf("tracer: %llu rays per run (%.3f per photon); tally checksum %016llx, identical in all %zu runs\n\n",
                static_cast<unsigned long long>(tracer_rays), double(tracer_rays) / double(photons),
                static_cast<unsigned long long>(reference), thread_counts.size() * set.repeats);
    // tracer/replay: ratio of the medians; paired: median of the ratios measured back to
    // back. busy: CPU / (wall x threads) of replay and tracer runs.
    std::printf("threads | replay Mrays/s          | cosine Mrays/s | tracer Mrays/s          | tracer/replay | paired "
                "| busy\n");
    std::printf("--------+-------------------------+----------------+-------------------------+---------------+--------"
                "+-----\n");
    auto lo = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
    auto hi = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
    for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
        const Series& se = series[ti];
        std::printf("%7d | %6.3f [%6.3f..%6.3f] | %14.3f | %6.3f [%6.3f..%6.3f] | %12.1f%% | %5.1f%% | %3.0f%%\n",
                    thread_counts[ti], median(se.replay) * 1e-6, lo(se.replay) * 1e-6, hi(se.replay) * 1e-6,
                    median(se.cosine) * 1e-6, median(se.tracer) * 1e-6, lo(se.tracer) * 1e-6, hi(se.tracer) * 1e-6,
                    100.0 * median(se.tracer) / median(se.replay), 100.0 * median(se.paired), 100.0 * median(se.busy));
    }
    if (set.packets)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti)
            std::printf("packets, %d thread(s): rtcIntersect8 on the same rays in groups of 8 consecutive ones: "
                        "%.1f%% of rtcIntersect1's rate (paired median; same hits)\n",
                        thread_counts[ti], 100.0 * median(series[ti].packets));
    if (set.floor)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
            const Series& se = series[ti];
            std::printf("floor, %d thread(s): %.3f Mrays/s (%.3f rays/photon), replay of its rays %.3f Mrays/s: "
                        "floor/replay %.1f%% (paired %.1f%%)\n",
                        thread_counts[ti], median(se.floor) * 1e-6, double(floor_rays.size()) / double(photons),
                        median(se.floor_replay) * 1e-6, 100.0 * median(se.floor) / median(se.floor_replay),
                        100.0 * median(se.floor_paired));
        }
    for (std::size_t i = 1; i < series.size(); ++i) {
        std::vector<double> tr, rp;
        for (int rep = 0; rep < set.repeats; ++rep) {
            tr.push_back(series[i].tracer[rep] / series[0].tracer[rep]);
            rp.push_back(series[i].replay[rep] / series[0].replay[rep]);
        }
        std::printf("speed-up %d/%d threads: tracer %.2fx (paired %.2fx), replay %.2fx (paired %.2fx)\n",
                    thread_counts[i], thread_counts[0], median(series[i].tracer) / median(series[0].tracer), median(tr),
                    median(series[i].replay) / median(series[0].replay), median(rp));
    }
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
