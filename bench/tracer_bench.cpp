// tracer_bench: how close the photon tracer comes to Embree's raw incoherent ray rate.
//
// In one run, on one scene and one EmbreeScene, for each repeat and thread count:
//   raw    - rtcIntersect1 on pre-generated rays that start at random points of the
//            scene's surfaces (area-weighted triangle, uniform point, offset by the
//            scene's ray epsilon along the normal) with cosine-distributed directions;
//   tracer - luxtrace::trace_photons over a photon budget; its rays are the
//            intersections it performed, recovered from the tallies (see count_rays).
// Raw and tracer measurements alternate, and so do the thread counts within each repeat,
// so that load from other processes on the machine hits all alike; medians over the
// repeats are reported.
// Every tracer run must give bit-identical tallies (same seed, any thread count).
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <CLI/CLI.hpp>
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

using namespace luxtrace;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU time of the whole process: CPU time / (wall time x threads) tells whether the
// threads really had their cores (other load on the machine shows as < 100%).
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

// A ray in the form Embree takes it (single precision).
struct RawRay {
    float org[3];
    float dir[3];
};

// Rays leaving the scene's surfaces the way diffusely reflected photons do.
std::vector<RawRay> make_surface_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n, std::uint64_t seed) {
    std::vector<double> cdf(scene.triangle_count());
    double sum = 0.0;
    for (std::size_t t = 0; t < cdf.size(); ++t) cdf[t] = (sum += scene.triangle_area_m2[t]);
    const double eps = scene.ray_epsilon_m();
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<RawRay> rays(n);
    for (RawRay& r : rays) {
        const auto it = std::upper_bound(cdf.begin(), cdf.end(), uni(rng) * sum);
        const std::size_t t = std::min<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), cdf.size() - 1);
        const glm::uvec3 tri = scene.triangles[t];
        const Vec3 a(scene.vertices[tri.x]), b(scene.vertices[tri.y]), c(scene.vertices[tri.z]);
        // Uniform point in the triangle: barycentrics (1 - sqrt(u1), u2 sqrt(u1)).
        const double s = std::sqrt(uni(rng)), u2 = uni(rng);
        const Vec3& normal = scene.triangle_normal[t];
        const Vec3 p = (1.0 - s) * a + (u2 * s) * b + (s - u2 * s) * c + eps * normal;
        const double d1 = uni(rng), d2 = uni(rng);
        const Vec3 d = sample_cosine_hemisphere(normal, d1, d2);
        const Vec3f pl = embree.to_local(p);  // Embree's frame
        r = {{pl.x, pl.y, pl.z}, {float(d.x), float(d.y), float(d.z)}};
    }
    return rays;
}

struct RawResult {
    double seconds = 0.0, cpu_seconds = 0.0;
    std::uint64_t hits = 0;
};

// rtcIntersect1 on every ray, `threads` threads taking chunks as the tracer does.
RawResult run_raw(const EmbreeScene& embree, const std::vector<RawRay>& rays, int threads) {
    constexpr std::size_t kChunk = 1024;
    const RTCScene handle = embree.handle();
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> hits{0};
    auto worker = [&] {
        std::uint64_t my_hits = 0;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);  // default flags: incoherent, as in EmbreeScene
        while (true) {
            const std::size_t first = next.fetch_add(kChunk);
            if (first >= rays.size()) break;
            const std::size_t last = std::min(rays.size(), first + kChunk);
            for (std::size_t i = first; i < last; ++i) {
                RTCRayHit rh;
                rh.ray.org_x = rays[i].org[0];
                rh.ray.org_y = rays[i].org[1];
                rh.ray.org_z = rays[i].org[2];
                rh.ray.dir_x = rays[i].dir[0];
                rh.ray.dir_y = rays[i].dir[1];
                rh.ray.dir_z = rays[i].dir[2];
                rh.ray.tnear = 0.0f;
                rh.ray.tfar = std::numeric_limits<float>::infinity();
                rh.ray.time = 0.0f;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.ray.id = 0;
                rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(handle, &ctx, &rh);
                my_hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
        }
        hits += my_hits;
    };
    const auto t0 = Clock::now();
    const double c0 = process_cpu_seconds();
    {
        std::vector<std::jthread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
        worker();
    }
    return {seconds_since(t0), process_cpu_seconds() - c0, hits.load()};
}

