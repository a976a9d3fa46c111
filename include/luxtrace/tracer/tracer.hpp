#pragma once
// The photon path: light (emit) -> Embree (intersect) -> filters (detectors, the surface
// map) -> material (scatter), and the scorer (tally/photon_tally.hpp) commits what the
// filters registered.
//
// Random numbers of photon k come in Philox blocks of four (philox_sampler.hpp), one block per
// group of decisions, always the same block for the same decision:
//   block 0: light, band, emission direction (2);
//   block 1: emission position (2), drawn by area and directional lights only;
//   block 2 + b: event and direction (2) at the b-th surface arrival.
// This is photon layout kPhotonLayout, stored in results; a restart refuses another.
//
// A thread keeps several photons in flight: their rays are intersected one after the
// other, then the records of the triangles they hit are fetched together and each photon
// takes its next step, so the memory latencies of one photon overlap the work of the
// others. Photons never interact, and tallies are integer sums, so the order in which
// their steps are taken changes no count.
#include "luxtrace/core/math.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/tally/photon_tally.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/detector_filters.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/ray_offset.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"
#include "luxtrace/tracer/surface_table.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace luxtrace {

struct Scene;

// The random-number layout above, stored in results and checked on restart.
inline constexpr std::uint64_t kPhotonLayout = 2;

// A ray as the tracer hands it to Embree (local float coordinates), for benchmarks that
// replay exactly the tracer's rays through Embree alone.
struct RecordedRay {
    Vec3f origin, direction;
    float t_near = 0.0f;
};

class PhotonTracer {
public:
    PhotonTracer(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, const TallyLayout& layout,
                 PhotonSampler sampler);
    // Trace photons [first, last) and add their contributions to `out`.
    void trace(std::uint64_t first, std::uint64_t last, TallyBuffer& out);
    // The same, appending every ray it hands to Embree to `rays` (the benchmarks' replays):
    // a loop of its own, so that trace() tests nothing per ray for it.
    void trace_recording(std::uint64_t first, std::uint64_t last, TallyBuffer& out, std::vector<RecordedRay>& rays);

    static constexpr int kInFlight = 8;

private:
    struct Photon {
        std::uint64_t k = 0;
        int band = 0;
        int bounce = 0;
        // Still on the straight line from its light: no event has turned it (going
        // straight through glazing does not), so its arrivals count as direct light.
        bool direct = true;
        // Its last event was a diffuse reflection, or that and then panes the gather passes
        // (at most `kGatherPanes` of them): its light at a gathered grid is the gather's.
        bool after_diffuse = false;
        int panes = 0;
        Vec3f origin;
        Vec3 direction;
        Hit hit;
        PhotonTally tally;
    };
    // Start photon k with its block 0; false if it ended at once (a portal photon whose
    // way back to the sky is blocked).
    bool start(Photon& p, std::uint64_t k, const PhotonSampler::Block& b0, TallyBuffer& out);
    // Start photons next, next + 1, ... in slot p until one does not end at once; false
    // when none is left before `last`.
    bool launch(Photon& p, std::uint64_t& next, std::uint64_t last, TallyBuffer& out);
    // A portal photon: whether its ray back out to the sky is clear (else it has ended).
    bool sees_sky(Photon& p, TallyBuffer& out);
    // Block b (0: the start; 1: the start position) of photon k, drawn with those of the
    // next kBatch - 1 photons.
    struct BlockBatch {
        std::array<PhotonSampler::Block, PhiloxSampler::kBatch> blocks{};
        std::uint64_t base = UINT64_MAX;  // photon of blocks[0]
    };
    const PhotonSampler::Block& batched_block(BlockBatch& batch, std::uint64_t k, std::uint32_t b);
    const PhotonSampler::Block& start_block(std::uint64_t k) { return batched_block(start_batch_, k, 0); }
    // The loop of both trace()s: photons in flight until [first, last) is done, and
    // `see_ray(origin, direction)` called before each ray is intersected.
    template <class SeeRay>
    void fly(std::uint64_t first, std::uint64_t last, TallyBuffer& out, SeeRay see_ray);
    // One step after the photon's ray was intersected, with the block of its arrival;
    // false once the photon has ended.
    bool step(Photon& p, const PhotonSampler::Block& u, TallyBuffer& out);
    // The photon leaves `point` (scene coordinates) along its direction.
    void depart(Photon& p, const Vec3& point);
    void end(Photon& p, TallyLayout::Counter fate, TallyBuffer& out) { p.tally.end(layout_, fate, out); }
    // The arrival's light gathered to the sensors that see its site (gather_table.hpp); and
    // after event `e` (on a pane or not), whether the photon's light is the gather's.
    // (Each arrival also counts at its site: the surfaces' irradiance for the gather's own
    // error, GatherTable::rays_rel_var.)
    void gather(Photon& p, bool front, TallyBuffer& out) {
        const std::size_t site = gather_.site(p.hit.triangle, front ? 0 : 1, p.hit.u, p.hit.v);
        p.tally.gather(gather_.entries(site), gather_.slots());
        out.add(layout_.gather_site(site), 1);
    }
    static void follow_event(Photon& p, ScatterEvent e, bool pane);

    const Scene& scene_;
    const EmbreeScene& embree_;
    const SurfaceTable& surfaces_;
    const TallyLayout& layout_;
    PhotonSampler sampler_;
    DetectorFilters detectors_;
    std::array<Photon, kInFlight> flight_;
    static_assert(kInFlight <= static_cast<int>(PhiloxSampler::kBatch));
    BlockBatch start_batch_, position_batch_;
    // Every light draws a start position (area lights, beams, luminous openings): block 1
    // is then drawn in batches too; otherwise one at a time, for the photons that need it.
    bool all_positioned_ = false;
    const GatherTable& gather_;
};

}  // namespace luxtrace
