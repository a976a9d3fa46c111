#include "tracer_run.hpp"

#include "luxtrace/io/result_data.hpp"
#include "luxtrace/run/simulation.hpp"

#include <sstream>
#include <stdexcept>

namespace luxtrace::bench {

namespace fs = std::filesystem;

std::uint64_t tally_checksum(const fs::path& result) {
    const ResultFile r(result);
    const SurfaceCounts s = r.surface_counts();
    std::vector<const std::vector<std::uint64_t>*> tallies{&s.count_odd, &s.count_even, &s.direct_odd, &s.direct_even};
    std::vector<DetectorData> detectors;
    for (const std::string& d : r.detector_names()) detectors.push_back(r.detector(d));
    for (const DetectorData& d : detectors) tallies.insert(tallies.end(), {&d.count, &d.sumsq});
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const std::vector<std::uint64_t>* t : tallies)
        for (std::uint64_t v : *t)
            for (int i = 0; i < 8; ++i) h = (h ^ ((v >> (8 * i)) & 0xFFu)) * 0x100000001b3ull;
    return h;
}

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
    const RunSummary s = run_simulation(scene, comm, opt, sink);
    if (s.failed || s.photons != photons) throw std::runtime_error("the tracer run failed: " + s.error);
    if (checksum != nullptr) *checksum = tally_checksum(out);
    // The tracing threads' own CPU share (the result's write, single-threaded, is not theirs).
    return {s.tracing_s, s.tracing_busy * s.tracing_s * threads, s.rays, 0};
}

}  // namespace luxtrace::bench
