#pragma once
// The whole simulated world after loading: one triangle soup with a material per
// triangle, the lights, the detectors and the run settings. Built once per rank and
// then shared read-only by its threads.
#include "luxtrace/annual/annual_sky.hpp"
#include "luxtrace/core/math.hpp"
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/glare/observer.hpp"
#include "luxtrace/light/light_set.hpp"
#include "luxtrace/light/site.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/scene/run_config.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

// A named view for `luxtrace render` ([[camera]] in the scene file).
struct Camera {
    std::string name;
    Vec3 position{0.0}, target{0, 1, 0}, up{0, 0, 1};
    double fov_deg = 60.0;  // horizontal field of view
    int width = 800, height = 600;
};

// [[light_scene]]: a named linear combination of the light groups (issue 22). Groups the
// scene does not name are off.
struct LightScene {
    std::string name;
    std::vector<double> weights;  // per light group (Scene::light_groups), 0 = off
};

// A bare Radiance model run (`luxtrace run sky.rad model.rad --sensors grid.pts`): the scene
// of a [[radiance]] table per model, in order, and a points detector on the sensor file
// (named after it), with every other key at its default; the scene is named after the last
// model. docs/RADIANCE.md "Running Radiance models".
struct RadianceRun {
    std::vector<std::filesystem::path> models;
    std::optional<std::filesystem::path> sensors;
    std::optional<double> sensor_radius_m;
    double scale = 1.0;  // metres per model unit
    // `--target` of a run with sensors: a [[run.target]] on the sensors' relative error
    // (pooled quadratically over them, eq. 9) instead of the global map's.
    std::optional<double> sensors_relative_error;
};
struct Scene {
    std::filesystem::path file;
    std::string name;
    std::vector<std::string> bands{"Y"};
    std::vector<Material> materials;
    // Geometry in scene coordinates (double: a model placed kilometres from the origin
    // keeps its millimetres; Embree gets float coordinates relative to the scene's centre).
    std::vector<Vec3> vertices;
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> triangle_material;
    std::vector<double> triangle_area_m2;
    std::vector<Vec3> triangle_normal;  // unit geometric normal (front side)
    LightSet lights;
    // [site]: where and when, for the sun's position (daylight, docs/DAYLIGHT.md).
    Site site;
    // The light groups, in order of first appearance; lights without `group` are in
    // kDefaultLightGroup. A scene without groups has exactly that one.
    static constexpr const char* kDefaultLightGroup = "default";
    std::vector<std::string> light_groups{kDefaultLightGroup};
    std::vector<LightScene> light_scenes;
    // [annual]: the year of skies whose patches and suns are the light groups (docs/ANNUAL.md).
    std::optional<AnnualSetup> annual;
    std::vector<Detector> detectors;  // the user's, then one eye detector per observer
    std::vector<Observer> observers;
    std::vector<Camera> cameras;
    RunConfig run;
    std::vector<std::string> warnings;
    // [[radiance]] models: each modifier and what luxtrace makes of it, "file:line: TYPE
    // NAME -> ...; approximations" (radiance_materials.hpp), for `luxtrace check`.
    std::vector<std::string> radiance_modifiers;
    // A bare Radiance model run: what it was made from (absolute paths), for the result's
    // root attributes and for reloading it (render).
    std::optional<RadianceRun> radiance_run;
    // [scene] maintenance_factor: the default of every light's (EN 12464-1 MF).
    double maintenance_factor = 1.0;
    Vec3 bounds_min{0.0}, bounds_max{0.0};

    int band_count() const { return static_cast<int>(bands.size()); }
    std::size_t triangle_count() const { return triangles.size(); }
    double total_area_m2() const;
    // Length scale for the renderer's ray offsets: a small fraction of the scene's size
    // (the photon tracer derives its offsets from each hit point's error, ray_offset.hpp).
    double ray_epsilon_m() const;
};

// Parse and validate a scene file; throws InputError naming the file and line or key.
// `sky_share`: how the ranks share building an [annual] year of skies (annual_sky.hpp).
Scene load_scene(const std::filesystem::path& file, const AnnualSkyShare& sky_share = {});

Scene load_radiance_scene(const RadianceRun& run);
// Whether a file given as a scene is a Radiance model (.rad, .mat, .sky) by its extension.
bool is_radiance_file(const std::filesystem::path& file);

// The layout of the scene's tallies: its triangles, bands, light groups, replicates and
// detector cells (tally.hpp).
TallyLayout tally_layout(const Scene& scene);

}  // namespace luxtrace
