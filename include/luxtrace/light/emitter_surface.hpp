#pragma once
// The triangles a light's photons leave from (an area light's shape, a portal's opening),
// with their cumulative area for uniform points on them.
#include "luxtrace/core/math.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace luxtrace {

struct EmitterSurface {
    std::vector<Vec3> p0, e1, e2, normal;  // vertex, two edges, unit front normal
    std::vector<double> cdf;               // normalised cumulative area
    std::vector<int> scene_triangle;
    double area_m2 = 0.0;
    // The area-weighted centre, and the largest distance from it to a corner.
    Vec3 centroid() const;
    double radius_around(const Vec3& centre) const;
};

// A uniform point on the surface (two uniforms): the surface's triangle, the point's
// barycentrics on it, the point.
struct SurfacePick {
    std::size_t triangle = 0;
    double a = 0.0, b = 0.0;
    Vec3 point{0.0};
};
SurfacePick surface_point(const EmitterSurface& surface, double u1, double u2);
// The surface's triangle and barycentrics of a point `x` in the plane of its triangles,
// if it lies on one of them.
std::optional<SurfacePick> locate_on_surface(const EmitterSurface& surface, const Vec3& x);

}  // namespace luxtrace
