#include "luxtrace/tracer/embree_scene.hpp"

#include "luxtrace/scene/scene.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace luxtrace {

EmbreeScene::EmbreeScene(const Scene& scene) {
    device_ = rtcNewDevice(nullptr);
    if (device_ == nullptr) throw std::runtime_error("Embree: cannot create a device");
    scene_ = rtcNewScene(device_);
    // Static scene traced by incoherent photon rays: spend build time on BVH quality.
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), scene.vertices.size()));
    std::memcpy(v, scene.vertices.data(), scene.vertices.size() * 3 * sizeof(float));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), scene.triangles.size()));
    std::memcpy(idx, scene.triangles.data(), scene.triangles.size() * 3 * sizeof(unsigned));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: building the scene failed");
}

EmbreeScene::~EmbreeScene() {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    if (device_ != nullptr) rtcReleaseDevice(device_);
}

}  // namespace luxtrace
