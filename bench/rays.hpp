#pragma once
// The rays the bench replays through Embree alone, prepared from the scene.
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/tracer.hpp"

#include <cstdint>
#include <vector>

namespace luxtrace::bench {

// The tracer's own rays: photons [0, n) traced by one PhotonTracer with recording on.
std::vector<RecordedRay> record_tracer_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                            std::uint64_t seed);

// Rays leaving the surfaces as diffusely reflected photons would: an area-weighted
// triangle, a uniform point in it, a cosine direction about its normal (the baseline of
// the first version of this benchmark).
std::vector<RecordedRay> make_cosine_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                          std::uint64_t seed);

}  // namespace luxtrace::bench
