#pragma once
// Built-in geometry, triangulated with counter-clockwise winding seen from the front
// side, so that cross(v1 - v0, v2 - v0) points to the front (lit) side.
#include "luxtrace/core/math.hpp"

#include <string>
#include <vector>

namespace luxtrace {

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles;
    // Per triangle, an empty string where none is given; empty (the built-in shapes): none
    // given for any triangle.
    std::vector<std::string> material_names;
};

// Default `up` for a plane with normal n: +z unless n is close to +-z, then +y.
Vec3 default_up(const Vec3& normal);

// size_u along u = up x normal, size_v along up (the detector convention).
TriangleMesh make_rectangle(const Vec3& center, const Vec3& normal, const Vec3& up, double size_u, double size_v,
                            int subdivisions);
TriangleMesh make_box(const Vec3& center, const Vec3& size, int subdivisions, bool inward);
TriangleMesh make_sphere(const Vec3& center, double radius, int subdivisions, bool inward);
TriangleMesh make_disk(const Vec3& center, const Vec3& normal, double radius, int subdivisions);

}  // namespace luxtrace
