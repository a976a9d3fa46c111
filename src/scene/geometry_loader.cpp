// [[material]], [[mesh]] and [[shape]] -> the scene's materials and triangles
// (docs/REFERENCE.md §2).
#include "luxtrace/core/error.hpp"
#include "luxtrace/core/parallel.hpp"
#include "luxtrace/scene/mesh_loader.hpp"
#include "luxtrace/scene/shapes.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace luxtrace::detail {

namespace {

// Limits that keep an absurd scene from allocating gigabytes before anything is traced:
// triangles of one built-in shape, triangles of the whole scene (each costs about 300
// bytes in the scene, the BVH and the tallies), and vertex coordinates (no lighting scene
// spans a million kilometres; huge values would overflow areas and Embree's floats).
constexpr std::uint64_t kMaxShapeTriangles = std::uint64_t{1} << 22;  // 4,194,304
constexpr std::uint64_t kMaxSceneTriangles = std::uint64_t{1} << 25;  // 33,554,432
constexpr double kMaxCoordinate = 1e9;                                // metres

// Triangles make_rectangle/box/sphere/disk produce for `subdivisions` (shapes.cpp).
std::uint64_t shape_triangles(const std::string& type, std::uint64_t s) {
    if (type == "rectangle") return 2 * s * s;
    if (type == "box") return 12 * s * s;
    if (type == "sphere") {
        const std::uint64_t stacks = std::max<std::uint64_t>(3, s);
        return 4 * stacks * (stacks - 1);
    }
    if (type == "disk") return std::max<std::uint64_t>(12, 8 * s) * (2 * s - 1);
    return 0;
}

struct GeometryReader : StepReader {
    using StepReader::StepReader;
    std::map<std::string, std::uint32_t> material_index;

    void parse_material(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("material", i, t), "material");
        Material m;
        const auto name = r.string("name");
        if (!name || name->empty()) r.fail_entry("needs a 'name'");
        m.name = *name;
        if (material_index.count(m.name)) r.fail("name", "material '" + m.name + "' is defined twice");
        const std::string type = r.string("type").value_or("diffuse");
        const std::size_t nb = scene.bands.size();
        auto required = [&](const std::string& key) {
            auto v = r.per_band(key, nb);
            if (!v) r.fail_entry("type '" + type + "' needs '" + key + "'");
            return *v;
        };
        if (type == "diffuse") {
            m.type = MaterialType::diffuse;
            m.diffuse_reflectance = required("reflectance");
        } else if (type == "mirror") {
            m.type = MaterialType::mirror;
            m.specular_reflectance = required("specular_reflectance");
            read_roughness(r, m);
        } else if (type == "glass") {
            m.type = MaterialType::glass;
            m.ior = r.number("ior").value_or(1.5);
            if (!(m.ior >= 1.0 && m.ior <= 4.0)) r.fail("ior", "must lie in [1, 4]");
            m.transmittance = r.per_band("transmittance", nb).value_or(std::vector<double>(nb, 1.0));
        } else if (type == "general") {
            m.type = MaterialType::general;
            const std::vector<double> zero(nb, 0.0);
            m.diffuse_reflectance = r.per_band("diffuse_reflectance", nb).value_or(zero);
            m.specular_reflectance = r.per_band("specular_reflectance", nb).value_or(zero);
            m.diffuse_transmittance = r.per_band("diffuse_transmittance", nb).value_or(zero);
            m.specular_transmittance = r.per_band("specular_transmittance", nb).value_or(zero);
            read_roughness(r, m);
            for (std::size_t b = 0; b < nb; ++b) {
                const double sum = m.diffuse_reflectance[b] + m.specular_reflectance[b] + m.diffuse_transmittance[b] +
                                   m.specular_transmittance[b];
                if (sum > 1.0 + 1e-12)
                    r.fail_entry("reflectances and transmittances sum to " + std::to_string(sum) + " > 1 in band '" +
                                 scene.bands[b] + "'");
            }
        } else if (type == "black") {
            m.type = MaterialType::black;
        } else if (type == "glazing") {
            m.type = MaterialType::glazing;
            parse_glazing(r, m);
        } else {
            r.fail("type",
                   "unknown material type '" + type + "' (expected diffuse, mirror, glass, general, black or glazing)");
        }
        r.finish();
        material_index[m.name] = static_cast<std::uint32_t>(scene.materials.size());
        scene.materials.push_back(std::move(m));
    }

