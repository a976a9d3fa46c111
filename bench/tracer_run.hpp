#pragma once
// Runs of the production path: run_simulation, the code `luxtrace run` runs.
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "timing.hpp"

#include <cstdint>
#include <filesystem>

namespace luxtrace::bench {

// FNV-1a over every tally of a result: equal checksums mean identical counts.
std::uint64_t tally_checksum(const std::filesystem::path& result);

// The production path on `photons` photons and `threads` threads, writing `out`: the
// work plan, the pausable worker pool, snapshots and reductions at the scene's period, on
// `embree`. Its rays are the intersections it made (arrivals + escapes), its time that of
// its tracing threads (the result file is written after). With `checksum`, the result's
// tally_checksum.
Timed run_tracer(const Scene& base, const EmbreeScene& embree, const Communicator& comm, std::uint64_t photons,
                 int threads, const std::filesystem::path& out, std::uint64_t* checksum);

}  // namespace luxtrace::bench
