#pragma once
// Embree alone on recorded rays, on the same BVH and threads as the tracer.
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/tracer.hpp"
#include "timing.hpp"

#include <vector>

namespace luxtrace::bench {

// rtcIntersect1 on every ray through EmbreeScene::intersect_local, the call the tracer
// makes (same context, same ray set-up).
Timed replay(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads);

// rtcIntersect8 on groups of 8 consecutive rays (the last group masked): the packet the
// tracer could form, since its consecutive calls come from its 8 photons in flight in
// turn. `--packets` only: an upper bound on what packets of those photons could give.
Timed replay_packets(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads);

}  // namespace luxtrace::bench
