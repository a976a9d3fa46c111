#pragma once
// The floor (--floor): what no analog photon tracer can leave out around Embree, and
// nothing more, to tell how far above Embree's own time any tracer of this kind must be
// on these scenes. Like the tracer it keeps 8 photons in flight per thread and draws
// their Philox blocks together; per photon one isotropic ray from the first light's
// position; per arrival one count on the triangle (a plain per-thread array), absorption
// with the band-0 reflectance of the triangle's material, a cosine direction about the
// normal on the incoming side, and the hit point moved off the surface by the triangle's
// margin. All float; no bands, detectors, odd/even maps, edge test or tally buffer.
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"
#include "luxtrace/tracer/tracer.hpp"
#include "timing.hpp"

#include <cstdint>
#include <vector>

namespace luxtrace::bench {

class FloorTracer {
public:
    FloorTracer(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, std::uint64_t seed);

    // Photons [first, last); returns the rays cast.
    std::uint64_t trace(std::uint64_t first, std::uint64_t last, std::vector<std::uint32_t>& counts,
                        std::vector<RecordedRay>* record);

private:
    static float to_float(std::uint32_t w) { return (static_cast<float>(w >> 8) + 0.5f) * 0x1p-24f; }

    const EmbreeScene& embree_;
    const SurfaceTable& surfaces_;
    PhiloxSampler sampler_;
    Vec3f light_;
    int max_bounces_;
    std::vector<float> reflectance_;
};

// The floor tracer on `threads` threads taking chunks of photons from one counter; every
// thread keeps its own counts. `arrivals` gets the sum of all counts (the same for any
// thread count, as every photon's path depends only on its index).
Timed run_floor(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, std::uint64_t photons,
                int threads, std::uint64_t* arrivals);

}  // namespace luxtrace::bench
