#include "luxtrace/tracer/embree_scene.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/ray_offset.hpp"

#include <chrono>
#include <stdexcept>
#include <string>

namespace luxtrace {

EmbreeScene::EmbreeScene(const Scene& scene) : origin_(0.5 * (scene.bounds_min + scene.bounds_max)) {
    const auto start = std::chrono::steady_clock::now();
    device_ = rtcNewDevice(nullptr);
    if (device_ == nullptr) throw std::runtime_error("Embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    // Static scene traced by incoherent photon rays: spend build time on BVH quality.
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    // Robust mode: no arithmetic shortcuts in the triangle and box tests, so that a ray
    // never slips through the shared edge of two triangles (a closed room stays closed).
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertex buffers with 16-byte loads: the buffer it allocates is padded.
    auto* v = static_cast<Vec3f*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          sizeof(Vec3f), scene.vertices.size()));
    for (std::size_t i = 0; i < scene.vertices.size(); ++i) v[i] = to_local(scene.vertices[i]);
    vertices_ = v;
    auto* idx = static_cast<glm::uvec3*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 sizeof(glm::uvec3), scene.triangles.size()));
    margin_.resize(scene.triangles.size());
    for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
        const glm::uvec3 t = idx[i] = scene.triangles[i];
        margin_[i] = luxtrace::self_hit_margin(v[t.x], v[t.y], v[t.z]);
    }
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
