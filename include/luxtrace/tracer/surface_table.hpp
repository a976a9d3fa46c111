#pragma once
// What a photon reads when it arrives on a surface, laid out for the tracing path: one
// 64-byte record per triangle (its vertices in Embree's float frame, its normal, its
// material and the margin its ray origins keep, ray_offset.hpp), and each material's
// probabilities per band flattened (material.hpp). Built once per rank and shared,
// read-only, by its tracing threads: memory does not grow with the thread count. Ten
// million triangles make 627 MB of records, written by all cores (issue 26).
#include "luxtrace/core/math.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/tracer/gather_table.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace luxtrace {

struct Scene;
class EmbreeScene;

struct alignas(64) TriangleRecord {
    Vec3f p0, p1, p2;        // local float coordinates, as Embree intersects them
    Vec3f normal;            // unit geometric normal, front side
    std::uint32_t material;  // index into Scene::materials
    float margin;            // EmbreeScene::self_hit_margin
    float min_height;        // the smallest of its three heights (point_on_triangle)
};
static_assert(sizeof(TriangleRecord) == 64, "one cache line per triangle");

class SurfaceTable {
public:
    // With the scene's gather table (empty unless its annual grids gather).
    SurfaceTable(const Scene& scene, const EmbreeScene& embree, const GatherShare& share = {});
    const TriangleRecord& triangle(std::size_t t) const { return triangles_[t]; }
    const ScatterModel& model(std::uint32_t material, int band) const {
        return models_[material * static_cast<std::size_t>(bands_) + static_cast<std::size_t>(band)];
    }
    // What an arrival gathers to the annual grids' sensors (gather_table.hpp).
    const GatherTable& gather() const { return gather_; }
    // A pane the gather's rays pass (glazing, or glass of index 1): light after a diffuse
    // reflection stays gathered through it (sensor_gather.hpp).
    bool pane(std::uint32_t material) const { return panes_[material] != 0; }

private:
    void fill(const Scene& scene, const EmbreeScene& embree, std::size_t t);  // triangle t's record
    std::unique_ptr<TriangleRecord[]> triangles_;                             // written once, not zeroed first
    std::vector<ScatterModel> models_;
    int bands_ = 1;
    GatherTable gather_;
    std::vector<std::uint8_t> panes_;
};

}  // namespace luxtrace