struct TracerResult {
    double seconds = 0.0, cpu_seconds = 0.0;
    std::uint64_t rays = 0, arrivals = 0, escaped = 0, absorbed = 0, truncated = 0;
    std::uint64_t checksum = 0;
};

// Intersections performed by the tracer, from its tallies. In PhotonTracer::trace each
// loop pass does one intersect: a hit adds 1 to count_odd or count_even of the hit
// triangle (then the photon scatters, is absorbed, or runs into max_bounces), a miss
// ends the photon as escaped. So rays = all surface arrivals + escaped photons.
void count_rays(const TallyStore& store, TracerResult& r) {
    const TallyLayout& L = store.layout();
    for (std::size_t t = 0; t < L.triangles(); ++t)
        for (std::size_t b = 0; b < L.bands(); ++b)
            r.arrivals += store[L.surface(t, b, TallyLayout::kCountOdd)] +
                          store[L.surface(t, b, TallyLayout::kCountEven)];
    r.escaped = store[L.counter(TallyLayout::kEscaped)];
    r.absorbed = store[L.counter(TallyLayout::kAbsorbed)];
    r.truncated = store[L.counter(TallyLayout::kTruncated)];
    r.rays = r.arrivals + r.escaped;
    // FNV-1a over all tallies: equal checksums across runs mean identical counts.
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::uint64_t v : store.data())
        for (int i = 0; i < 8; ++i) h = (h ^ ((v >> (8 * i)) & 0xFFu)) * 0x100000001b3ull;
    r.checksum = h;
}

TracerResult run_tracer(const Scene& scene, const EmbreeScene& embree, std::uint64_t photons,
                        int threads, std::uint64_t seed) {
    TallyStore store{TallyLayout(scene)};  // allocated and zeroed outside the timing
    TraceOptions opt;
    opt.seed = seed;
    opt.threads = threads;
    const auto t0 = Clock::now();
    const double c0 = process_cpu_seconds();
    trace_photons(scene, embree, store, 0, photons, opt);
    TracerResult r;
    r.seconds = seconds_since(t0);
    r.cpu_seconds = process_cpu_seconds() - c0;
    count_rays(store, r);
    if (r.escaped + r.absorbed + r.truncated != photons)
        throw std::runtime_error("photon fates do not add up to the photon budget");
    return r;
}

