#include "replay.hpp"

#include <embree3/rtcore.h>

#include <limits>

namespace luxtrace::bench {

Timed replay(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads) {
    return on_threads(rays.size(), threads, [&](std::size_t first, std::size_t last) {
        std::uint64_t hits = 0;
        for (std::size_t i = first; i < last; ++i)
            hits += embree.intersect_local(rays[i].origin, rays[i].direction, rays[i].t_near).found;
        return hits;
    });
}

Timed replay_packets(const EmbreeScene& embree, const std::vector<RecordedRay>& rays, int threads) {
    const RTCScene handle = embree.handle();
    return on_threads(rays.size(), threads, [&](std::size_t first, std::size_t last) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        alignas(32) RTCRayHit8 rh;
        alignas(32) int valid[8];
        std::uint64_t hits = 0;
        for (std::size_t g = first; g < last; g += 8) {
            for (std::size_t k = 0; k < 8; ++k) {
                const bool on = g + k < last;
                valid[k] = on ? -1 : 0;
                const RecordedRay& r = rays[on ? g + k : g];
                rh.ray.org_x[k] = r.origin.x;
                rh.ray.org_y[k] = r.origin.y;
                rh.ray.org_z[k] = r.origin.z;
                rh.ray.dir_x[k] = r.direction.x;
                rh.ray.dir_y[k] = r.direction.y;
                rh.ray.dir_z[k] = r.direction.z;
                rh.ray.tnear[k] = r.t_near;
                rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
                rh.ray.time[k] = 0.0f;
                rh.ray.mask[k] = 0xFFFFFFFFu;
                rh.ray.id[k] = 0;
                rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, handle, &ctx, &rh);
            for (std::size_t k = 0; k < 8; ++k) hits += valid[k] != 0 && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
        }
        return hits;
    });
}

}  // namespace luxtrace::bench