    // mirror, general: the specular reflection's roughness (ward_lobe.hpp), 0 a mirror.
    static void read_roughness(TableReader& r, Material& m) {
        const double alpha = r.number("roughness").value_or(0.0);
        if (!(alpha >= 0.0 && alpha <= WardLobe::kMaxRoughness))
            r.fail("roughness",
                   "must lie in [0, " + fmt_number(WardLobe::kMaxRoughness) + "], got " + fmt_number(alpha));
        m.set_roughness(alpha);
    }

    // An array of numbers of any length (a glazing table's column).
    static std::vector<double> column(TableReader& r, const std::string& key) {
        const toml::array* a = r.array(key);
        if (a == nullptr) r.fail_entry("a glazing table needs 'angles_deg', 'transmittance_at' and 'reflectance_at'");
        std::vector<double> out;
        for (const toml::node& e : *a) {
            const std::optional<double> v = e.value<double>();
            if (!v || !std::isfinite(*v)) r.fail(key, "expected an array of numbers");
            out.push_back(*v);
        }
        return out;
    }

    // type = "glazing": a pane given by its normal transmittance and index, or a maker's
    // table against the angle of incidence (glazing.hpp); one curve per band.
    void parse_glazing(TableReader& r, Material& m) const {
        const std::size_t nb = scene.bands.size();
        const bool table = r.has("angles_deg") || r.has("transmittance_at") || r.has("reflectance_at");
        auto curves = std::make_shared<std::vector<GlazingCurve>>();
        if (table) {
            if (r.has("transmittance"))
                r.fail("transmittance", "give either 'transmittance' or the table 'angles_deg', 'transmittance_at', "
                                        "'reflectance_at', not both");
            GlazingTable t{column(r, "angles_deg"), column(r, "transmittance_at"), column(r, "reflectance_at")};
            const GlazingTableError e = check_glazing_table(t);
            if (!e.key.empty()) r.fail(e.key, e.what);
            curves->assign(nb, table_curve(t));
        } else {
            const auto t = r.per_band("transmittance", nb);
            if (!t)
                r.fail_entry("type 'glazing' needs 'transmittance' (normal incidence) or a table 'angles_deg', "
                             "'transmittance_at', 'reflectance_at'");
            m.ior = r.number("refractive_index").value_or(1.52);
            if (!(m.ior >= 1.2 && m.ior <= 3.0)) r.fail("refractive_index", "must lie in [1.2, 3]");
            const double t_max = max_pane_transmittance(m.ior);
            for (std::size_t b = 0; b < nb; ++b) {
                const double tb = (*t)[b];
                if (!(tb > 0.0 && tb < 1.0)) r.fail("transmittance", "must lie in (0, 1), got " + fmt_number(tb));
                if (tb > t_max * (1.0 + 1e-12))
                    r.fail("transmittance", fmt_number(tb) + " is more than a pane of refractive index " +
                                                fmt_number(m.ior) + " can transmit (" + fmt_number(t_max) +
                                                ", with no absorption)");
                curves->push_back(pane_curve(std::min(tb, t_max), m.ior));
            }
            m.transmittance = *t;
        }
        m.glazing = std::move(curves);
    }

    std::uint32_t material_ref(TableReader& r, const std::string& key, bool required) {
        const auto name = r.string(key);
        if (!name) {
            if (required) r.fail_entry("needs a '" + key + "'");
            return UINT32_MAX;
        }
        const auto it = material_index.find(*name);
        if (it == material_index.end()) r.fail(key, "no [[material]] is named '" + *name + "'");
        return it->second;
    }

