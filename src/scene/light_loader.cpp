// [[light]] -> the scene's lights (docs/REFERENCE.md §2): point lights with or without a
// luminaire's photometry, spots, area lights on a named [[shape]], directional beams.
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/orientation.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

namespace luxtrace::detail {

namespace {

namespace fs = std::filesystem;

struct LightReader : StepReader {
    using StepReader::StepReader;
    // By canonical file path and lamp set.
    std::map<std::string, std::pair<std::shared_ptr<const Photometry>, std::shared_ptr<const PhotometryDistribution>>>
        photometry_cache;
    std::vector<std::string> groups;  // in order of first appearance

    // `group`: the index of the entry's light group. Without the key the light is in the
    // default group, which therefore exists only if some light has no `group`.
    std::size_t group_of(TableReader& r) {
        const auto name = r.string("group");
        if (name) check_group_name(r, "group", *name);
        const std::string group = name.value_or(Scene::kDefaultLightGroup);
        const auto it = std::find(groups.begin(), groups.end(), group);
        if (it != groups.end()) return static_cast<std::size_t>(it - groups.begin());
        groups.push_back(group);
        return groups.size() - 1;
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
        pl.aim = unit_vector(r, aim_key, r.vec3(aim_key).value_or(Vec3(0, 0, -1)));
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
        if (!(v > 0.0 && v <= hi)) r.fail(key, "must lie in (0, " + fmt_number(hi) + "], got " + fmt_number(v));
        return v;
    }

    std::vector<Light> parse_light(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("light", i, t), "light");
        Light l;
        const std::string type = r.string("type").value_or("");
        l.label = "light " + std::to_string(i + 1) + " (" + type + ")";
        l.group = group_of(r);  // shared by every copy at `positions` or on the `grid`
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
                const std::string key = fs::weakly_canonical(load.resolve(*file)).string() + "#" + std::to_string(set);
                auto cached = photometry_cache.find(key);
                if (cached == photometry_cache.end()) {
                    Photometry photometry;
                    try {
                        photometry = load_photometry(load.resolve(*file), static_cast<int>(set));
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
                        r.fail(file_key, load.resolve(*file).string() +
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
                                               fmt_number(tilt_from_nadir_deg(l.frame)) + " degrees");
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
            const auto it = load.named_shapes.find(*shape);
            if (it == load.named_shapes.end()) r.fail("shape", "no [[shape]] is named '" + *shape + "'");
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
            l.aim = unit_vector(r, "direction", *d);
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
};

// Directional beams cover the scene's bounding sphere, started just outside it.
void place_directional_beams(const Scene& scene, std::vector<Light>& lights) {
    const Vec3 mid = 0.5 * (scene.bounds_min + scene.bounds_max);
    const double radius = 0.5 * glm::length(scene.bounds_max - scene.bounds_min) * 1.001 + 1e-6;
    for (Light& l : lights)
        if (l.type == LightType::directional) {
            l.beam_radius = radius;
            l.beam_center = mid - 1.01 * radius * l.aim;
            l.flux_lm = l.illuminance_lx * kPi * radius * radius;
        }
}

}  // namespace

void check_group_name(const TableReader& r, const std::string& key, const std::string& name) {
    if (name.empty()) r.fail(key, "must not be empty");
    for (const char c : name)
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
              c == '.'))
            r.fail(key, "'" + name + "' may contain only letters, digits, '_', '-' and '.'");
}

void read_lights(SceneLoad& load, TableReader& root) {
    LightReader reader(load);
    std::vector<Light> lights;
    const auto tables = tables_of(root, "light");
    for (std::size_t i = 0; i < tables.size(); ++i)
        for (Light& l : reader.parse_light(*tables[i], i)) lights.push_back(std::move(l));
    if (lights.empty()) throw InputError(load.fname + ": the scene has no [[light]]");
    place_directional_beams(load.scene, lights);
    double total_flux = 0.0;
    for (const Light& l : lights) {
        total_flux += l.flux_lm;
        if (!(l.flux_lm > 0.0 && std::isfinite(l.flux_lm)) || !std::isfinite(total_flux))
            throw InputError(load.fname + ": " + l.label + ": its flux (" + fmt_number(l.flux_lm) +
                             " lm) makes the total flux of the scene too large or not positive");
    }
    Scene& scene = load.scene;
    scene.lights = LightSet(std::move(lights));
    scene.light_groups = std::move(reader.groups);
    if (!scene.lights.maintenance_factor_uniform())
        scene.warnings.push_back("maintenance factors differ between lights: results are initial values, and the "
                                 "maintained ones luxtrace reports use the flux-weighted mean factor (" +
                                 fmt_number(scene.lights.maintenance_factor()) + ")");
}

}  // namespace luxtrace::detail
