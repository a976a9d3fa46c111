// Scene file (docs/REFERENCE.md §2) -> Scene. Every key is checked; the first problem found is
// thrown as an InputError naming the file, the line and the key.
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/orientation.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/scene/mesh_loader.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/scene/scene_schema.hpp"
#include "luxtrace/scene/shapes.hpp"
#include "toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace luxtrace {

using detail::TableReader;
namespace fs = std::filesystem;

double Scene::total_area_m2() const {
    double s = 0.0;
    for (double a : triangle_area_m2) s += a;
    return s;
}

double Scene::ray_epsilon_m() const {
    // Embree works relative to the scene's centre (EmbreeScene), so the scene's size,
    // not its distance from the origin, sets the precision.
    return 2e-6 * std::max(glm::length(bounds_max - bounds_min), 1e-3);
}

namespace {

constexpr double kMaxDetectorCells = 1e8;
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

std::string fmt_count(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    return os.str();
}

struct Loader {
    fs::path file;
    std::string fname;
    Scene scene;
    std::map<std::string, std::uint32_t> material_index;
    std::map<std::string, std::pair<std::size_t, std::size_t>> named_shapes;  // triangle range
    std::map<std::string, std::pair<std::shared_ptr<const Photometry>, std::shared_ptr<const PhotometryDistribution>>>
        photometry_cache;  // by canonical file path and lamp set

    fs::path resolve(const std::string& p) const {
        const fs::path path(p);
        return path.is_absolute() ? path : file.parent_path() / path;
    }

    std::vector<const toml::table*> tables_of(TableReader& root, const std::string& key) {
        std::vector<const toml::table*> out;
        const toml::array* a = root.array(key);
        if (a == nullptr) return out;
        for (const toml::node& n : *a) {
            if (!n.is_table()) root.fail(key, "expected [[" + key + "]] tables");
            out.push_back(n.as_table());
        }
        return out;
    }

    static std::string entry_name(const std::string& kind, std::size_t i, const toml::table& t) {
        std::string s = "[[" + kind + "]] #" + std::to_string(i + 1);
        if (const auto n = t["name"].value<std::string>()) s += " '" + *n + "'";
        return s;
    }

    static Vec3 unit(TableReader& r, const std::string& key, Vec3 v) {
        if (glm::length(v) < 1e-12) r.fail(key, "must be a non-zero vector");
        return glm::normalize(v);
    }

