#pragma once
// The rank's one Embree BVH over all scene triangles (geometry 0, primID = triangle).
//
// Embree works in float. Its coordinates are relative to the centre of the scene's
// bounding box ("local"), so a model placed kilometres from the scene origin (a site in
// national grid coordinates) is intersected with the precision it would have at the
// origin. The photon tracer works in local float coordinates throughout; callers in
// scene coordinates use intersect(), which converts.
#include "luxtrace/core/math.hpp"

#include <embree3/rtcore.h>

#include <cstddef>
#include <limits>
#include <vector>

namespace luxtrace {

struct Scene;

// Embree's build settings. docs/SCALING.md "Setup time of ten million triangles" measures
// each against the build time and the photon rate it gives.
struct BvhOptions {
    // Scenes of this many triangles or more are built at RTC_BUILD_QUALITY_MEDIUM by "auto":
    // there HIGH's spatial splits take seconds and give the rays nothing; LOW's faster build
    // costs 10-15 % of the photon rate, more than it saves once tracing lasts about 15 s
    // (docs/SCALING.md, "Setup time of ten million triangles").
    static constexpr std::size_t kMediumBvhTriangles = std::size_t{1} << 22;
    // The options of the scene's [run] bvh_quality.
    static BvhOptions of(const Scene& scene);

    RTCBuildQuality quality = RTC_BUILD_QUALITY_HIGH;
    // Used by Embree only under RTC_BUILD_QUALITY_LOW, which builds two levels: a BVH over
    // the geometry's triangles at this quality, under a top level over the geometries.
    RTCBuildQuality geometry_quality = RTC_BUILD_QUALITY_MEDIUM;
    bool compact = false;  // RTC_SCENE_FLAG_COMPACT: a smaller BVH (indexed leaves)
};

struct Hit {
    bool found = false;
    float t = std::numeric_limits<float>::infinity();
    unsigned triangle = 0;
    float u = 0.0f, v = 0.0f;  // barycentrics: p = (1 - u - v) p0 + u p1 + v p2
};

class EmbreeScene {
public:
    // `scene` must outlive the EmbreeScene: Embree reads its triangles in place. Built with
    // BvhOptions::of(scene) unless given options.
    explicit EmbreeScene(const Scene& scene);
    EmbreeScene(const Scene& scene, const BvhOptions& options);
    ~EmbreeScene();
    // Wall time the construction took (buffers and BVH build), for the result's report.
    double build_s() const { return build_s_; }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Conversions between scene coordinates and Embree's local frame.
    Vec3f to_local(const Vec3& p) const { return Vec3f(p - origin_); }
    Vec3 to_scene(const Vec3f& p) const { return Vec3(p) + origin_; }
    // Vertex v in local coordinates (Embree's own buffer).
    const Vec3f& local_vertex(unsigned v) const { return vertices_[v]; }
    // How far off its plane a ray leaving the triangle must start (ray_offset.hpp).
    float self_hit_margin(unsigned triangle) const { return margin_[triangle]; }

    // Closest hit of the local ray o + t d, t in [t_near, t_far). Thread-safe.
    Hit intersect_local(const Vec3f& o, const Vec3f& d, float t_near = 0.0f,
                        float t_far = std::numeric_limits<float>::infinity()) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        rh.ray.org_x = o.x;
        rh.ray.org_y = o.y;
        rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
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
            h.u = rh.hit.u;
            h.v = rh.hit.v;
        }
        return h;
    }
    // The same for a ray in scene coordinates (t is the same in both).
    Hit intersect(const Vec3& o, const Vec3& d, float t_near = 0.0f,
                  float t_far = std::numeric_limits<float>::infinity()) const {
        return intersect_local(to_local(o), Vec3f(d), t_near, t_far);
    }
    // Any hit of the ray o + t d (scene coordinates), t in [0, t_far).
    bool occluded(const Vec3& o, const Vec3& d, float t_far) const {
        return occluded_local(to_local(o), Vec3f(d), t_far);
    }
    // The same in local coordinates, from t_near on.
    bool occluded_local(const Vec3f& lo, const Vec3f& d, float t_far = std::numeric_limits<float>::infinity(),
                        float t_near = 0.0f) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay ray;
        ray.org_x = lo.x;
        ray.org_y = lo.y;
        ray.org_z = lo.z;
        ray.dir_x = d.x;
        ray.dir_y = d.y;
        ray.dir_z = d.z;
        ray.tnear = t_near;
        ray.tfar = t_far;
        ray.time = 0.0f;
        ray.mask = 0xFFFFFFFFu;
        ray.id = 0;
        ray.flags = 0;
        rtcOccluded1(scene_, &ctx, &ray);
        return ray.tfar < 0.0f;  // Embree marks a found occluder with tfar = -inf
    }
    RTCScene handle() const { return scene_; }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    Vec3 origin_{0.0};
    double build_s_ = 0.0;
    const Vec3f* vertices_ = nullptr;
    std::vector<float> margin_;
};

}  // namespace luxtrace
