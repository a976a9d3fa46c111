#include "luxtrace/scene/scene_schema.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace luxtrace {

bool SceneTableSchema::accepts(std::string_view key) const {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

const std::vector<SceneTableSchema>& scene_schema() {
    // One place to add a key (docs/REFERENCE.md §2 documents each with its type, default and
    // unit). Kept as a table, one scene table per entry, not one key per line:
    // clang-format off
    static const std::vector<SceneTableSchema> schema = {
        {"", {"scene", "material", "mesh", "shape", "light", "light_scene", "detector", "camera", "run", "observer",
             "site", "portal", "annual", "radiance"}},
        {"radiance", {"file", "scale", "photometry"}},
        {"annual",
         {"weather", "sky_mf", "sky", "cie_type", "ground_reflectance", "occupied_hours", "year", "ladybug_folder",
          "direct", "direct_sky_rays", "direct_sun_rays", "indirect", "gather_rays", "gather_patch_m",
          "sun_group_days"}},
        {"portal", {"shape", "flip"}},
        {"site",
         {"latitude_deg", "longitude_deg", "utc_offset_h", "elevation_m", "north", "time", "pressure_mbar",
          "temperature_c", "delta_t_s"}},
        {"scene", {"name", "bands", "maintenance_factor"}},
        {"material",
         {"name", "type", "reflectance", "specular_reflectance", "ior", "transmittance", "diffuse_reflectance",
          "diffuse_transmittance", "specular_transmittance", "refractive_index", "angles_deg", "transmittance_at",
          "reflectance_at", "roughness"}},
        {"mesh", {"file", "material", "transform"}},
        {"mesh.transform", {"translate", "rotate_deg", "scale"}},
        {"shape", {"type", "name", "material", "center", "normal", "up", "size", "radius", "subdivisions", "inward"}},
        {"light",
         {"type", "position", "positions", "grid", "flux_lm", "photometry", "ies", "multiplier", "lamp_factor",
          "lamp_set", "emission", "aim", "direction", "c0", "rotation_deg", "tilt_deg", "roll_deg", "spin_deg",
          "half_angle_deg", "shape", "illuminance_lx", "dimming", "maintenance_factor", "colour", "group", "direct_normal_lx",
          "sun_altitude_deg", "sun_azimuth_deg", "sky", "cie_type", "diffuse_horizontal_lx", "zenith_luminance_cd_m2",
          "diffuse_horizontal_w_m2", "direct_normal_w_m2", "dew_point_c",
          "ground_reflectance"}},
        {"light.grid", {"first", "spacing", "count"}},
        {"light_scene", {"name", "dimming"}},
        {"detector",
         {"name", "type", "center", "normal", "up", "size", "cells", "view_direction", "half_angle_deg", "radius",
          "height", "facing", "horizontal", "task_area", "daylight_factor", "en17037", "points", "radius_m"}},
        {"detector.task_area", {"name", "cells"}},
        {"detector.en17037", {"target_df", "minimum_df"}},
        {"observer", {"name", "position", "view_direction", "eye_detector_size"}},
        {"camera", {"name", "position", "target", "up", "fov_deg", "size"}},
        {"run",
         {"seed", "photons", "time_limit_s", "report_every_s", "report_every_photons", "output", "checkpoint",
          "checkpoint_every_s", "sampler", "replicates", "max_bounces", "group_maps", "bvh_quality", "target"}},
        {"run.target", {"on", "relative_error", "absolute_error", "photons_received", "averaging", "scene"}},
    };
    // clang-format on
    return schema;
}

const SceneTableSchema& scene_table_schema(std::string_view path) {
    for (const SceneTableSchema& t : scene_schema())
        if (t.path == path) return t;
    throw std::logic_error("scene_schema.cpp lists no table '" + std::string(path) + "'");
}

}  // namespace luxtrace
