#pragma once
// The photon path: light (emit) -> Embree (intersect) -> material (scatter) -> tallies.
//
// Random dimensions of photon k, always in this order, so that a quasi-random sampler
// sees the same dimension for the same decision:
//   0 light, 1 band, 2-3 emission position, 4-5 emission direction,
//   6+3b, 7+3b, 8+3b: event and direction at the b-th surface arrival.
#include "luxtrace/core/math.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/ray_offset.hpp"

#include <cstdint>
#include <vector>

namespace luxtrace {

struct Scene;
class EmbreeScene;
class Sampler;

// A ray as the tracer hands it to Embree (local float coordinates), for benchmarks that
// replay exactly the tracer's rays through Embree alone.
struct RecordedRay {
    Vec3f origin, direction;
    float t_near = 0.0f;
};

class PhotonTracer {
public:
    PhotonTracer(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout);
    // Trace photon k and add its contributions to `out`.
    void trace(std::uint64_t k, Sampler& sampler, TallyBuffer& out);
    // Append every ray traced from now on to `sink` (null: stop recording).
    void record_rays(std::vector<RecordedRay>* sink) { record_ = sink; }

private:
    struct Registration { std::size_t index; std::uint32_t detector; };
    void finish_photon(TallyBuffer& out);
    void check_luminance(const Vec3& p, const Vec3& d, int band);
    SurfacePoint surface_point(unsigned triangle, float u, float v) const;

    const Scene& scene_;
    const EmbreeScene& embree_;
    const TallyLayout& layout_;
    std::vector<std::uint32_t> illuminance_dets_, luminance_dets_;
    std::vector<Registration> regs_;  // this photon's detector registrations
    std::vector<RecordedRay>* record_ = nullptr;
};

}  // namespace luxtrace
