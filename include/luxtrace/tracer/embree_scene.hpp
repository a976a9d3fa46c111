#pragma once
// The rank's one Embree BVH over all scene triangles (geometry 0, primID = triangle).
#include "luxtrace/core/math.hpp"

#include <embree3/rtcore.h>

#include <limits>

namespace luxtrace {

struct Scene;

struct Hit {
    bool found = false;
    float t = std::numeric_limits<float>::infinity();
    unsigned triangle = 0;
};

class EmbreeScene {
public:
    explicit EmbreeScene(const Scene& scene);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest hit of the ray o + t d, t in [t_near, t_far). Thread-safe.
    Hit intersect(const Vec3& o, const Vec3& d, float t_near = 0.0f,
                  float t_far = std::numeric_limits<float>::infinity()) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        rh.ray.org_x = static_cast<float>(o.x);
        rh.ray.org_y = static_cast<float>(o.y);
        rh.ray.org_z = static_cast<float>(o.z);
        rh.ray.dir_x = static_cast<float>(d.x);
        rh.ray.dir_y = static_cast<float>(d.y);
        rh.ray.dir_z = static_cast<float>(d.z);
        rh.ray.tnear = t_near;
        rh.ray.tfar = t_far;
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &ctx, &rh);
        Hit h;
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            h.found = true;
            h.t = rh.ray.tfar;
            h.triangle = rh.hit.primID;
        }
        return h;
    }
    RTCScene handle() const { return scene_; }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

}  // namespace luxtrace
