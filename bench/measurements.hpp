#pragma once
// The timed runs: for each repeat and thread count, back to back, the replay of the
// tracer's rays, the cosine rays, optionally the packets and the floor, then a tracer run;
// so that other load hits all alike. Paired ratios are taken from runs measured back to
// back. Every tracer run with the same seed must give bit-identical tallies whatever the
// thread count.
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace luxtrace::bench {

// One thread count's measurements, one entry per repeat (rays/s; ratios as fractions).
struct Series {
    std::vector<double> replay, cosine, tracer, paired, busy, packets;
    std::vector<double> floor, floor_replay, floor_paired;
};

struct MeasurePlan {
    std::vector<int> thread_counts;
    int repeats = 1;
    std::uint64_t photons = 0;  // per tracer and floor run
    bool packets = false, floor = false, verbose = false;
    std::filesystem::path dir;  // where the tracer runs write their results
};

// The rays measured: the tracer's recorded rays, the cosine rays, the floor's own rays.
struct BenchRays {
    std::vector<RecordedRay> tracer, cosine, floor;
};

struct Measurements {
    std::vector<Series> series;        // per thread count
    std::uint64_t tally_checksum = 0;  // of every tracer run (they are checked equal)
    std::uint64_t tracer_rays = 0;     // per tracer run
};

// Throws std::runtime_error when runs that must agree do not (tallies, hits, rays).
Measurements measure(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces,
                     const Communicator& comm, const BenchRays& rays, const MeasurePlan& plan);

}  // namespace luxtrace::bench