    void parse_scene_table(TableReader& root) {
        const toml::table* t = root.table("scene");
        if (t == nullptr) return;
        TableReader r(*t, fname, "[scene]", "scene");
        scene.name = r.string("name").value_or(file.stem().string());
        if (auto b = r.strings("bands")) {
            if (b->empty()) r.fail("bands", "needs at least one band");
            scene.bands = *b;
        }
        scene.maintenance_factor = r.number("maintenance_factor").value_or(1.0);
        if (!(scene.maintenance_factor > 0.0 && scene.maintenance_factor <= 1.0))
            r.fail("maintenance_factor", "must lie in (0, 1]");
        r.finish();
    }

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
            for (std::size_t b = 0; b < nb; ++b) {
                const double sum = m.diffuse_reflectance[b] + m.specular_reflectance[b] + m.diffuse_transmittance[b] +
                                   m.specular_transmittance[b];
                if (sum > 1.0 + 1e-12)
                    r.fail_entry("reflectances and transmittances sum to " + std::to_string(sum) + " > 1 in band '" +
                                 scene.bands[b] + "'");
            }
        } else if (type == "black") {
            m.type = MaterialType::black;
        } else {
            r.fail("type", "unknown material type '" + type + "' (expected diffuse, mirror, glass, general or black)");
        }
        r.finish();
        material_index[m.name] = static_cast<std::uint32_t>(scene.materials.size());
        scene.materials.push_back(std::move(m));
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
        if (scene.triangles.size() + mesh.triangles.size() > kMaxSceneTriangles)
            r.fail_entry("the scene would have " + std::to_string(scene.triangles.size() + mesh.triangles.size()) +
                         " triangles; a scene may have at most " + std::to_string(kMaxSceneTriangles));
        for (const Vec3& v : mesh.vertices)
            if (!(std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate &&
                  std::abs(v.z) <= kMaxCoordinate))
                r.fail_entry("a vertex at (" + fmt_count(v.x) + ", " + fmt_count(v.y) + ", " + fmt_count(v.z) +
                             ") lies outside the +-" + fmt_count(kMaxCoordinate) + " m that luxtrace can place");
        const auto base = static_cast<unsigned>(scene.vertices.size());
        for (const Vec3& v : mesh.vertices) scene.vertices.emplace_back(v);
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            std::uint32_t mat = default_material;
            const std::string& usemtl = mesh.material_names[t];
            if (!usemtl.empty()) {
                const auto it = material_index.find(usemtl);
                if (it != material_index.end()) mat = it->second;
            }
            if (mat == UINT32_MAX)
                r.fail_entry("triangles with file material '" + usemtl +
                             "' match no [[material]] and no default 'material' is given");
            const glm::uvec3 tri = mesh.triangles[t] + glm::uvec3(base);
            const Vec3 a(scene.vertices[tri.x]), b(scene.vertices[tri.y]), c(scene.vertices[tri.z]);
            const Vec3 cr = glm::cross(b - a, c - a);
            const double area = 0.5 * glm::length(cr);
            if (!(area > 0.0)) continue;  // degenerate triangles carry no light and no map entry
            scene.triangles.push_back(tri);
            scene.triangle_material.push_back(mat);
            scene.triangle_area_m2.push_back(area);
            scene.triangle_normal.push_back(cr / (2.0 * area));
        }
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
        TriangleMesh mesh = load_mesh(resolve(*f), tr,
                                      fname + ":" + std::to_string(r.line("file")) + ": " + r.context());
        if (tr.scale.x * tr.scale.y * tr.scale.z < 0.0)  // a mirroring scale flips the winding
            for (glm::uvec3& tri : mesh.triangles) std::swap(tri.y, tri.z);
        add_triangles(mesh, mat, r);
    }

    void parse_shape(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("shape", i, t), "shape");
        const std::string type = r.string("type").value_or("");
        const std::uint32_t mat = material_ref(r, "material", true);
        const Vec3 center = r.vec3("center").value_or(Vec3(0.0));
        const auto name = r.string("name");
        const std::int64_t subdiv64 = r.integer("subdivisions").value_or(type == "sphere" ? 16 : 1);
        if (subdiv64 < 1 || subdiv64 > 4096) r.fail("subdivisions", "must lie in [1, 4096]");
        const int subdiv = static_cast<int>(subdiv64);
        if (const std::uint64_t n = shape_triangles(type, static_cast<std::uint64_t>(subdiv)); n > kMaxShapeTriangles)
            r.fail("subdivisions", std::to_string(subdiv) + " gives " + std::to_string(n) + " triangles; a " + type +
                                       " may have at most " + std::to_string(kMaxShapeTriangles) +
                                       " (split it into several shapes or use a mesh)");
        auto positive = [&](const std::string& key) {
            const auto v = r.number(key);
            if (!v) r.fail_entry("type '" + type + "' needs '" + key + "'");
            if (!(*v > 0.0)) r.fail(key, "must be positive");
            return *v;
        };
        TriangleMesh mesh;
        if (type == "rectangle" || type == "disk") {
            const Vec3 n = unit(r, "normal", r.vec3("normal").value_or(Vec3(0, 0, 1)));
            if (type == "rectangle") {
                const Vec3 up = unit(r, "up", r.vec3("up").value_or(default_up(n)));
                if (glm::length(glm::cross(up, n)) < 1e-6) r.fail("up", "must not be parallel to 'normal'");
                const auto size = r.numbers("size", 2);
                if (!size) r.fail_entry("type 'rectangle' needs 'size' = [w, h]");
                if (!((*size)[0] > 0.0 && (*size)[1] > 0.0)) r.fail("size", "must be positive");
                mesh = make_rectangle(center, n, up, (*size)[0], (*size)[1], subdiv);
            } else {
                mesh = make_disk(center, n, positive("radius"), subdiv);
            }
        } else if (type == "box") {
            const auto size = r.vec3("size");
            if (!size) r.fail_entry("type 'box' needs 'size' = [x, y, z]");
            if (!(size->x > 0.0 && size->y > 0.0 && size->z > 0.0)) r.fail("size", "must be positive");
            mesh = make_box(center, *size, subdiv, r.boolean("inward").value_or(false));
        } else if (type == "sphere") {
            mesh = make_sphere(center, positive("radius"), subdiv, r.boolean("inward").value_or(false));
        } else {
            r.fail("type", "unknown shape type '" + type + "' (expected rectangle, box, sphere or disk)");
        }
        r.finish();
        const std::size_t first = scene.triangles.size();
        add_triangles(mesh, mat, r);
        if (name) {
            if (named_shapes.count(*name)) r.fail("name", "shape '" + *name + "' is defined twice");
            named_shapes[*name] = {first, scene.triangles.size()};
        }
    }

    // The light's positions: `position`, a list `positions`, or a `grid` (first point,
    // spacing along scene x and y, counts) - one photometry shared by all of them.
    std::vector<Vec3> light_positions(TableReader& r, const std::string& type) {
        const int given = int(r.has("position")) + int(r.has("positions")) + int(r.has("grid"));
        if (given == 0) r.fail_entry("type '" + type + "' needs 'position' (or 'positions' or 'grid')");
        if (given > 1) r.fail_entry("give one of 'position', 'positions' and 'grid'");
        if (const auto p = r.vec3("position")) return {*p};
        std::vector<Vec3> out;
        constexpr std::size_t kMaxCopies = 100000;
        if (const toml::array* a = r.array("positions")) {
            for (const toml::node& n : *a) {
                const toml::array* v = n.as_array();
                if (v == nullptr || v->size() != 3 ||
                    !std::all_of(v->begin(), v->end(), [](const toml::node& x) { return x.is_number(); }))
                    r.fail("positions", "expected a list of [x, y, z] positions");
                out.emplace_back(v->get(0)->value<double>().value(), v->get(1)->value<double>().value(),
                                 v->get(2)->value<double>().value());
            }
            if (out.empty()) r.fail("positions", "needs at least one position");
            if (out.size() > kMaxCopies) r.fail("positions", "at most " + std::to_string(kMaxCopies) + " positions");
            return out;
        }
        const toml::table* g = r.table("grid");
        if (g == nullptr)
            r.fail("grid", "expected a table { first = [x, y, z], spacing = [dx, dy], count = [nx, ny] }");
        TableReader gr(*g, fname, r.context() + " grid", "light.grid");
        const auto first = gr.vec3("first");
        const auto spacing = gr.numbers("spacing", 2);
        const auto count = gr.numbers("count", 2);
        if (!first || !spacing || !count)
            gr.fail_entry("needs 'first' = [x, y, z], 'spacing' = [dx, dy] and 'count' = [nx, ny]");
        for (double c : *count)
            if (!(c >= 1.0 && c == std::floor(c) && c <= double(kMaxCopies)))
                gr.fail("count", "must be whole numbers >= 1");
        if ((*count)[0] * (*count)[1] > double(kMaxCopies))
            gr.fail("count", "at most " + std::to_string(kMaxCopies) + " lights in a grid");
        gr.finish();
        for (int j = 0; j < int((*count)[1]); ++j)
            for (int k = 0; k < int((*count)[0]); ++k)
                out.push_back(*first + Vec3(k * (*spacing)[0], j * (*spacing)[1], 0.0));
        return out;
    }

    // aim / rotation_deg / c0 / tilt_deg -> the photometric frame (orientation.hpp).
    Frame placement_frame(TableReader& r, const char* aim_key) {
        LuminairePlacement pl;
        pl.aim = unit(r, aim_key, r.vec3(aim_key).value_or(Vec3(0, 0, -1)));
        if (r.has("c0") && r.has("rotation_deg")) r.fail("c0", "give 'c0' or 'rotation_deg', not both");
        if (const auto c0 = r.vec3("c0")) pl.c0 = *c0;
        for (const auto& [key, value] : {std::pair<const char*, double*>{"rotation_deg", &pl.rotation_deg},
                                         {"tilt_deg", &pl.tilt_deg},
                                         {"roll_deg", &pl.roll_deg},
                                         {"spin_deg", &pl.spin_deg}}) {
            *value = r.number(key).value_or(0.0);
            if (!(std::abs(*value) <= 360.0)) r.fail(key, "must lie in [-360, 360] degrees");
        }
        try {
            return luminaire_frame(pl);
        } catch (const std::invalid_argument&) {
            r.fail("c0", "must not be parallel to the '" + std::string(aim_key) + "'");
        }
    }

    // A factor key in (0, hi].
    double factor(TableReader& r, const std::string& key, double fallback, double hi) {
        const double v = r.number(key).value_or(fallback);
        if (!(v > 0.0 && v <= hi)) r.fail(key, "must lie in (0, " + fmt_count(hi) + "], got " + fmt_count(v));
        return v;
    }

    std::vector<Light> parse_light(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("light", i, t), "light");
        Light l;
        const std::string type = r.string("type").value_or("");
        l.label = "light " + std::to_string(i + 1) + " (" + type + ")";
        auto flux = [&](const char* key) {
            const auto f = r.number(key);
            if (!f) r.fail_entry("type '" + type + "' needs '" + key + "'");
            if (!(*f > 0.0)) r.fail(key, "must be positive, got " + std::to_string(*f));
            return *f;
        };
        std::vector<Vec3> positions{Vec3(0.0)};
        if (type == "point" || type == "spot") positions = light_positions(r, type);
        l.maintenance_factor = factor(r, "maintenance_factor", scene.maintenance_factor, 1.0);
        l.dimming = factor(r, "dimming", 1.0, 1.0);
        if (type == "point") {
            l.type = LightType::point;
            l.frame = placement_frame(r, "aim");
            l.aim = l.frame.n;
            if (r.has("ies") && r.has("photometry")) r.fail("photometry", "give 'photometry' or 'ies', not both");
            const std::string file_key = r.has("ies") ? "ies" : "photometry";
            if (const auto file = r.string(file_key)) {
                l.multiplier = r.number("multiplier").value_or(1.0);
                if (!(l.multiplier > 0.0)) r.fail("multiplier", "must be positive");
                l.lamp_factor = factor(r, "lamp_factor", 1.0, 100.0);
                if (r.has("flux_lm"))
                    r.fail("flux_lm", "with '" + file_key + "' the flux comes from the file (use 'multiplier')");
                const auto set = r.integer("lamp_set").value_or(1);
                if (set < 1 || set > 20) r.fail("lamp_set", "must lie in [1, 20]");
                // Lights sharing a file share its photometry and sampling table (about
                // 1 MB each: one copy keeps it in cache).
                const std::string key = fs::weakly_canonical(resolve(*file)).string() + "#" + std::to_string(set);
                auto cached = photometry_cache.find(key);
                if (cached == photometry_cache.end()) {
                    Photometry photometry;
                    try {
                        photometry = load_photometry(resolve(*file), static_cast<int>(set));
                    } catch (const InputError& e) {  // say which scene entry named the file
                        r.fail(r.has("lamp_set") && std::string(e.what()).find("lamp set") != std::string::npos
                                   ? "lamp_set"
                                   : file_key,
                               e.what());
                    }
                    std::shared_ptr<const PhotometryDistribution> dist;
                    try {
                        dist = std::make_shared<const PhotometryDistribution>(photometry);
                    } catch (const std::invalid_argument&) {  // no light on the sampling grid
                        r.fail(file_key, resolve(*file).string() +
                                             ": its light lies in too narrow a beam for the 0.5 degree sampling grid");
                    }
                    for (const std::string& note : photometry.notes) scene.warnings.push_back(note);
                    cached = photometry_cache
                                 .emplace(key, std::make_pair(std::make_shared<const Photometry>(std::move(photometry)),
                                                              std::move(dist)))
                                 .first;
                }
                l.photometry = cached->second.first;
                l.distribution = cached->second.second;
                const std::string emission = r.string("emission").value_or("opening");
                if (emission == "opening") l.opening = l.photometry->opening;
                else if (emission != "point")
                    r.fail("emission", "must be \"opening\" or \"point\", got '" + emission + "'");
                // The file's own flux (exact for its interpolant), not the sampling table's,
                // with the lamp's output at this tilt (LM-63 TILT data).
                if (!l.photometry->tilt.empty()) l.tilt_factor = l.photometry->tilt.at(tilt_from_nadir_deg(l.frame));
                l.flux_lm = l.photometry->flux_lm() * l.multiplier * l.lamp_factor * l.dimming * l.tilt_factor;
                if (!(l.flux_lm > 0.0))
                    r.fail(file_key, l.tilt_factor > 0.0
                                         ? "the photometry carries no flux"
                                         : "the file's TILT multiplier is 0 at this luminaire's tilt of " +
                                               fmt_count(tilt_from_nadir_deg(l.frame)) + " degrees");
                if (!std::isfinite(l.flux_lm))
                    r.fail("multiplier", "the flux of the file times the multiplier is too large");
            } else {
                for (const char* k : {"emission", "lamp_set", "lamp_factor", "multiplier"})
                    if (r.has(k)) r.fail(k, "applies to a light with 'photometry' (or 'ies') only");
                l.flux_lm = flux("flux_lm") * l.dimming;
            }
        } else if (type == "spot") {
            l.type = LightType::spot;
            l.flux_lm = flux("flux_lm") * l.dimming;
            if (r.has("aim") && r.has("direction")) r.fail("aim", "give 'direction' or 'aim', not both");
            l.frame = placement_frame(r, r.has("aim") ? "aim" : "direction");
            l.aim = l.frame.n;
            const auto half = r.number("half_angle_deg");
            if (!half) r.fail_entry("type 'spot' needs 'half_angle_deg'");
            if (!(*half > 0.0 && *half <= 180.0)) r.fail("half_angle_deg", "must lie in (0, 180]");
            l.cos_half_angle = std::cos(*half * kPi / 180.0);
        } else if (type == "area") {
            l.type = LightType::area;
            l.flux_lm = flux("flux_lm") * l.dimming;
            const auto shape = r.string("shape");
            if (!shape) r.fail_entry("type 'area' needs 'shape' (the name of a [[shape]])");
            const auto it = named_shapes.find(*shape);
            if (it == named_shapes.end()) r.fail("shape", "no [[shape]] is named '" + *shape + "'");
            EmitterSurface& s = l.surface;
            for (std::size_t tri = it->second.first; tri < it->second.second; ++tri) {
                const glm::uvec3 v = scene.triangles[tri];
                const Vec3 a(scene.vertices[v.x]), b(scene.vertices[v.y]), c(scene.vertices[v.z]);
                s.p0.push_back(a);
                s.e1.push_back(b - a);
                s.e2.push_back(c - a);
                s.normal.push_back(scene.triangle_normal[tri]);
                s.scene_triangle.push_back(static_cast<int>(tri));
                s.area_m2 += scene.triangle_area_m2[tri];
                s.cdf.push_back(s.area_m2);
            }
            if (!(s.area_m2 > 0.0 && std::isfinite(s.area_m2)))
                r.fail("shape", "shape '" + *shape + "' has no area to emit from (its triangles are degenerate)");
            for (double& c : s.cdf) c /= s.area_m2;
        } else if (type == "directional") {
            l.type = LightType::directional;
            const auto d = r.vec3("direction");
            if (!d) r.fail_entry("type 'directional' needs 'direction'");
            l.aim = unit(r, "direction", *d);
            l.frame = Frame::around(l.aim);
            l.illuminance_lx = flux("illuminance_lx") * l.dimming;
        } else {
            r.fail("type", "unknown light type '" + type + "' (expected point, spot, area or directional)");
        }
        const std::size_t nb = scene.bands.size();
        l.band_share.assign(nb, 1.0);
        if (r.has("colour")) {
            if (t["colour"].is_array()) l.band_share = *r.numbers("colour", nb);
            else l.band_share.assign(nb, *r.number("colour"));
            double sum = 0.0;
            for (double c : l.band_share) {
                if (!(c >= 0.0)) r.fail("colour", "shares must not be negative");
                sum += c;
            }
            if (!(sum > 0.0)) r.fail("colour", "needs a positive share in some band");
            if (!std::isfinite(sum)) r.fail("colour", "shares are too large");
        }
        double share_sum = 0.0;  // Light::band_share is normalised
        for (double c : l.band_share) share_sum += c;
        for (double& c : l.band_share) c /= share_sum;
        r.finish();
        std::vector<Light> out;
        for (std::size_t k = 0; k < positions.size(); ++k) {
            Light copy = l;
            copy.position = positions[k];
            if (positions.size() > 1) copy.label += " #" + std::to_string(k + 1);
            out.push_back(std::move(copy));
        }
        return out;
    }

    // [[detector.task_area]] (or task_area = [{...}]): name, cells = [i0, i1, j0, j1],
    // half-open and 0-based like a run target's [i0:i1,j0:j1].
    void parse_task_areas(TableReader& r, const toml::array& areas, Detector& d) {
        if (d.type != DetectorType::illuminance)
            r.fail("task_area", std::string("task areas belong to illuminance detectors (this one is ") +
                                    detector_type_name(d.type) + ": no uniformity U0 is computed for it)");
        for (std::size_t k = 0; k < areas.size(); ++k) {
            const toml::table* t = areas[k].as_table();
            if (t == nullptr)
                r.fail("task_area", "expected [[detector.task_area]] tables { name, cells = [i0, i1, j0, j1] }");
            std::string context = r.context() + " task_area #" + std::to_string(k + 1);
            if (const auto n = (*t)["name"].value<std::string>()) context += " '" + *n + "'";
            TableReader ar(*t, fname, context, "detector.task_area");
            const auto name = ar.string("name");
            if (!name || name->empty()) ar.fail_entry("needs a 'name'");
            if (name->find_first_of("/[]:. ") != std::string::npos)
                ar.fail("name", "may not contain '/', '[', ']', ':', '.' or spaces");
            for (const TaskArea& other : d.task_areas)
                if (other.name == *name) ar.fail("name", "task area '" + *name + "' is defined twice in this detector");
            const auto cells = ar.numbers("cells", 4);
            if (!cells) ar.fail_entry("needs 'cells' = [i0, i1, j0, j1] (cells i0 <= i < i1, j0 <= j < j1, from 0)");
            for (double c : *cells)
                if (c != std::floor(c) || c < 0)
                    ar.fail("cells", "expected four whole numbers [i0, i1, j0, j1], none negative");
            const std::vector<double>& c = *cells;
            if (!(c[0] < c[1] && c[1] <= d.nx && c[2] < c[3] && c[3] <= d.ny))
                ar.fail("cells", "[" + fmt_count(c[0]) + ", " + fmt_count(c[1]) + ", " + fmt_count(c[2]) + ", " +
                                     fmt_count(c[3]) + "] is empty or outside the " + std::to_string(d.nx) + " x " +
                                     std::to_string(d.ny) + " cells (need i0 < i1 <= nx, j0 < j1 <= ny)");
            const TaskArea a{*name, static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2]),
                             static_cast<int>(c[3])};
            ar.finish();
            d.task_areas.push_back(a);
        }
    }

    void parse_detector(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("detector", i, t), "detector");
        Detector d;
        const auto name = r.string("name");
        if (!name || name->empty()) r.fail_entry("needs a 'name'");
        for (const Detector& other : scene.detectors)
            if (other.name == *name) r.fail("name", "detector '" + *name + "' is defined twice");
        if (name->find_first_of("/[]:. ") != std::string::npos)
            r.fail("name", "may not contain '/', '[', ']', ':', '.' or spaces");
        d.name = *name;
        const std::string type = r.string("type").value_or("illuminance");
        if (type == "illuminance") d.type = DetectorType::illuminance;
        else if (type == "luminance") d.type = DetectorType::luminance;
        else if (type == "cylindrical") d.type = DetectorType::cylindrical;
        else if (type == "semicylindrical") d.type = DetectorType::semicylindrical;
        else
            r.fail("type", "unknown detector type '" + type +
                               "' (expected illuminance, luminance, cylindrical or semicylindrical)");
        const auto c = r.vec3("center");
        if (!c) r.fail_entry("needs 'center'");
        d.center = *c;
        d.normal = unit(r, "normal", r.vec3("normal").value_or(Vec3(0, 0, 1)));
        d.up = unit(r, "up", r.vec3("up").value_or(default_up(d.normal)));
        if (glm::length(glm::cross(d.up, d.normal)) < 1e-6) r.fail("up", "must not be parallel to 'normal'");
        const auto size = r.numbers("size", 2);
        if (!size) r.fail_entry("needs 'size' = [w, h]");
        if (!((*size)[0] > 0.0 && (*size)[1] > 0.0)) r.fail("size", "the detector has zero or negative area");
        d.size_u = (*size)[0];
        d.size_v = (*size)[1];
        if (const auto cells = r.numbers("cells", 2)) {
            const double nx = (*cells)[0], ny = (*cells)[1];
            if (!(nx >= 1 && ny >= 1 && nx == std::floor(nx) && ny == std::floor(ny)))
                r.fail("cells", "expected two positive whole numbers [nx, ny]");
            // Every cell costs 16 bytes per band in each copy of the tallies (the rank's
            // store, the reduction message, rank 0's reduced copy).
            if (nx * ny > kMaxDetectorCells)
                r.fail("cells", fmt_count(nx) + " x " + fmt_count(ny) + " = " + fmt_count(nx * ny) +
                                    " cells; a detector may have at most " + fmt_count(kMaxDetectorCells) +
                                    " (e.g. 10000 x 10000)");
            d.nx = static_cast<int>(nx);
            d.ny = static_cast<int>(ny);
        }
        if (const toml::array* areas = r.array("task_area")) parse_task_areas(r, *areas, d);
        if (d.type == DetectorType::luminance) {
            d.view_direction = unit(r, "view_direction", r.vec3("view_direction").value_or(d.normal));
            d.half_angle_deg = r.number("half_angle_deg").value_or(5.0);
            if (!(d.half_angle_deg > 0.0 && d.half_angle_deg <= 90.0)) r.fail("half_angle_deg", "must lie in (0, 90]");
            if (std::abs(glm::dot(d.view_direction, d.normal)) < 1e-3)
                r.fail("view_direction", "must not lie in the detector plane");
        }
        if (d.cylinders()) parse_cylinder(r, d);
        r.finish();
        d.finalize();
        if (!(d.value_per_lm() > 0.0 && std::isfinite(d.value_per_lm())))
            r.fail_entry("its cells are too small (or its cone too narrow) to measure anything");
        if (d.type == DetectorType::luminance && d.cone_below_plane())
            scene.warnings.push_back(fname + ": " + entry_name("detector", i, t) +
                                     ": the view cone dips below the detector plane (view angle + half_angle_deg > "
                                     "90): its luminance is then underestimated");
        scene.detectors.push_back(d);
    }

    // Cylindrical and semicylindrical detectors: the small cylinder at each point, its
    // axis the grid's normal. A finite cylinder's lateral mean differs from the point
    // value by about -(pi r / 2 rho)(1 - 1.5 sin^2 gamma) for a light at horizontal
    // distance rho (first order in r), the height only in second order; so the default is
    // thin and tall, r = 1 cm, h = 20 cm: within 2 % of the point value for lights 0.5 m
    // or more to the side and 1.5 m above, 0.1 % beyond 1.5 m (docs/VALIDATION.md), while
    // its 2 pi r h = 0.0126 m^2 still catches photons like an 11 cm x 11 cm cell.
    void parse_cylinder(TableReader& r, Detector& d) {
        d.radius_m = r.number("radius").value_or(0.01);
        d.height_m = r.number("height").value_or(0.2);
        if (!(d.radius_m > 0.0)) r.fail("radius", "must be positive (metres)");
        if (!(d.height_m > 0.0)) r.fail("height", "must be positive (metres)");
        if (d.type == DetectorType::semicylindrical) {
            const auto f = r.vec3("facing");
            if (!f) r.fail_entry("type 'semicylindrical' needs 'facing' (the direction its curved half faces)");
            d.facing = unit(r, "facing", *f);
            if (std::abs(glm::dot(d.facing, d.normal)) > 1e-6)
                r.fail("facing", "must be perpendicular to the cylinder axis (the detector's 'normal', default "
                                 "[0, 0, 1])");
        } else if (const auto h = r.string("horizontal")) {
            if (h->empty()) r.fail("horizontal", "needs the name of an illuminance [[detector]]");
            d.horizontal = *h;
        }
    }

    // A cylindrical detector's `horizontal` names an illuminance detector on the same grid
    // (the modelling ratio divides point by point); checked once every detector is known.
    void link_horizontal(const toml::table& t, std::size_t i) {
        Detector& d = scene.detectors[i];
        if (d.horizontal.empty()) return;
        TableReader r(t, fname, entry_name("detector", i, t), "detector");
        const auto it = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                     [&](const Detector& o) { return o.name == d.horizontal; });
        if (it == scene.detectors.end()) r.fail("horizontal", "no [[detector]] is named '" + d.horizontal + "'");
        if (it->type != DetectorType::illuminance)
            r.fail("horizontal", "detector '" + d.horizontal + "' is " + detector_type_name(it->type) +
                                     "; the modelling ratio needs an illuminance detector");
        const double scale = std::max({1.0, glm::length(d.center), d.size_u, d.size_v});
        std::string differs;
        if (glm::length(it->center - d.center) > 1e-9 * scale) differs = "center";
        else if (glm::dot(it->normal, d.normal) < 1.0 - 1e-12) differs = "normal";
        else if (glm::dot(it->v_axis, d.v_axis) < 1.0 - 1e-12) differs = "up";
        else if (std::abs(it->size_u - d.size_u) > 1e-9 * scale || std::abs(it->size_v - d.size_v) > 1e-9 * scale)
            differs = "size";
        else if (it->nx != d.nx || it->ny != d.ny) differs = "cells";
        if (!differs.empty())
            r.fail("horizontal", "detector '" + d.horizontal +
                                     "' must lie on the same grid as this one (center, "
                                     "normal, up, size, cells), but its '" +
                                     differs + "' differs");
        d.horizontal_index = static_cast<int>(it - scene.detectors.begin());
    }

    // [[observer]]: an eye and a line of sight for UGR (glare/observer.hpp), with its eye
    // detector appended to the detectors (after the user's).
    void parse_observer(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("observer", i, t), "observer");
        Observer o;
        o.name = r.string("name").value_or("observer_" + std::to_string(i + 1));
        if (o.name.empty()) r.fail("name", "must not be empty");
        if (o.name.find_first_of("/[]:. ") != std::string::npos)
            r.fail("name", "may not contain '/', '[', ']', ':', '.' or spaces");
        for (const Observer& other : scene.observers)
            if (other.name == o.name) r.fail("name", "observer '" + o.name + "' is defined twice");
        const auto pos = r.vec3("position");
        if (!pos) r.fail_entry("needs 'position' (the eye)");
        o.position = *pos;
        const auto view = r.vec3("view_direction");
        if (!view) r.fail_entry("needs 'view_direction' (the line of sight)");
        o.view_direction = unit(r, "view_direction", *view);
        // Guth's index is defined about a line of sight with a vertical beside it.
        if (std::abs(o.view_direction.z) > std::cos(10.0 * kPi / 180.0))
            r.fail("view_direction", "must lie more than 10 degrees from the vertical (CIE 117's line of sight is "
                                     "about horizontal)");
        // Side of the square eye detector: a head's width (0.2 m) is local on the scale over
        // which a room's indirect light changes (metres), and gathers 16 times the photons a
        // 5 cm one would.
        o.eye_detector_size_m = r.number("eye_detector_size").value_or(0.2);
        if (!(o.eye_detector_size_m > 0.0 && o.eye_detector_size_m <= 1.0))
            r.fail("eye_detector_size", "must lie in (0, 1] metres");
        r.finish();
        o.finalize();
        if (std::abs(o.view_direction.z) > std::sin(1.0 * kPi / 180.0))
            scene.warnings.push_back(fname + ": " + entry_name("observer", i, t) +
                                     ": the line of sight is not horizontal; CIE 117 assumes a horizontal one (UGR "
                                     "is computed about the given one, the eye detector stays vertical)");
        Detector d;
        d.name = "observer:" + o.name;
        d.type = DetectorType::illuminance;
        d.center = o.position;
        // Vertical, facing along the horizontal line of sight: it counts the light arriving
        // at the eye from in front (CIE 117's vertical illuminance at the eye).
        d.normal = glm::normalize(Vec3(o.view_direction.x, o.view_direction.y, 0.0));
        d.up = Vec3(0, 0, 1);
        d.size_u = d.size_v = o.eye_detector_size_m;
        d.indirect_only = true;
        d.observer = static_cast<int>(scene.observers.size());
        d.finalize();
        o.eye_detector = scene.detectors.size();
        scene.detectors.push_back(d);
        o.sources = glare_sources(o, scene.lights);
        if (o.sources.empty())
            o.notes.push_back("observer '" + o.name + "': no luminaire in the field of view: UGR is undefined");
        for (const std::string& n : o.notes) scene.warnings.push_back(fname + ": " + n);
        scene.observers.push_back(std::move(o));
    }

    void parse_camera(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("camera", i, t), "camera");
        Camera c;
        const auto name = r.string("name");
        if (!name || name->empty()) r.fail_entry("needs a 'name'");
        for (const Camera& other : scene.cameras)
            if (other.name == *name) r.fail("name", "camera '" + *name + "' is defined twice");
        c.name = *name;
        const auto pos = r.vec3("position");
        const auto target = r.vec3("target");
        if (!pos || !target) r.fail_entry("needs 'position' and 'target'");
        c.position = *pos;
        c.target = *target;
        if (glm::length(c.target - c.position) < 1e-9) r.fail("target", "must differ from 'position'");
        c.up = unit(r, "up", r.vec3("up").value_or(Vec3(0, 0, 1)));
        if (glm::length(glm::cross(c.up, c.target - c.position)) < 1e-9 * glm::length(c.target - c.position))
            r.fail("up", "must not be parallel to the viewing direction");
        c.fov_deg = r.number("fov_deg").value_or(60.0);
        if (!(c.fov_deg > 0.0 && c.fov_deg < 180.0)) r.fail("fov_deg", "must lie in (0, 180)");
        if (const auto size = r.numbers("size", 2)) {
            const double w = (*size)[0], h = (*size)[1];
            if (!(w >= 1 && h >= 1 && w <= 16384 && h <= 16384 && w == std::floor(w) && h == std::floor(h)))
                r.fail("size", "expected two whole numbers of pixels [width, height] up to 16384");
            c.width = static_cast<int>(w);
            c.height = static_cast<int>(h);
        }
        r.finish();
        scene.cameras.push_back(c);
    }

    void parse_run(TableReader& root) {
        RunConfig& run = scene.run;
        run.output = (fs::path(file.stem().string() + ".h5")).string();
        const toml::table* t = root.table("run");
        if (t == nullptr) return;
        TableReader r(*t, fname, "[run]", "run");
        run.seed = r.count("seed").value_or(run.seed);
        run.photons = r.count("photons").value_or(run.photons);
        if (run.photons == 0) r.fail("photons", "must be positive");
        auto nonneg = [&](const std::string& key, double def) {
            const double v = r.number(key).value_or(def);
            if (!(v >= 0.0)) r.fail(key, "must not be negative");
            return v;
        };
        run.time_limit_s = nonneg("time_limit_s", run.time_limit_s);
        run.report_every_s = nonneg("report_every_s", run.report_every_s);
        run.report_every_photons = r.count("report_every_photons").value_or(0);
        run.checkpoint_every_s = nonneg("checkpoint_every_s", run.checkpoint_every_s);
        if (auto o = r.string("output")) run.output = resolve(*o).string();
        if (auto c = r.string("checkpoint")) run.checkpoint = resolve(*c).string();
        run.sampler = r.string("sampler").value_or(run.sampler);
        if (const std::string why = sampler_unavailable(run.sampler); !why.empty()) r.fail("sampler", why);
        if (const auto reps = r.integer("replicates")) {
            if (const std::string why = replicates_invalid(*reps); !why.empty()) r.fail("replicates", why);
            run.replicates = static_cast<std::uint32_t>(*reps);
        }
        if (const auto mb = r.integer("max_bounces")) {
            if (*mb < 1 || *mb > 1000000) r.fail("max_bounces", "must lie in [1, 1000000]");
            run.max_bounces = static_cast<int>(*mb);
        }
        if (const toml::array* targets = r.array("target"))
            for (std::size_t i = 0; i < targets->size(); ++i) {
                const toml::table* tt = (*targets)[i].as_table();
                if (tt == nullptr) r.fail("target", "expected [[run.target]] tables");
                run.targets.push_back(parse_target(*tt, i));
            }
        r.finish();
    }

    Target parse_target(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, "[[run.target]] #" + std::to_string(i + 1), "run.target");
        Target g;
        g.on = r.string("on").value_or("global");
        if (g.on.rfind("observer:", 0) == 0) {
            // An observer's eye detector (one cell): its relative error is E_ind's, and
            // UGR's error is 8 / ln 10 = 3.47 times it (glare/ugr.hpp).
            g.detector = g.on;
            const auto det = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                          [&](const Detector& d) { return d.name == g.detector; });
            if (det == scene.detectors.end()) r.fail("on", "no [[observer]] is named '" + g.on.substr(9) + "'");
            g.i1 = det->nx;
            g.j1 = det->ny;
        } else if (g.on != "global") {
            if (g.on.rfind("detector:", 0) != 0)
                r.fail("on", "expected 'global', 'detector:NAME', 'detector:NAME[i0:i1,j0:j1]' or 'observer:NAME'");
            std::string rest = g.on.substr(9);
            const auto br = rest.find('[');
            g.detector = rest.substr(0, br);
            const auto det = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                          [&](const Detector& d) { return d.name == g.detector; });
            if (det == scene.detectors.end()) r.fail("on", "no [[detector]] is named '" + g.detector + "'");
            if (br != std::string::npos) {
                char close = 0;
                std::istringstream in(rest.substr(br + 1));
                char c1 = 0, c2 = 0, c3 = 0, extra = 0;
                if (!(in >> g.i0 >> c1 >> g.i1 >> c2 >> g.j0 >> c3 >> g.j1 >> close) || c1 != ':' || c2 != ',' ||
                    c3 != ':' || close != ']' || (in >> extra))
                    r.fail("on", "cell range must read [i0:i1,j0:j1]");
                if (!(0 <= g.i0 && g.i0 < g.i1 && g.i1 <= det->nx && 0 <= g.j0 && g.j0 < g.j1 && g.j1 <= det->ny))
                    r.fail("on", "cell range lies outside the " + std::to_string(det->nx) + " x " +
                                     std::to_string(det->ny) + " grid or is empty");
            } else {
                g.i1 = det->nx;
                g.j1 = det->ny;
            }
        }
        int kinds = 0;
        if (auto v = r.number("relative_error")) {
            g.relative_error = *v;
            ++kinds;
            if (!(*v > 0)) r.fail("relative_error", "must be positive");
        }
        if (auto v = r.number("absolute_error")) {
            g.absolute_error = *v;
            ++kinds;
            if (!(*v > 0)) r.fail("absolute_error", "must be positive");
        }
        if (auto v = r.count("photons_received")) {
            g.photons_received = static_cast<double>(*v);
            ++kinds;
            if (g.detector.empty()) r.fail("photons_received", "applies to a detector target only");
        }
        if (kinds != 1) r.fail_entry("needs exactly one of relative_error, absolute_error, photons_received");
        const std::string avg = r.string("averaging").value_or("quadratic");
        if (avg == "quadratic") g.averaging = Averaging::quadratic;
        else if (avg == "arithmetic") g.averaging = Averaging::arithmetic;
        else r.fail("averaging", "expected 'quadratic' or 'arithmetic'");
        r.finish();
        return g;
    }

    void finish_geometry() {
        if (scene.triangles.empty()) throw InputError(fname + ": the scene has no surfaces");
        scene.bounds_min = scene.bounds_max = Vec3(scene.vertices[scene.triangles[0].x]);
        for (const glm::uvec3& t : scene.triangles)
            for (int k = 0; k < 3; ++k) {
                const Vec3 v(scene.vertices[t[k]]);
                scene.bounds_min = glm::min(scene.bounds_min, v);
                scene.bounds_max = glm::max(scene.bounds_max, v);
            }
    }
};

}  // namespace

