#pragma once
// Internal to load_scene(): the state its steps share and the steps themselves, one file
// per concept (geometry_loader.cpp, light_loader.cpp, light_scene_loader.cpp,
// detector_loader.cpp, camera_loader.cpp, run_loader.cpp). load_scene() (scene_loader.cpp)
// calls them in the order below; a step may rely on what the steps before it have put
// into the scene.
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/scene/shapes.hpp"
#include "toml_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace::detail {

struct SceneLoad {
    std::filesystem::path file;
    std::string fname;         // the file as given, for messages
    AnnualSkyShare sky_share;  // how the ranks share building an [annual] year of skies
    Scene scene;
    // [[shape]] name -> its triangles [first, last) in scene.triangles, for area lights.
    std::map<std::string, std::pair<std::size_t, std::size_t>> named_shapes;
    // What [[radiance]] models bring besides surfaces (radiance_loader.cpp): lights made
    // whole (area and distant sources), sky and sun lights as [[light]] tables for
    // read_lights to read like the user's, and the openings of `illum` surfaces.
    struct RadianceLight {
        toml::table table;  // a [[light]] table (sky, sun), or empty when `light` is set
        Light light;
        std::string label;
        std::optional<int> day_of_year;  // a Perez sky's day (gendaylit's), not the [site]'s
    };
    struct RadiancePortal {
        std::string name;
        std::vector<std::size_t> triangles;  // scene triangles of the opening
        std::string where;                   // "file:line" of the illum surface
    };
    std::vector<RadianceLight> radiance_lights;
    std::vector<RadiancePortal> radiance_portals;

    // The folder relative paths start from: the scene file's, or for a bare Radiance run
    // (load_radiance_scene) the working directory ("").
    std::filesystem::path folder;
    // A path in the scene file, relative to `folder` unless absolute.
    std::filesystem::path resolve(const std::string& path) const;
};

// What each step's reader holds: the load it adds to, and short names for its scene and file.
struct StepReader {
    explicit StepReader(SceneLoad& l) : load(l), scene(l.scene), fname(l.fname) {}

    SceneLoad& load;
    Scene& scene;
    const std::string& fname;
};

// The tables of a top-level array of tables ([[key]]); none if the key is absent.
std::vector<const toml::table*> tables_of(TableReader& root, const std::string& key);
// "[[kind]] #i 'name'" for messages (i from 0; shown from 1).
std::string entry_name(const std::string& kind, std::size_t i, const toml::table& t);
// The key's vector normalised; an error if it is (about) zero.
Vec3 unit_vector(TableReader& r, const std::string& key, Vec3 v);
// A number as the user would write it (up to 15 significant digits).
std::string fmt_number(double v);

// What material_of returns for a triangle that is not to be placed (an ies2rad luminaire's
// emitting face, whose light the luminaire's photometry carries).
inline constexpr std::uint32_t kLeaveOutTriangle = UINT32_MAX;
// Appends the mesh's triangles to the scene, triangle t with material material_of(t); leaves
// out degenerate ones and those of kLeaveOutTriangle. Returns each mesh triangle's index in
// the scene (-1 if left out).
// `fail` is called (and must throw) for a scene grown too large or a vertex out of range.
// material_of is called once per triangle, in order, on the calling thread; the areas and
// normals are computed in parallel.
std::vector<std::int64_t> add_mesh_triangles(SceneLoad& load, const TriangleMesh& mesh,
                                             const std::function<std::uint32_t(std::size_t)>& material_of,
                                             const std::function<void(const std::string&)>& fail);
// Room in the scene's per-triangle arrays for `more` triangles (and as many vertices) than
// it has, so that adding many meshes copies none of them.
void reserve_triangles(SceneLoad& load, std::size_t more);
// The scene triangles as a surface to emit from, uniform in area (any order, any planes).
EmitterSurface triangles_surface(const Scene& scene, const std::vector<std::size_t>& triangles);

// The triangles of [[shape]] `name` as a surface to emit from (area lights, portals),
// uniform in area; refuses (at `key`) an unknown shape or one without area (light_loader.cpp).
EmitterSurface shape_surface(const SceneLoad& load, const TableReader& r, const std::string& key,
                             const std::string& name);

// Light group and light scene names go into the result's HDF5 group names and into
// `--scene "a=0.5,b=1"`: not empty, and only letters, digits, '_', '-' and '.'.
void check_group_name(const TableReader& r, const std::string& key, const std::string& name);

// The steps of load_scene(), in order.
void read_scene_table(SceneLoad& load, TableReader& root);  // scene_loader.cpp
// [site]: Scene::site (the sun and sky lights read it).
void read_site(SceneLoad& load, TableReader& root);
// [[material]], [[mesh]], [[shape]]; the scene's bounds. Refuses a scene without surfaces.
void read_geometry(SceneLoad& load, TableReader& root);
// [[radiance]]: Radiance models' surfaces and materials (called by read_geometry, after the
// shapes), their lights and portals kept in the load for read_lights and read_portals.
void read_radiance_models(SceneLoad& load, TableReader& root);
// [[light]]: Scene::lights and Scene::light_groups (directional beams need the bounds).
// Refuses a scene without lights.
void read_lights(SceneLoad& load, TableReader& root);
// [annual]: the weather file's year of skies as lights, one light group per sky patch, the
// ground and every hour's sun (annual_loader.cpp); called by read_lights.
void read_annual(SceneLoad& load, TableReader& root, std::vector<Light>& lights, std::vector<std::string>& groups);
// [[portal]]: every sun and sky light becomes one light per opening (portal_loader.cpp).
void read_portals(SceneLoad& load, TableReader& root);
// [[light_scene]]: Scene::light_scenes, weights per light group.
void read_light_scenes(SceneLoad& load, TableReader& root);
// [[detector]] with their task areas and cylinders.
void read_detectors(SceneLoad& load, TableReader& root);
// [[observer]]: each with its eye detector appended after the user's detectors (needs the lights).
void read_observers(SceneLoad& load, TableReader& root);
void read_cameras(SceneLoad& load, TableReader& root);
// Beams (directional, sun, sky) cover the sphere around the geometry and every detector, so
// no detector lies outside the light they bring; their fluxes follow from it (light_loader.cpp).
void cover_detectors_with_beams(SceneLoad& load);
// [run] and its [[run.target]] (needs the light scenes, detectors and observers).
void read_run(SceneLoad& load, TableReader& root);

}  // namespace luxtrace::detail
