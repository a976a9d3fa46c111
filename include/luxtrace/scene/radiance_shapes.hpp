#pragma once
// Radiance's surfaces as triangles (docs/RADIANCE.md). Polygons keep their vertices and are
// cut into triangles by ear clipping (Radiance polygons may be concave and may hold holes
// joined to the outline by a seam). Curved surfaces are tessellated to a chord tolerance:
// every point of a triangle lies within chord_tolerance * radius of the true surface (for a
// circle cut into n chords, the sagitta r (1 - cos(pi / n))). The winding follows
// shapes.hpp: cross(v1 - v0, v2 - v0) points to the front side, which for a polygon is the
// side from which its vertices run counter-clockwise (Radiance's right-hand rule).
#include "luxtrace/scene/shapes.hpp"

#include <vector>

namespace luxtrace::radiance {

// Chords on a full circle so that each chord's sagitta is at most chord_tolerance * r.
int circle_segments(double chord_tolerance);

// Twice the polygon's vector area (Newell's sum, as Radiance's face.c): its direction is
// the polygon's normal, its length twice its area.
Vec3 polygon_area_vector(const std::vector<Vec3>& vertices);

// Appends the polygon's triangles to `out` (vertices shared). Returns false when ear
// clipping found no valid ear (a self-intersecting outline): the rest is then cut as a fan
// and the caller should warn. A polygon of zero area adds nothing and returns true.
bool append_polygon(const std::vector<Vec3>& vertices, TriangleMesh& out);

// A flat annulus around `center` facing `normal` (r_inner may be 0: a disc).
void append_ring(const Vec3& center, const Vec3& normal, double r_inner, double r_outer, double chord_tolerance,
                 TriangleMesh& out);
// A sphere facing outward, or inward (Radiance's bubble).
void append_sphere(const Vec3& center, double radius, double chord_tolerance, bool inward, TriangleMesh& out);
// The open side of a truncated cone from p0 (radius r0) to p1 (radius r1), either radius
// possibly 0, facing away from the axis or toward it (Radiance's cup and tube).
void append_cone(const Vec3& p0, const Vec3& p1, double r0, double r1, double chord_tolerance, bool inward,
                 TriangleMesh& out);

}  // namespace luxtrace::radiance
