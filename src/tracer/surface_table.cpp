#include "luxtrace/tracer/surface_table.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

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
    }
    for (const Material& m : scene.materials)
        for (int b = 0; b < bands_; ++b) models_.push_back(scatter_model(m, b));
}

}  // namespace luxtrace
