// [[radiance]] -> a Radiance model's surfaces, materials, lights and portals in the scene
// (docs/RADIANCE.md "Running Radiance models"). The model is read by radiance_reader, its
// modifiers mapped by radiance_materials; this step places the triangles and turns the
// emitters into lights: light/glow/spotlight surfaces into area lights, narrow distant
// sources into directional beams, a 180-degree glow source overhead into a uniform sky,
// and the !gensky / !gendaylit lines into the daylight lights (radiance_sky.hpp).
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/orientation.hpp"
#include "luxtrace/light/photometry_distribution.hpp"
#include "luxtrace/scene/radiance_luminaire.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "luxtrace/scene/radiance_reader.hpp"
#include "luxtrace/scene/radiance_sky.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace luxtrace::detail {

namespace {

namespace fs = std::filesystem;

// Distant sources up to this full angle are read as parallel beams (the sun subtends 0.53).
constexpr double kMaxBeamSourceAngleDeg = 5.0;

struct RadianceModelReader : StepReader {
    using StepReader::StepReader;
    const RadianceModel* model = nullptr;
    std::vector<RadianceMapping> mappings;
    std::vector<std::int64_t> material_of_modifier;  // scene material, -1 until used
    std::size_t first_description = 0;               // of this model's modifiers in scene.radiance_modifiers

    // The first modifier along `index`'s chain of modifiers (itself, its modifier, ...) for
    // which `is` holds, or -1.
    template <class Pred>
    int along_chain(int index, Pred is) const {
        for (int k = index, depth = 0; k >= 0 && depth < 64; k = model->modifiers[k].modifier, ++depth)
            if (is(model->modifiers[k])) return k;
        return -1;
    }
    // The `skyfunc` of a sky command that modifier `index` is or descends from (the glow of
    // Radiance's sky description, which the command's sky replaces), or -1.
    int sky_pattern_of(int index) const {
        return along_chain(index, [](const RadianceModifier& m) { return m.sky_command >= 0; });
    }
    bool from_sky(int index) const { return sky_pattern_of(index) >= 0; }
    bool from_brightdata(int index) const {
        return along_chain(index, [](const RadianceModifier& m) { return m.type == "brightdata"; }) >= 0;
    }
    // check's line for modifier k: what it maps to; the sky's pattern and glows say that
    // the sky line's sky is their light (add_skies).
    std::string describe(std::size_t k) const {
        const RadianceModifier& mod = model->modifiers[k];
        const std::string where = model->where(mod.at) + ": ";
        const int pattern = sky_pattern_of(static_cast<int>(k));
        if (pattern < 0) return where + mod.type + " " + mappings[k].describe();
        const RadianceCommand& sky = model->sky_commands[static_cast<std::size_t>(
            model->modifiers[static_cast<std::size_t>(pattern)].sky_command)];
        if (mod.sky_command >= 0)
            return where + mod.name + " -> the sky pattern of the !" + sky.program + " line (below)";
        return where + mod.type + " " + mod.name + " -> the sky's glow: its light is the sky of the " +
               model->where(sky.at) + " line (below)";
    }
    std::string modifier_where(int index) const {
        const RadianceModifier& m = model->modifiers[static_cast<std::size_t>(index)];
        return model->where(m.at) + ": modifier '" + m.name + "' (" + m.type + ")";
    }

    // The scene material of modifier `index`, added when first used; a name a [[material]]
    // or an earlier modifier has taken gets the modifier's place appended.
    std::uint32_t material(int index) {
        std::int64_t& slot = material_of_modifier[static_cast<std::size_t>(index)];
        if (slot >= 0) return static_cast<std::uint32_t>(slot);
        Material m = mappings[static_cast<std::size_t>(index)].material;
        const auto taken = [&](const std::string& name) {
            return std::any_of(scene.materials.begin(), scene.materials.end(),
                               [&](const Material& x) { return x.name == name; });
        };
        if (taken(m.name)) m.name += " (" + model->where(model->modifiers[static_cast<std::size_t>(index)].at) + ")";
        slot = static_cast<std::int64_t>(scene.materials.size());
        scene.materials.push_back(std::move(m));
        return static_cast<std::uint32_t>(slot);
    }

