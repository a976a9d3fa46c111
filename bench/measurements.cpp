#include "measurements.hpp"

#include "floor_tracer.hpp"
#include "replay.hpp"
#include "tracer_run.hpp"

#include <cstdio>
#include <stdexcept>

namespace luxtrace::bench {

Measurements measure(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces,
                     const Communicator& comm, const BenchRays& bench_rays, const MeasurePlan& plan) {
    const std::vector<int>& thread_counts = plan.thread_counts;
    const std::vector<RecordedRay>&rays = bench_rays.tracer, &cosine = bench_rays.cosine,
          &floor_rays = bench_rays.floor;
    const std::uint64_t photons = plan.photons;
    std::vector<Series> series(thread_counts.size());
    std::uint64_t reference = 0, tracer_rays = 0;
    bool have_reference = false;
    for (int rep = 0; rep < plan.repeats; ++rep)
        for (std::size_t ti = 0; ti < thread_counts.size(); ++ti) {
            const int threads = thread_counts[ti];
            Series& se = series[ti];
            const Timed r = replay(embree, rays, threads);
            const Timed c = replay(embree, cosine, threads);
            if (plan.packets) {
                const Timed p = replay_packets(embree, rays, threads);
                if (p.hits != r.hits)
                    throw std::runtime_error("rtcIntersect8 and rtcIntersect1 disagree on the replayed rays");
                se.packets.push_back(double(p.rays) / p.seconds / (double(r.rays) / r.seconds));
            }
            if (plan.floor) {
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
            const Timed t = run_tracer(scene, embree, comm, photons, threads, plan.dir / "bench.h5", &sum);
            se.replay.push_back(double(r.rays) / r.seconds);
            se.cosine.push_back(double(c.rays) / c.seconds);
            se.tracer.push_back(double(t.rays) / t.seconds);
            se.paired.push_back(se.tracer.back() / se.replay.back());
            se.busy.push_back(r.cpu_seconds / (r.seconds * threads));
            se.busy.push_back(t.cpu_seconds / (t.seconds * threads));
            if (plan.verbose)
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
    return {std::move(series), reference, tracer_rays};
}

}  // namespace luxtrace::bench
