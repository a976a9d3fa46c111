#include "luxtrace/scene/mesh_loader.hpp"

#include "luxtrace/core/error.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <cctype>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

namespace luxtrace {

namespace {

// assimp 5.2.5's PLY reader never returns on a header that has no "end_header" line (a
// file cut short inside its header, a damaged header): it seeks for ever. Such a file
// is refused before assimp sees it. The header is ASCII lines even in binary PLY files.
// A PLY file by its extension or its "ply" magic; `in` is left at the start.
bool is_ply(const std::filesystem::path& file, std::ifstream& in) {
    std::string ext = file.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    char magic[3] = {};
    in.read(magic, sizeof magic);
    const bool ply = ext == ".ply" || (in.gcount() == 3 && std::string_view(magic, 3) == "ply");
    in.clear();
    in.seekg(0);
    return ply;
}

bool ply_header_ends(const std::string& head) {
    std::size_t pos = 0;
    while (pos < head.size()) {
        std::size_t end = head.find('\n', pos);
        if (end == std::string::npos) end = head.size();
        std::string_view line(head.data() + pos, end - pos);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
            line.remove_suffix(1);
        if (line == "end_header") return true;
        pos = end + 1;
    }
    return false;
}

}  // namespace

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

TriangleMesh load_mesh(const std::filesystem::path& file, const Transform& transform, const std::string& context) {
    if (!std::filesystem::is_regular_file(file))
        throw InputError(context + ": mesh file '" + file.string() + "' does not exist");
    {
        std::ifstream in(file, std::ios::binary);
        if (is_ply(file, in)) {  // only a PLY file's header is read, up to 1 MiB
            constexpr std::size_t kMaxPlyHeader = std::size_t{1} << 20;
            std::string head(kMaxPlyHeader, '\0');
            in.read(head.data(), static_cast<std::streamsize>(head.size()));
            head.resize(static_cast<std::size_t>(in.gcount()));
            if (!ply_header_ends(head))
                throw InputError(
                    context + ": cannot read mesh '" + file.string() +
                    "': its PLY header has no 'end_header' line (in its first MiB); is the file cut short?");
        }
    }
    Assimp::Importer importer;
    // Keep the file's winding and vertices; only triangulate polygons and bake node
    // transforms. Lines and points are dropped.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* sc = importer.ReadFile(file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                             aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (sc == nullptr || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
        throw InputError(context + ": cannot read mesh '" + file.string() + "': " + importer.GetErrorString());
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
            out.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
            out.material_names.push_back(material_name);
        }
    }
    if (out.triangles.empty()) throw InputError(context + ": mesh '" + file.string() + "' has no triangles");
    return out;
}

}  // namespace luxtrace