    void read(const toml::table& t, std::size_t i) {
        TableReader r(t, fname, entry_name("radiance", i, t), "radiance");
        // `file`: one file, or several read in turn as one model (oconv's order: a .mat's
        // modifiers are in force in the files after it).
        std::vector<fs::path> files;
        if (!r.has("file")) r.fail_entry("needs a 'file' (a Radiance scene description, .rad, or an array of them)");
        if (t["file"].is_array()) {
            const std::vector<std::string> names = *r.strings("file");
            for (const std::string& f : names) files.push_back(load.resolve(f));
            if (files.empty()) r.fail("file", "names no file");
        } else {
            files.push_back(load.resolve(*r.string("file")));
        }
        RadianceOptions options;
        options.scale = r.number("scale").value_or(1.0);
        if (!(options.scale > 0.0 && std::isfinite(options.scale)))
            r.fail("scale", "must be positive (metres per model unit: 1, 0.3048 for feet, 0.001 for mm), got " +
                                fmt_number(options.scale));
        // `photometry = { BRIGHTDATA = "file.ies" }`: an ies2rad luminaire from the IES file it
        // came from instead of its .dat (radiance_luminaire.hpp).
        std::map<std::string, std::pair<fs::path, int>> named;
        if (const toml::table* ph = r.table("photometry"))
            for (const auto& [key, node] : *ph) {
                const auto f = node.value<std::string>();
                if (!f) r.fail_nested("photometry." + std::string(key.str()), node, "expected a file name");
                named[std::string(key.str())] = {load.resolve(*f), node.source().begin.line};
            }
        r.finish();
        const RadianceModel m = read_radiance(files, options);
        model = &m;
        for (const std::string& w : m.warnings) scene.warnings.push_back(w);
        mappings.clear();
        for (std::size_t k = 0; k < m.modifiers.size(); ++k)
            mappings.push_back(map_radiance_modifier(m, k, scene.bands));
        first_description = scene.radiance_modifiers.size();
        for (std::size_t k = 0; k < m.modifiers.size(); ++k) scene.radiance_modifiers.push_back(describe(k));
        material_of_modifier.assign(m.modifiers.size(), -1);
        const std::string context = fname + ":" + std::to_string(r.line("file")) + ": " + r.context();
        const std::vector<bool> luminaire_triangle = add_luminaires(m, files, named, r.context());
        const std::vector<std::int64_t> placed = add_mesh_triangles(
            load, m.mesh,
            [&](std::size_t tri) {
                return luminaire_triangle[tri] ? kLeaveOutTriangle
                                               : material(static_cast<int>(m.triangle_modifier[tri]));
            },
            [&](const std::string& what) { throw InputError(context + ": " + what); });
        add_surface_lights(placed);
        add_portals(placed);
        add_sources();
        add_skies();
        model = nullptr;
    }

    // ies2rad luminaires are point lights with their photometry; their small emitting
    // surfaces are left out of the geometry (a photon would start on them): which mesh
    // triangles those are. `named`: the entry's `photometry` files by brightdata name.
    std::vector<bool> add_luminaires(const RadianceModel& m, const std::vector<fs::path>& files,
                                     std::map<std::string, std::pair<fs::path, int>>& named, const std::string& entry) {
        std::vector<bool> luminaire_triangle(m.mesh.triangles.size(), false);
        const std::vector<std::size_t> luminaires = radiance_luminaire_modifiers(m);
        for (const std::size_t b : luminaires) {
            const std::string& bname = m.modifiers[b].name;
            const auto it = named.find(bname);
            RadianceLuminaire lum;
            if (it != named.end()) {
                lum = radiance_luminaire_named(m, b, load_named_photometry(it->second.first, it->second.second, bname));
            } else {
                // Library paths ("source/x/y.dat") also from the named file's folder, as
                // Radiance run there finds them (RAYPATH's ".").
                RadianceLuminaireOptions lo;
                for (const fs::path& f : files) lo.search_path.push_back(f.parent_path());
                lum = radiance_luminaire(m, b, lo);
            }
            for (const std::size_t k : lum.surfaces) {
                const RadianceSurface& surf = m.surfaces[k];
                for (std::size_t t = surf.first_triangle; t < surf.first_triangle + surf.triangle_count; ++t)
                    luminaire_triangle[t] = true;
            }
            describe_luminaire(b, lum, it != named.end() ? it->second.first.filename().string() : "");
            add_luminaire(std::move(lum), m.modifiers[b]);
        }
        for (const std::size_t b : luminaires) named.erase(m.modifiers[b].name);
        if (!named.empty())
            throw InputError(fname + ":" + std::to_string(named.begin()->second.second) + ": " + entry +
                             ": photometry: '" + named.begin()->first +
                             "' is no brightdata luminaire of the model (check lists its modifiers)");
        return luminaire_triangle;
    }

