// [[light_scene]] -> the scene's light scenes (docs/REFERENCE.md §2): each a named weight per
// light group, groups it does not name off.
#include "scene_loader.hpp"

#include "luxtrace/core/text.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace::detail {

namespace {

LightScene parse_light_scene(const SceneLoad& load, const toml::table& t, std::size_t i) {
    const Scene& scene = load.scene;
    TableReader r(t, load.fname, entry_name("light_scene", i, t), "light_scene");
    LightScene ls;
    const auto name = r.string("name");
    if (!name) r.fail_entry("needs a 'name'");
    check_group_name(r, "name", *name);
    for (const LightScene& other : scene.light_scenes)
        if (other.name == *name) r.fail("name", "light scene '" + *name + "' is defined twice");
    ls.name = *name;
    const toml::table* dimming = r.table("dimming");
    if (dimming == nullptr) r.fail_entry("needs 'dimming' = { GROUP = weight, ... }");
    ls.weights.assign(scene.light_groups.size(), 0.0);
    for (const auto& [k, node] : *dimming) {
        const std::string group(k.str());
        const std::string key = "dimming." + group;
        if (node.is_table())  // `a.b = 1` is a nested table in TOML
            r.fail_nested(key, node, "expected a weight; quote a group name with '.' (\"a.b\" = 1)");
        const auto g = std::find(scene.light_groups.begin(), scene.light_groups.end(), group);
        if (g == scene.light_groups.end())
            r.fail_nested(key, node,
                          "no light group is named '" + group + "' (the groups: " + comma_list(scene.light_groups) +
                              ")");
        const std::optional<double> w = node.value<double>();
        if (!w || !std::isfinite(*w) || *w < 0.0) r.fail_nested(key, node, "expected a weight, a number >= 0");
        ls.weights[static_cast<std::size_t>(g - scene.light_groups.begin())] = *w;
    }
    if (std::all_of(ls.weights.begin(), ls.weights.end(), [](double w) { return w == 0.0; }))
        r.fail("dimming", "gives no group a weight above 0: the light scene would be dark");
    r.finish();
    return ls;
}

}  // namespace

void read_light_scenes(SceneLoad& load, TableReader& root) {
    const auto tables = tables_of(root, "light_scene");
    for (std::size_t i = 0; i < tables.size(); ++i)
        load.scene.light_scenes.push_back(parse_light_scene(load, *tables[i], i));
}

}  // namespace luxtrace::detail
