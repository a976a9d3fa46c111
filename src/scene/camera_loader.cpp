// [[camera]] -> the scene's named views for `luxtrace render` (docs/REFERENCE.md §2).
#include "scene_loader.hpp"

#include <cmath>

namespace luxtrace::detail {

namespace {

Camera parse_camera(SceneLoad& load, const toml::table& t, std::size_t i) {
    TableReader r(t, load.fname, entry_name("camera", i, t), "camera");
    Camera c;
    const auto name = r.string("name");
    if (!name || name->empty()) r.fail_entry("needs a 'name'");
    for (const Camera& other : load.scene.cameras)
        if (other.name == *name) r.fail("name", "camera '" + *name + "' is defined twice");
    c.name = *name;
    const auto pos = r.vec3("position");
    const auto target = r.vec3("target");
    if (!pos || !target) r.fail_entry("needs 'position' and 'target'");
    c.position = *pos;
    c.target = *target;
    if (glm::length(c.target - c.position) < 1e-9) r.fail("target", "must differ from 'position'");
    c.up = unit_vector(r, "up", r.vec3("up").value_or(Vec3(0, 0, 1)));
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
    return c;
}

}  // namespace

void read_cameras(SceneLoad& load, TableReader& root) {
    const auto tables = tables_of(root, "camera");
    for (std::size_t i = 0; i < tables.size(); ++i) load.scene.cameras.push_back(parse_camera(load, *tables[i], i));
}

}  // namespace luxtrace::detail