    // check's lines for a luminaire's brightdata and the emitting modifiers it feeds.
    void describe_luminaire(std::size_t brightdata, const RadianceLuminaire& lum, const std::string& ies) {
        const RadianceModifier& b = model->modifiers[brightdata];
        scene.radiance_modifiers[first_description + brightdata] =
            model->where(b.at) + ": brightdata " + b.name + " -> ies2rad luminaire: a point light of " +
            (ies.empty() ? "its .dat's photometry" : ies + "'s photometry (named in the scene)") + ", " +
            fmt_number(std::round(lum.photometry.flux_lm() * 10.0) / 10.0) + " lm, at (" +
            fmt_number(std::round(lum.position_m.x * 1e4) / 1e4) + ", " +
            fmt_number(std::round(lum.position_m.y * 1e4) / 1e4) + ", " +
            fmt_number(std::round(lum.position_m.z * 1e4) / 1e4) + ")";
        for (std::size_t k = 0; k < model->modifiers.size(); ++k)
            if (model->modifiers[k].modifier == static_cast<int>(brightdata))
                scene.radiance_modifiers[first_description + k] = model->where(model->modifiers[k].at) + ": " +
                                                                  model->modifiers[k].type + " " +
                                                                  model->modifiers[k].name +
                                                                  " -> the emitting surface of luminaire '" + b.name +
                                                                  "' (left out: the light is the luminaire's)";
    }

    Photometry load_named_photometry(const fs::path& path, int line, const std::string& name) {
        try {
            return load_photometry(path, 1);
        } catch (const InputError& e) {
            throw InputError(fname + ":" + std::to_string(line) + ": [[radiance]] photometry." + name + ": " +
                             e.what());
        }
    }

    // A point light of the luminaire's photometry at its place, as a [[light]] with a file.
    void add_luminaire(RadianceLuminaire lum, const RadianceModifier& brightdata) {
        for (const std::string& n : lum.notes) scene.warnings.push_back(n);
        for (const std::string& n : lum.photometry.notes) scene.warnings.push_back(n);
        SceneLoad::RadianceLight out;
        out.label = "radiance luminaire '" + lum.name + "'";
        Light& l = out.light;
        l.label = out.label;
        PointLight k;
        k.position = lum.position_m;
        k.frame = lum.frame;
        auto photometry = std::make_shared<const Photometry>(std::move(lum.photometry));
        try {
            k.distribution = std::make_shared<const PhotometryDistribution>(*photometry);
        } catch (const std::invalid_argument&) {
            throw InputError(model->where(brightdata.at) + ": luminaire '" + lum.name +
                             "': its light lies in too narrow a beam for the 0.5 degree sampling grid");
        }
        k.photometry = photometry;
        k.opening = photometry->opening;
        if (!photometry->tilt.empty()) k.tilt_factor = photometry->tilt.at(tilt_from_nadir_deg(k.frame));
        l.flux_lm = photometry->flux_lm() * k.tilt_factor;
        l.kind = std::move(k);
        l.maintenance_factor = scene.maintenance_factor;
        l.band_share.assign(scene.bands.size(), 1.0 / static_cast<double>(scene.bands.size()));
        if (!(l.flux_lm > 0.0 && std::isfinite(l.flux_lm)))
            throw InputError(model->where(brightdata.at) + ": luminaire '" + lum.name + "' carries no flux");
        load.radiance_lights.push_back(std::move(out));
    }

