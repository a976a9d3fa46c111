#include "luxtrace/scene/mesh_loader.hpp"

#include "luxtrace/core/error.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <string>

namespace luxtrace {

Vec3 Transform::apply(const Vec3& p) const {
    Vec3 q = p * scale;
    const Vec3 r = rotate_deg * (kPi / 180.0);
    auto rot = [](double a, double& x, double& y) {
        const double c = std::cos(a), s = std::sin(a);
        const double nx = c * x - s * y, ny = s * x + c * y;
        x = nx;
        y = ny;
    };
    rot(r.x, q.y, q.z);
    rot(r.y, q.z, q.x);
    rot(r.z, q.x, q.y);
    return q + translate;
}

TriangleMesh load_mesh(const std::filesystem::path& file, const Transform& transform,
                       const std::string& context) {
    if (!std::filesystem::is_regular_file(file))
        throw InputError(context + ": mesh file '" + file.string() + "' does not exist");
    Assimp::Importer importer;
    // Keep the file's winding and vertices; only triangulate polygons and bake node
    // transforms. Lines and points are dropped.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* sc = importer.ReadFile(
        file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                           aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (sc == nullptr || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
        throw InputError(context + ": cannot read mesh '" + file.string() +
                         "': " + importer.GetErrorString());
    TriangleMesh out;
    for (unsigned mi = 0; mi < sc->mNumMeshes; ++mi) {
        const aiMesh* mesh = sc->mMeshes[mi];
        if ((mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
        std::string material_name;
        if (mesh->mMaterialIndex < sc->mNumMaterials) {
            aiString name;
            if (sc->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS)
                material_name = name.C_Str();
        }
        if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr)
            throw InputError(context + ": mesh '" + file.string() + "' has faces but no vertex positions");
        const auto base = static_cast<unsigned>(out.vertices.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            out.vertices.push_back(transform.apply(Vec3(p.x, p.y, p.z)));
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3 || face.mIndices == nullptr) continue;
            for (unsigned k = 0; k < 3; ++k)  // assimp does not check every importer's indices
                if (face.mIndices[k] >= mesh->mNumVertices)
                    throw InputError(context + ": mesh '" + file.string() + "': face " + std::to_string(f + 1) +
                                     " names vertex " + std::to_string(face.mIndices[k] + 1) + " of " +
                                     std::to_string(mesh->mNumVertices));
            out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1],
                                     base + face.mIndices[2]});
            out.material_names.push_back(material_name);
        }
    }
    if (out.triangles.empty())
        throw InputError(context + ": mesh '" + file.string() + "' has no triangles");
    return out;
}

}  // namespace luxtrace
