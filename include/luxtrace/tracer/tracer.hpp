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

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
class EmbreeScene;
class Sampler;

class PhotonTracer {
public:
    PhotonTracer(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout);
    // Trace photon k and add its contributions to `out`.
    void trace(std::uint64_t k, Sampler& sampler, TallyBuffer& out);

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
};

struct TraceOptions {
    std::uint64_t seed = 1;
    std::string sampler = "random";
    int threads = 1;
    std::uint64_t chunk = 1024;  // photons a thread takes at a time
};

// Trace photons [begin, end) with `threads` threads into `store`. `done` (optional) is
// advanced as chunks finish, for progress reports from another thread.
void trace_photons(const Scene& scene, const EmbreeScene& embree, TallyStore& store,
                   std::uint64_t begin, std::uint64_t end, const TraceOptions& opt,
                   std::atomic<std::uint64_t>* done = nullptr);

}  // namespace luxtrace