    void add_triangles(const TriangleMesh& mesh, std::uint32_t default_material, TableReader& r) {
        static const std::string kNoName;
        add_mesh_triangles(
            load, mesh,
            [&](std::size_t t) {
                std::uint32_t mat = default_material;
                const std::string& usemtl = mesh.material_names.empty() ? kNoName : mesh.material_names[t];
                if (!usemtl.empty()) {
                    const auto it = material_index.find(usemtl);
                    if (it != material_index.end()) mat = it->second;
                }
                if (mat == UINT32_MAX)
                    r.fail_entry("triangles with file material '" + usemtl +
                                 "' match no [[material]] and no default 'material' is given");
                return mat;
            },
            [&](const std::string& what) { r.fail_entry(what); });
    }

    void parse_mesh(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("mesh", i, t), "mesh");
        const auto f = r.string("file");
        if (!f) r.fail_entry("needs a 'file'");
        const std::uint32_t mat = material_ref(r, "material", false);
        Transform tr;
        if (const toml::table* tt = r.table("transform")) {
            TableReader tx(*tt, fname, r.context() + " transform", "mesh.transform");
            tr.translate = tx.vec3("translate").value_or(Vec3(0.0));
            tr.rotate_deg = tx.vec3("rotate_deg").value_or(Vec3(0.0));
            if (tx.has("scale")) {
                if (t["transform"]["scale"].is_array()) tr.scale = *tx.vec3("scale");
                else tr.scale = Vec3(*tx.number("scale"));
                if (!(tr.scale.x != 0.0 && tr.scale.y != 0.0 && tr.scale.z != 0.0))
                    tx.fail("scale", "must be non-zero");
            }
            tx.finish();
        }
        r.finish();
        TriangleMesh mesh = load_mesh(load.resolve(*f), tr,
                                      fname + ":" + std::to_string(r.line("file")) + ": " + r.context());
        if (tr.scale.x * tr.scale.y * tr.scale.z < 0.0)  // a mirroring scale flips the winding
            for (glm::uvec3& tri : mesh.triangles) std::swap(tri.y, tri.z);
        add_triangles(mesh, mat, r);
    }

    // A [[shape]] read and checked, its triangles not yet made.
    struct PendingShape {
        TableReader r;
        std::uint32_t material;
        std::optional<std::string> name;
        std::function<TriangleMesh()> make;
        std::uint64_t triangles;
    };

    PendingShape read_shape(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("shape", i, t), "shape");
        const std::string type = r.string("type").value_or("");
        const std::uint32_t mat = material_ref(r, "material", true);
        const Vec3 center = r.vec3("center").value_or(Vec3(0.0));
        auto name = r.string("name");
        const std::int64_t subdiv64 = r.integer("subdivisions").value_or(type == "sphere" ? 16 : 1);
        if (subdiv64 < 1 || subdiv64 > 4096) r.fail("subdivisions", "must lie in [1, 4096]");
        const int subdiv = static_cast<int>(subdiv64);
        const std::uint64_t n = shape_triangles(type, static_cast<std::uint64_t>(subdiv));
        if (n > kMaxShapeTriangles)
            r.fail("subdivisions", std::to_string(subdiv) + " gives " + std::to_string(n) + " triangles; a " + type +
                                       " may have at most " + std::to_string(kMaxShapeTriangles) +
                                       " (split it into several shapes or use a mesh)");
        auto positive = [&](const std::string& key) {
            const auto v = r.number(key);
            if (!v) r.fail_entry("type '" + type + "' needs '" + key + "'");
            if (!(*v > 0.0)) r.fail(key, "must be positive");
            return *v;
        };
        std::function<TriangleMesh()> make;
        if (type == "rectangle" || type == "disk") {
            const Vec3 nrm = unit_vector(r, "normal", r.vec3("normal").value_or(Vec3(0, 0, 1)));
            if (type == "rectangle") {
                const Vec3 up = unit_vector(r, "up", r.vec3("up").value_or(default_up(nrm)));
                if (glm::length(glm::cross(up, nrm)) < 1e-6) r.fail("up", "must not be parallel to 'normal'");
                const auto size = r.numbers("size", 2);
                if (!size) r.fail_entry("type 'rectangle' needs 'size' = [w, h]");
                if (!((*size)[0] > 0.0 && (*size)[1] > 0.0)) r.fail("size", "must be positive");
                make = [=, w = (*size)[0], h = (*size)[1]] { return make_rectangle(center, nrm, up, w, h, subdiv); };
            } else {
                make = [=, radius = positive("radius")] { return make_disk(center, nrm, radius, subdiv); };
            }
        } else if (type == "box") {
            const auto size = r.vec3("size");
            if (!size) r.fail_entry("type 'box' needs 'size' = [x, y, z]");
            if (!(size->x > 0.0 && size->y > 0.0 && size->z > 0.0)) r.fail("size", "must be positive");
            make = [=, size = *size, inward = r.boolean("inward").value_or(false)] {
                return make_box(center, size, subdiv, inward);
            };
        } else if (type == "sphere") {
            make = [=, radius = positive("radius"), inward = r.boolean("inward").value_or(false)] {
                return make_sphere(center, radius, subdiv, inward);
            };
        } else {
            r.fail("type", "unknown shape type '" + type + "' (expected rectangle, box, sphere or disk)");
        }
        r.finish();
        return PendingShape{std::move(r), mat, std::move(name), std::move(make), n};
    }

    // The shapes' triangles are made in parallel (each shape on its own) and placed in the
    // scene in the file's order, so the scene is the same on any number of threads.
    void add_shapes(const std::vector<const toml::table*>& tables) {
        std::vector<PendingShape> shapes;
        shapes.reserve(tables.size());
        std::uint64_t total = 0;
        for (std::size_t i = 0; i < tables.size(); ++i) {
            shapes.push_back(read_shape(*tables[i], i));
            total += shapes.back().triangles;
        }
        reserve_triangles(load, std::min<std::uint64_t>(total, kMaxSceneTriangles));
        std::vector<TriangleMesh> meshes(shapes.size());
        tbb::parallel_for(std::size_t{0}, shapes.size(), [&](std::size_t i) { meshes[i] = shapes[i].make(); });
        for (std::size_t i = 0; i < shapes.size(); ++i) {
            PendingShape& shape = shapes[i];
            const std::size_t first = scene.triangles.size();
            add_triangles(meshes[i], shape.material, shape.r);
            meshes[i] = TriangleMesh();  // its memory back before the next is placed
            if (shape.name) {
                if (load.named_shapes.count(*shape.name))
                    shape.r.fail("name", "shape '" + *shape.name + "' is defined twice");
                load.named_shapes[*shape.name] = {first, scene.triangles.size()};
            }
        }
    }

    void finish_geometry() {
        if (scene.triangles.empty()) throw InputError(fname + ": the scene has no surfaces");
        // The box of the triangles' vertices: min and max are exact, so any split gives it.
        using Box = std::pair<Vec3, Vec3>;
        const Vec3 v0 = scene.vertices[scene.triangles[0].x];
        std::tie(scene.bounds_min, scene.bounds_max) = tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, scene.triangles.size(), 1 << 14), Box{v0, v0},
            [&](const tbb::blocked_range<std::size_t>& r, Box box) {
                for (std::size_t i = r.begin(); i < r.end(); ++i)
                    for (int k = 0; k < 3; ++k) {
                        const Vec3& v = scene.vertices[scene.triangles[i][k]];
                        box = {glm::min(box.first, v), glm::max(box.second, v)};
                    }
                return box;
            },
            [](const Box& a, const Box& b) {
                return Box{glm::min(a.first, b.first), glm::max(a.second, b.second)};
            });
    }
};

}  // namespace

