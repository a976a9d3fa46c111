#include "luxtrace/tracer/surface_table.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <algorithm>

namespace luxtrace {

SurfaceTable::SurfaceTable(const Scene& scene, const EmbreeScene& embree) : bands_(scene.band_count()) {
    triangles_.resize(scene.triangle_count());
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
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
    for (const Material& m : scene.materials)
        for (int b = 0; b < bands_; ++b) models_.push_back(scatter_model(m, b));
}

}  // namespace luxtrace