    // One area light per light modifier, over every surface it modifies.
    void add_surface_lights(const std::vector<std::int64_t>& placed) {
        std::map<std::uint32_t, std::vector<std::size_t>> triangles;  // by modifier
        for (std::size_t tri = 0; tri < placed.size(); ++tri)
            if (placed[tri] >= 0 && mappings[model->triangle_modifier[tri]].role == RadianceRole::light)
                triangles[model->triangle_modifier[tri]].push_back(static_cast<std::size_t>(placed[tri]));
        for (auto& [index, tris] : triangles) {
            const int k = static_cast<int>(index);
            if (from_sky(k)) {
                scene.warnings.push_back(modifier_where(k) +
                                         ": a surface of the sky's glow emits nothing (the sky is the !gensky or "
                                         "!gendaylit command's)");
                continue;
            }
            if (from_brightdata(k)) continue;  // an ies2rad luminaire's surface, left out above
            const RadianceMapping& map = mappings[index];
            const double luminance = std::accumulate(map.luminance_cd_m2.begin(), map.luminance_cd_m2.end(), 0.0);
            if (!(luminance > 0.0)) {
                scene.warnings.push_back(modifier_where(k) + ": a light of zero radiance emits nothing");
                continue;
            }
            SceneLoad::RadianceLight out;
            out.label = "radiance light '" + model->modifiers[index].name + "'";
            Light& l = out.light;
            l.label = out.label;
            AreaLight area;
            area.surface = triangles_surface(scene, tris);
            // Lambertian from the front side: M = pi L, the flux M A.
            l.flux_lm = kPi * luminance * area.surface.area_m2;
            l.kind = std::move(area);
            l.maintenance_factor = scene.maintenance_factor;
            for (const double x : map.luminance_cd_m2) l.band_share.push_back(x / luminance);
            load.radiance_lights.push_back(std::move(out));
        }
    }

    void add_portals(const std::vector<std::int64_t>& placed) {
        for (const RadianceSurface& s : model->surfaces) {
            if (s.modifier < 0 || mappings[static_cast<std::size_t>(s.modifier)].role != RadianceRole::portal) continue;
            SceneLoad::RadiancePortal p{s.name, {}, model->where(s.at)};
            for (std::size_t tri = s.first_triangle; tri < s.first_triangle + s.triangle_count; ++tri)
                if (placed[tri] >= 0) p.triangles.push_back(static_cast<std::size_t>(placed[tri]));
            if (!p.triangles.empty()) load.radiance_portals.push_back(std::move(p));
        }
    }