std::vector<std::int64_t> add_mesh_triangles(SceneLoad& load, const TriangleMesh& mesh,
                                             const std::function<std::uint32_t(std::size_t)>& material_of,
                                             const std::function<void(const std::string&)>& fail) {
    Scene& scene = load.scene;
    if (scene.triangles.size() + mesh.triangles.size() > kMaxSceneTriangles)
        fail("the scene would have " + std::to_string(scene.triangles.size() + mesh.triangles.size()) +
             " triangles; a scene may have at most " + std::to_string(kMaxSceneTriangles));
    for (const Vec3& v : mesh.vertices)
        if (!(std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate && std::abs(v.z) <= kMaxCoordinate))
            fail("a vertex at (" + fmt_number(v.x) + ", " + fmt_number(v.y) + ", " + fmt_number(v.z) +
                 ") lies outside the +-" + fmt_number(kMaxCoordinate) + " m that luxtrace can place");
    const auto base = static_cast<unsigned>(scene.vertices.size());
    scene.vertices.insert(scene.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    const std::size_t n = mesh.triangles.size();
    std::vector<std::uint32_t> material(n);
    for (std::size_t t = 0; t < n; ++t) material[t] = material_of(t);
    // Every triangle's entries at first + t, in parallel; then the ones not placed (left
    // out, or degenerate: no light and no map entry) are squeezed out in order.
    const std::size_t first = scene.triangles.size();
    scene.triangles.resize(first + n);
    scene.triangle_material.resize(first + n);
    scene.triangle_area_m2.resize(first + n);
    scene.triangle_normal.resize(first + n);
    std::vector<std::uint8_t> keep(n);
    constexpr std::size_t kGrain = 1 << 14;
    for_each_index(n, kGrain, [&](std::size_t t) {
        const glm::uvec3 tri = mesh.triangles[t] + glm::uvec3(base);
        const Vec3 a(scene.vertices[tri.x]), b(scene.vertices[tri.y]), c(scene.vertices[tri.z]);
        const Vec3 cr = glm::cross(b - a, c - a);
        const double area = 0.5 * glm::length(cr);
        keep[t] = material[t] != kLeaveOutTriangle && area > 0.0;
        const std::size_t i = first + t;
        scene.triangles[i] = tri;
        scene.triangle_material[i] = material[t];
        scene.triangle_area_m2[i] = area;
        scene.triangle_normal[i] = keep[t] ? cr / (2.0 * area) : Vec3(0.0);
    });
    std::vector<std::int64_t> placed(n, -1);
    std::size_t next = first;
    for (std::size_t t = 0; t < n; ++t) {
        if (!keep[t]) continue;
        if (const std::size_t i = first + t; i != next) {
            scene.triangles[next] = scene.triangles[i];
            scene.triangle_material[next] = scene.triangle_material[i];
            scene.triangle_area_m2[next] = scene.triangle_area_m2[i];
            scene.triangle_normal[next] = scene.triangle_normal[i];
        }
        placed[t] = static_cast<std::int64_t>(next++);
    }
    scene.triangles.resize(next);
    scene.triangle_material.resize(next);
    scene.triangle_area_m2.resize(next);
    scene.triangle_normal.resize(next);
    return placed;
}

void reserve_triangles(SceneLoad& load, std::size_t more) {
    Scene& scene = load.scene;
    scene.vertices.reserve(scene.vertices.size() + more);
    scene.triangles.reserve(scene.triangles.size() + more);
    scene.triangle_material.reserve(scene.triangle_material.size() + more);
    scene.triangle_area_m2.reserve(scene.triangle_area_m2.size() + more);
    scene.triangle_normal.reserve(scene.triangle_normal.size() + more);
}

void read_geometry(SceneLoad& load, TableReader& root) {
    GeometryReader g(load);
    const auto materials = tables_of(root, "material");
    for (std::size_t i = 0; i < materials.size(); ++i) g.parse_material(*materials[i], i);
    const auto meshes = tables_of(root, "mesh");
    for (std::size_t i = 0; i < meshes.size(); ++i) g.parse_mesh(*meshes[i], i);
    g.add_shapes(tables_of(root, "shape"));
    read_radiance_models(load, root);
    g.finish_geometry();
}

}  // namespace luxtrace::detail
