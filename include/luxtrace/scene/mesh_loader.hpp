#pragma once
// Triangle meshes from files (OBJ, PLY, STL, glTF/GLB) through assimp.
#include "luxtrace/scene/shapes.hpp"

#include <filesystem>

namespace luxtrace {

// Placement of a mesh: scale, then rotations about x, y, z (degrees, in that order),
// then translation.
struct Transform {
    Vec3 translate{0.0};
    Vec3 rotate_deg{0.0};
    Vec3 scale{1.0};
    Vec3 apply(const Vec3& p) const;
};

// Loads every triangle of the file with node transforms applied, then `transform`;
// each triangle carries the name of its file material (OBJ `usemtl`).
// Throws InputError naming `context` (file:line of the scene entry) and the mesh file.
TriangleMesh load_mesh(const std::filesystem::path& file, const Transform& transform, const std::string& context);

}  // namespace luxtrace