std::vector<int> parse_threads(const std::string& text) {
    std::vector<int> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        int v = 0;
        try { v = std::stoi(item); } catch (const std::exception&) { v = 0; }
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

struct Row {
    int threads = 0;
    double raw = 0.0, tracer = 0.0;  // median rays/s
    double paired = 0.0;             // median of tracer/raw within each repeat
    double busy = 0.0;               // median CPU time / (wall time x threads), both kinds
    double raw_lo = 0.0, raw_hi = 0.0, tracer_lo = 0.0, tracer_hi = 0.0;
};

struct Settings {
    std::string scene_file, threads = "1,2", photons = "auto", rays = "auto";
    int repeats = 5;
    double seconds = 1.5;  // auto sizing: length of one single-thread measurement
    std::uint64_t seed = 1;
    bool verbose = false;
};

// "auto": the count that makes one measurement at `rate` per second last `seconds`.
std::uint64_t size_for(const std::string& text, const char* opt, double rate, double seconds,
                       std::uint64_t lo) {
    if (text != "auto") return count_arg(opt, text);
    return std::max<std::uint64_t>(lo, static_cast<std::uint64_t>(rate * seconds));
}

int run(const Settings& set) {
    const std::vector<int> thread_counts = parse_threads(set.threads);
    if (set.repeats < 1) throw InputError("--repeats: must be at least 1");
    if (!(set.seconds > 0.0)) throw InputError("--seconds: must be positive");
    if (set.photons != "auto") count_arg("--photons", set.photons);  // fail before loading
    if (set.rays != "auto") count_arg("--rays", set.rays);
    const int repeats = set.repeats;
    const std::uint64_t seed = set.seed;
    const bool verbose = set.verbose;

    auto t0 = Clock::now();
    const Scene scene = load_scene(set.scene_file);
    const double t_load = seconds_since(t0);
    if (scene.triangle_count() == 0) throw InputError(set.scene_file + ": the scene has no triangles");
    t0 = Clock::now();
    const EmbreeScene embree(scene);
    const double t_build = seconds_since(t0);

    // Warm-up (pages in the BVH and the code paths) and, for "auto", rate estimates.
    constexpr std::uint64_t kProbeRays = 200000, kProbePhotons = 50000;
    const RawResult probe_raw = run_raw(embree, make_surface_rays(scene, embree, kProbeRays, seed + 1), 1);
    const TracerResult probe_tr = run_tracer(scene, embree, kProbePhotons, 1, seed + 1);
    const std::uint64_t n_rays =
        size_for(set.rays, "--rays", double(kProbeRays) / probe_raw.seconds, set.seconds, 100000);
    const std::uint64_t photons =
        size_for(set.photons, "--photons", double(kProbePhotons) / probe_tr.seconds, set.seconds, 10000);

    t0 = Clock::now();
    const std::vector<RawRay> rays = make_surface_rays(scene, embree, n_rays, seed);
    const double t_gen = seconds_since(t0);
    std::printf("scene %s: %zu triangles, %zu lights, %zu detectors, max_bounces %d\n",
                set.scene_file.c_str(), scene.triangle_count(), scene.lights.lights().size(),
                scene.detectors.size(), scene.run.max_bounces);
    std::printf("load %.2f s, BVH build %.2f s, %llu raw rays pre-generated in %.2f s\n", t_load, t_build,
                static_cast<unsigned long long>(n_rays), t_gen);
    std::printf("photons %llu per tracer run, seed %llu, %d repeats, medians [min..max]\n\n",
                static_cast<unsigned long long>(photons), static_cast<unsigned long long>(seed), repeats);

    // Per thread count, one entry per repeat. Repeats are the outer loop, so every thread
    // count is measured in each stretch of time and the speed-ups can be paired too.
    struct Series { std::vector<double> raw, tracer, paired, busy; };
    std::vector<Series> series(thread_counts.size());
    TracerResult reference;
    bool have_reference = false;
    std::uint64_t raw_hits = 0;
    for (int rep = 0; rep < repeats; ++rep)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
            const int threads = thread_counts[ti];
            Series& se = series[ti];
            const RawResult raw = run_raw(embree, rays, threads);
            const TracerResult tr = run_tracer(scene, embree, photons, threads, seed);
            raw_hits = raw.hits;
            se.raw.push_back(static_cast<double>(n_rays) / raw.seconds);
            se.tracer.push_back(static_cast<double>(tr.rays) / tr.seconds);
            se.paired.push_back(se.tracer.back() / se.raw.back());
            se.busy.push_back(raw.cpu_seconds / (raw.seconds * threads));
            se.busy.push_back(tr.cpu_seconds / (tr.seconds * threads));
            if (verbose)
                std::printf("  repeat %d threads %d: raw %.3f Mrays/s (%.2f s, busy %.0f%%), "
                            "tracer %.3f Mrays/s (%.2f s, busy %.0f%%)\n",
                            rep, threads, se.raw.back() * 1e-6, raw.seconds, 100.0 * se.busy[se.busy.size() - 2],
                            se.tracer.back() * 1e-6, tr.seconds, 100.0 * se.busy.back());
            if (!have_reference) {
                reference = tr;
                have_reference = true;
            } else if (tr.checksum != reference.checksum || tr.rays != reference.rays) {
                throw std::runtime_error("tracer tallies differ between runs with the same seed");
            }
        }
    std::vector<Row> rows;
    for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
        const Series& se = series[ti];
        Row row;
        row.threads = thread_counts[ti];
        row.raw = median(se.raw);
        row.tracer = median(se.tracer);
        row.paired = median(se.paired);
        row.busy = median(se.busy);
        row.raw_lo = *std::min_element(se.raw.begin(), se.raw.end());
        row.raw_hi = *std::max_element(se.raw.begin(), se.raw.end());
        row.tracer_lo = *std::min_element(se.tracer.begin(), se.tracer.end());
        row.tracer_hi = *std::max_element(se.tracer.begin(), se.tracer.end());
        rows.push_back(row);
    }

    const double ph = static_cast<double>(photons);
    std::printf("raw rays: %.1f%% hit a surface\n", 100.0 * double(raw_hits) / double(n_rays));
    std::printf("tracer rays: %llu = %llu surface arrivals + %llu escaped; %.3f rays/photon; "
                "fates: escaped %.1f%%, absorbed %.1f%%, truncated %.1f%%\n",
                static_cast<unsigned long long>(reference.rays), static_cast<unsigned long long>(reference.arrivals),
                static_cast<unsigned long long>(reference.escaped), double(reference.rays) / ph,
                100.0 * double(reference.escaped) / ph, 100.0 * double(reference.absorbed) / ph,
                100.0 * double(reference.truncated) / ph);
    std::printf("tally checksum %016llx (identical in all %zu tracer runs)\n\n",
                static_cast<unsigned long long>(reference.checksum), thread_counts.size() * repeats);
    // tracer/raw: ratio of the medians; paired: median over repeats of the ratio of the
    // two adjacent measurements, less sensitive to other load on the machine. busy: CPU
    // time / (wall x threads); well below 100% means other processes took the cores.
    std::printf("threads | raw Mrays/s            | tracer Mrays/s         | tracer/raw | paired | busy\n");
    std::printf("--------+------------------------+------------------------+------------+--------+-----\n");
    for (const Row& r : rows)
        std::printf("%7d | %6.3f [%6.3f..%6.3f] | %6.3f [%6.3f..%6.3f] | %9.1f%% | %5.1f%% | %3.0f%%\n",
                    r.threads, r.raw * 1e-6, r.raw_lo * 1e-6, r.raw_hi * 1e-6, r.tracer * 1e-6,
                    r.tracer_lo * 1e-6, r.tracer_hi * 1e-6, 100.0 * r.tracer / r.raw, 100.0 * r.paired,
                    100.0 * r.busy);
    // Speed-ups relative to the first thread count given (1 by default): ratio of the
    // medians, and paired (median over repeats of the ratio within the same repeat).
    for (std::size_t i = 1; i < rows.size(); ++i) {
        std::vector<double> tr_pair, raw_pair;
        for (int rep = 0; rep < repeats; ++rep) {
            tr_pair.push_back(series[i].tracer[rep] / series[0].tracer[rep]);
            raw_pair.push_back(series[i].raw[rep] / series[0].raw[rep]);
        }
        std::printf("speed-up %d/%d threads: tracer %.2fx (paired %.2fx), raw %.2fx (paired %.2fx)\n",
                    rows[i].threads, rows[0].threads, rows[i].tracer / rows[0].tracer, median(tr_pair),
                    rows[i].raw / rows[0].raw, median(raw_pair));
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tracer_bench: photon tracer ray rate vs raw Embree incoherent ray rate"};
    Settings set;
    app.add_option("scene", set.scene_file, "scene file (TOML)")->required();
    app.add_option("--threads-list", set.threads, "comma-separated thread counts")->capture_default_str();
    app.add_option("--photons", set.photons, "photons per tracer run, or auto")->capture_default_str();
    app.add_option("--rays", set.rays, "pre-generated raw rays per raw run, or auto")->capture_default_str();
    app.add_option("--repeats", set.repeats, "measurements per thread count")->capture_default_str();
    app.add_option("--seconds", set.seconds, "auto: single-thread length of one measurement")
        ->capture_default_str();
    app.add_option("--seed", set.seed, "seed of the tracer and of the raw rays")->capture_default_str();
    app.add_flag("--verbose", set.verbose, "print every measurement");
    CLI11_PARSE(app, argc, argv);
    try {
        return run(set);
    } catch (const InputError& e) {
        std::cerr << "tracer_bench: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "tracer_bench: error: " << e.what() << "\n";
        return 1;
    }
}