    // Distant sources: a narrow one is a parallel beam of illuminance L x its solid angle;
    // a glow over the whole upper hemisphere a uniform sky; the sky's own glow is the sky
    // command's.
    void add_sources() {
        for (const RadianceSource& s : model->sources) {
            const std::string where = model->where(s.at) + ": source '" + s.name + "'";
            if (s.modifier < 0) continue;
            if (from_sky(s.modifier)) {
                if (model->sky_commands.empty())
                    throw InputError(where + ": the sky's glow without the !gensky or !gendaylit line that defines it");
                continue;
            }
            const RadianceMapping& map = mappings[static_cast<std::size_t>(s.modifier)];
            if (map.role != RadianceRole::light) {
                scene.warnings.push_back(where + ": a distant source of a non-emitting material emits nothing");
                continue;
            }
            const double luminance = std::accumulate(map.luminance_cd_m2.begin(), map.luminance_cd_m2.end(), 0.0);
            if (!(luminance > 0.0)) continue;
            SceneLoad::RadianceLight out;
            out.label = "radiance source '" + s.name + "'";
            if (s.angle_deg >= 179.999 && s.direction.z > 1.0 - 1e-9) {
                out.table.insert("type", "sky");
                out.table.insert("sky", "uniform");
                out.table.insert("zenith_luminance_cd_m2", luminance);
                load.radiance_lights.push_back(std::move(out));
                continue;
            }
            if (!(s.angle_deg > 0.0 && s.angle_deg <= kMaxBeamSourceAngleDeg))
                throw InputError(where + ": a distant source of " + fmt_number(s.angle_deg) +
                                 " degrees; luxtrace reads sources up to " + fmt_number(kMaxBeamSourceAngleDeg) +
                                 " degrees (parallel beams) and a glow over the whole sky (180 degrees, straight up) "
                                 "as a uniform sky; give other skies as !gensky or !gendaylit");
            Light& l = out.light;
            l.label = out.label;
            DirectionalLight beam;
            beam.aim = -s.direction;  // the direction the light travels
            beam.frame = Frame::around(beam.aim);
            // E = L Omega, Omega = 2 pi (1 - cos(angle / 2)) the cone's solid angle.
            const double omega_sr = 2.0 * kPi * (1.0 - std::cos(0.5 * s.angle_deg * kPi / 180.0));
            beam.illuminance_lx = luminance * omega_sr;
            l.kind = std::move(beam);
            l.maintenance_factor = scene.maintenance_factor;
            for (const double x : map.luminance_cd_m2) l.band_share.push_back(x / luminance);
            load.radiance_lights.push_back(std::move(out));
        }
    }

    // Each !gensky / !gendaylit line: a [[light]] sky table and, with a sun, a sun table
    // (radiance_sky.hpp gives their keys), read by read_lights like the user's.
    void add_skies() {
        for (const RadianceCommand& c : model->sky_commands) {
            const RadianceSky sky = map_radiance_sky(*model, c);
            const std::string where = model->where(c.at);
            scene.radiance_modifiers.push_back(where + ": " + sky.describe());
            const RadianceSkyLight& k = sky.sky;
            SceneLoad::RadianceLight out;
            out.label = "radiance sky (" + where + ")";
            out.table.insert("type", "sky");
            out.table.insert("sky", k.sky);
            const bool sun_placed = k.sky == "perez" || (k.sky == "cie" && k.cie_type != 16);
            if (k.sky == "cie") out.table.insert("cie_type", k.cie_type);
            if (sun_placed) {
                out.table.insert("sun_altitude_deg", k.sun_altitude_deg);
                out.table.insert("sun_azimuth_deg", k.sun_azimuth_deg);
            }
            if (k.zenith_luminance_cd_m2) out.table.insert("zenith_luminance_cd_m2", *k.zenith_luminance_cd_m2);
            if (k.diffuse_horizontal_lx) out.table.insert("diffuse_horizontal_lx", *k.diffuse_horizontal_lx);
            if (k.sky == "perez") {
                out.table.insert("diffuse_horizontal_w_m2", k.diffuse_horizontal_w_m2);
                out.table.insert("direct_normal_w_m2", k.direct_normal_w_m2);
                out.table.insert("dew_point_c", k.dew_point_c);
                out.day_of_year = k.day_of_year;
            }
            out.table.insert("ground_reflectance", k.ground_reflectance);
            load.radiance_lights.push_back(std::move(out));
            if (!sky.sun) continue;
            SceneLoad::RadianceLight sun;
            sun.label = "radiance sun (" + where + ")";
            sun.table.insert("type", "sun");
            sun.table.insert("direct_normal_lx", sky.sun->direct_normal_lx);
            sun.table.insert("sun_altitude_deg", sky.sun->sun_altitude_deg);
            sun.table.insert("sun_azimuth_deg", sky.sun->sun_azimuth_deg);
            load.radiance_lights.push_back(std::move(sun));
        }
    }
};

}  // namespace

void read_radiance_models(SceneLoad& load, TableReader& root) {
    RadianceModelReader reader(load);
    const auto tables = tables_of(root, "radiance");
    for (std::size_t i = 0; i < tables.size(); ++i) reader.read(*tables[i], i);
}

}  // namespace luxtrace::detail
