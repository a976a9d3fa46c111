// Scene file (docs/REFERENCE.md §2) -> Scene. Every key is checked; the first problem found is
// thrown as an InputError naming the file, the line and the key. The steps, one concept
// each, are in scene_loader.hpp.
#include "scene_loader.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/scene_schema.hpp"

#include <sstream>
#include <string_view>

namespace luxtrace {

namespace fs = std::filesystem;

namespace detail {

fs::path SceneLoad::resolve(const std::string& path) const {
    const fs::path p(path);
    return p.is_absolute() || folder.empty() ? p : folder / p;
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

std::string entry_name(const std::string& kind, std::size_t i, const toml::table& t) {
    std::string s = "[[" + kind + "]] #" + std::to_string(i + 1);
    if (const auto n = t["name"].value<std::string>()) s += " '" + *n + "'";
    return s;
}

Vec3 unit_vector(TableReader& r, const std::string& key, Vec3 v) {
    if (glm::length(v) < 1e-12) r.fail(key, "must be a non-zero vector");
    return glm::normalize(v);
}

std::string fmt_number(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    return os.str();
}

void read_scene_table(SceneLoad& load, TableReader& root) {
    Scene& scene = load.scene;
    scene.name = load.file.stem().string();
    const toml::table* t = root.table("scene");
    if (t == nullptr) return;
    TableReader r(*t, load.fname, "[scene]", "scene");
    scene.name = r.string("name").value_or(scene.name);
    if (auto b = r.strings("bands")) {
        if (b->empty()) r.fail("bands", "needs at least one band");
        scene.bands = *b;
    }
    scene.maintenance_factor = r.number("maintenance_factor").value_or(1.0);
    if (!(scene.maintenance_factor > 0.0 && scene.maintenance_factor <= 1.0))
        r.fail("maintenance_factor", "must lie in (0, 1]");
    r.finish();
}

}  // namespace detail

namespace {

toml::table parse_toml(const fs::path& file, const std::string& fname) {
    if (!fs::is_regular_file(file)) throw InputError(fname + ": no such scene file");
    try {
        return toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw InputError(fname + ":" + std::to_string(e.source().begin.line) +
                         ": TOML syntax error: " + std::string(e.description()));
    }
}

// Unknown top-level tables first, before any file the scene names is read: a misspelt
// [[lights]] is reported as such, not as "no lights".
void refuse_unknown_tables(const toml::table& root, const std::string& fname) {
    for (const auto& [key, node] : root)
        if (!scene_table_schema("").accepts(key.str()))
            throw InputError(fname + ":" + std::to_string(node.source().begin.line) + ": top level: unknown key '" +
                             std::string(key.str()) + "'");
}

}  // namespace

namespace {

Scene load_from_table(const toml::table& root_table, const fs::path& file, const std::string& fname,
                      const fs::path& folder, const AnnualSkyShare& sky_share = {}) {
    detail::SceneLoad load;
    load.sky_share = sky_share;
    load.file = file;
    load.folder = folder;
    load.fname = fname;
    load.scene.file = file;
    refuse_unknown_tables(root_table, load.fname);
    detail::TableReader root(root_table, load.fname, "top level", "");
    detail::read_scene_table(load, root);
    detail::read_site(load, root);
    detail::read_geometry(load, root);
    detail::read_lights(load, root);
    detail::read_portals(load, root);
    detail::read_light_scenes(load, root);
    detail::read_detectors(load, root);
    detail::read_observers(load, root);
    detail::cover_detectors_with_beams(load);
    detail::read_cameras(load, root);
    detail::read_run(load, root);
    root.finish();
    return std::move(load.scene);
}

// A detector name from a file name: HDF5 group names and target paths refuse "/[]:. ".
std::string detector_name_of(const fs::path& file) {
    std::string name = file.stem().string();
    for (char& c : name)
        if (std::string_view("/[]:. ").find(c) != std::string_view::npos) c = '_';
    return name.empty() ? "sensors" : name;
}

}  // namespace

Scene load_scene(const fs::path& file, const AnnualSkyShare& sky_share) {
    if (is_radiance_file(file))
        throw InputError(file.string() + ": a Radiance model, not a scene file: run it with `luxtrace run " +
                         file.filename().string() +
                         " --sensors GRID.pts`, or name it in a scene's [[radiance]] table (docs/RADIANCE.md)");
    return load_from_table(parse_toml(file, file.string()), file, file.string(), file.parent_path(), sky_share);
}

bool is_radiance_file(const fs::path& file) {
    const std::string ext = file.extension().string();
    return ext == ".rad" || ext == ".mat" || ext == ".sky" || ext == ".RAD";
}

Scene load_radiance_scene(const RadianceRun& run) {
    if (run.models.empty()) throw InputError("no Radiance model given");
    for (const fs::path& m : run.models)
        if (!fs::is_regular_file(m)) throw InputError(m.string() + ": no such file");
    // The scene a user would write: [[radiance]] per model, the sensors as a points detector.
    toml::table root;
    toml::array files;
    // Paths as given, from the working directory (messages name the files as typed).
    const fs::path& last = run.models.back();
    for (const fs::path& m : run.models) files.push_back(m.string());
    toml::table model{{"file", std::move(files)}};
    if (run.scale != 1.0) model.insert("scale", run.scale);
    root.insert("radiance", toml::array{std::move(model)});
    if (run.sensors) {
        const std::string name = detector_name_of(*run.sensors);
        toml::table d{{"name", name}, {"type", "points"}, {"points", run.sensors->string()}};
        if (run.sensor_radius_m) d.insert("radius_m", *run.sensor_radius_m);
        root.insert("detector", toml::array{std::move(d)});
        if (run.sensors_relative_error) {
            toml::table target{{"on", "detector:" + name}, {"relative_error", *run.sensors_relative_error}};
            root.insert("run", toml::table{{"target", toml::array{std::move(target)}}});
        }
    }
    // Named after the last model (Radiance's order puts the sky first, the model last).
    Scene scene = load_from_table(root, last, last.string(), fs::path());
    RadianceRun made = run;
    for (fs::path& m : made.models) m = fs::absolute(m);
    if (made.sensors) made.sensors = fs::absolute(*made.sensors);
    scene.radiance_run = std::move(made);
    return scene;
}

}  // namespace luxtrace
