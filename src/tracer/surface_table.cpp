#include "luxtrace/tracer/surface_table.hpp"

#include "luxtrace/core/parallel.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"

#include <algorithm>

namespace luxtrace {

void SurfaceTable::fill(const Scene& scene, const EmbreeScene& embree, std::size_t t) {
    const glm::uvec3 v = scene.triangles[t];
    TriangleRecord& r = triangles_[t];
    r.p0 = embree.local_vertex(v.x);
    r.p1 = embree.local_vertex(v.y);
    r.p2 = embree.local_vertex(v.z);
    r.normal = Vec3f(scene.triangle_normal[t]);
    r.material = scene.triangle_material[t];
    r.margin = embree.self_hit_margin(static_cast<unsigned>(t));
    const float longest = std::max({glm::length(r.p1 - r.p0), glm::length(r.p2 - r.p1), glm::length(r.p0 - r.p2)});
    r.min_height = longest > 0.0f ? glm::length(glm::cross(r.p1 - r.p0, r.p2 - r.p0)) / longest : 0.0f;
}

SurfaceTable::SurfaceTable(const Scene& scene, const EmbreeScene& embree, const GatherShare& share)
    : triangles_(new TriangleRecord[scene.triangle_count()]), bands_(scene.band_count()) {
    for_each_index(scene.triangle_count(), 16384, [&](std::size_t t) { fill(scene, embree, t); });
    for (const Material& m : scene.materials)
        for (int b = 0; b < bands_; ++b) models_.push_back(scatter_model(m, b));
    for (const Material& m : scene.materials) panes_.push_back(gather_pane(m) ? 1 : 0);
    if (scene.annual && scene.annual->options.gathers())
        gather_ = GatherTable(scene, embree, tally_layout(scene), share);
}

}  // namespace luxtrace