Scene load_scene(const fs::path& file) {
    Loader L;
    L.file = file;
    L.fname = file.string();
    L.scene.file = file;
    if (!fs::is_regular_file(file)) throw InputError(L.fname + ": no such scene file");
    toml::table root_table;
    try {
        root_table = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw InputError(L.fname + ":" + std::to_string(e.source().begin.line) +
                         ": TOML syntax error: " + std::string(e.description()));
    }
    TableReader root(root_table, L.fname, "top level", "");
    for (const auto& [key, node] : root_table)  // unknown tables first, before any file is read
        if (!scene_table_schema("").accepts(key.str()))
            throw InputError(L.fname + ":" + std::to_string(node.source().begin.line) + ": top level: unknown key '" +
                             std::string(key.str()) + "'");
    L.scene.name = file.stem().string();
    L.parse_scene_table(root);
    {
        const auto materials = L.tables_of(root, "material");
        for (std::size_t i = 0; i < materials.size(); ++i) L.parse_material(*materials[i], i);
        const auto meshes = L.tables_of(root, "mesh");
        for (std::size_t i = 0; i < meshes.size(); ++i) L.parse_mesh(*meshes[i], i);
        const auto shapes = L.tables_of(root, "shape");
        for (std::size_t i = 0; i < shapes.size(); ++i) L.parse_shape(*shapes[i], i);
    }
    L.finish_geometry();
    std::vector<Light> lights;
    const auto light_tables = L.tables_of(root, "light");
    for (std::size_t i = 0; i < light_tables.size(); ++i)
        for (Light& l : L.parse_light(*light_tables[i], i)) lights.push_back(std::move(l));
    if (lights.empty()) throw InputError(L.fname + ": the scene has no [[light]]");
    // Directional beams cover the scene's bounding sphere, started just outside it.
    const Vec3 mid = 0.5 * (L.scene.bounds_min + L.scene.bounds_max);
    const double radius = 0.5 * glm::length(L.scene.bounds_max - L.scene.bounds_min) * 1.001 + 1e-6;
    for (Light& l : lights)
        if (l.type == LightType::directional) {
            l.beam_radius = radius;
            l.beam_center = mid - 1.01 * radius * l.aim;
            l.flux_lm = l.illuminance_lx * kPi * radius * radius;
        }
    double total_flux = 0.0;
    for (const Light& l : lights) {
        total_flux += l.flux_lm;
        if (!(l.flux_lm > 0.0 && std::isfinite(l.flux_lm)) || !std::isfinite(total_flux))
            throw InputError(L.fname + ": " + l.label + ": its flux (" + fmt_count(l.flux_lm) +
                             " lm) makes the total flux of the scene too large or not positive");
    }
    L.scene.lights = LightSet(std::move(lights));
    if (!L.scene.lights.maintenance_factor_uniform())
        L.scene.warnings.push_back("maintenance factors differ between lights: results are initial values, and the "
                                   "maintained ones luxtrace reports use the flux-weighted mean factor (" +
                                   fmt_count(L.scene.lights.maintenance_factor()) + ")");
    const auto detector_tables = L.tables_of(root, "detector");
    for (std::size_t i = 0; i < detector_tables.size(); ++i) L.parse_detector(*detector_tables[i], i);
    for (std::size_t i = 0; i < detector_tables.size(); ++i) L.link_horizontal(*detector_tables[i], i);
    const auto observer_tables = L.tables_of(root, "observer");
    for (std::size_t i = 0; i < observer_tables.size(); ++i) L.parse_observer(*observer_tables[i], i);
    const auto camera_tables = L.tables_of(root, "camera");
    for (std::size_t i = 0; i < camera_tables.size(); ++i) L.parse_camera(*camera_tables[i], i);
    L.parse_run(root);
    root.finish();
    return std::move(L.scene);
}

}  // namespace luxtrace
