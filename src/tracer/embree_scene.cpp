#include "luxtrace/tracer/embree_scene.hpp"

#include "luxtrace/core/parallel.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/ray_offset.hpp"

#include <chrono>
#include <stdexcept>
#include <string>

namespace luxtrace {

BvhOptions BvhOptions::of(const Scene& scene) {
    const std::string& q = scene.run.bvh_quality;
    BvhOptions o;
    if (q == "low") o.quality = o.geometry_quality = RTC_BUILD_QUALITY_LOW;
    else if (q == "medium" || (q == "auto" && scene.triangle_count() >= kMediumBvhTriangles))
        o.quality = RTC_BUILD_QUALITY_MEDIUM;
    return o;
}

EmbreeScene::EmbreeScene(const Scene& scene) : EmbreeScene(scene, BvhOptions::of(scene)) {}

EmbreeScene::EmbreeScene(const Scene& scene, const BvhOptions& options)
    : origin_(0.5 * (scene.bounds_min + scene.bounds_max)) {
    const auto start = std::chrono::steady_clock::now();
    device_ = rtcNewDevice(nullptr);
    if (device_ == nullptr) throw std::runtime_error("Embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, options.quality);
    // Robust mode: no arithmetic shortcuts in the triangle and box tests, so that a ray
    // never slips through the shared edge of two triangles (a closed room stays closed).
    rtcSetSceneFlags(scene_, options.compact ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, options.geometry_quality);
    // Embree reads vertex buffers with 16-byte loads: the buffer it allocates is padded.
    auto* v = static_cast<Vec3f*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          sizeof(Vec3f), scene.vertices.size()));
    // The scene's index buffer is Embree's too (no copy): the scene outlives this BVH.
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, scene.triangles.data(), 0,
                               sizeof(glm::uvec3), scene.triangles.size());
    margin_.resize(scene.triangles.size());
    // Element by element, so the threads' split changes no value.
    constexpr std::size_t kGrain = 1 << 14;
    for_each_index(scene.vertices.size(), kGrain, [&](std::size_t i) { v[i] = to_local(scene.vertices[i]); });
    vertices_ = v;
    for_each_index(scene.triangles.size(), kGrain, [&](std::size_t i) {
        const glm::uvec3 t = scene.triangles[i];
        margin_[i] = luxtrace::self_hit_margin(v[t.x], v[t.y], v[t.z]);
    });
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);  // the scene keeps it, and with it the vertex buffer
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the scene failed");
    build_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EmbreeScene::~EmbreeScene() {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    if (device_ != nullptr) rtcReleaseDevice(device_);
}

}  // namespace luxtrace
