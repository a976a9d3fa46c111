// [[light]] -> the scene's lights (docs/REFERENCE.md §2): point lights with or without a
// luminaire's photometry, spots, area lights on a named [[shape]], directional beams, and
// daylight: the sun and the sky (docs/DAYLIGHT.md).
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/orientation.hpp"
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "luxtrace/light/sun_position.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

namespace luxtrace::detail {

namespace {

namespace fs = std::filesystem;

struct LightReader : StepReader {
    using StepReader::StepReader;
    using PhotometryPair = std::pair<std::shared_ptr<const Photometry>, std::shared_ptr<const PhotometryDistribution>>;
    std::map<std::string, PhotometryPair> photometry_cache;  // by canonical file path and lamp set
    std::vector<std::string> groups;                         // in order of first appearance
    // The first sky light's ground reflectance, the default of every sun's ground glow, and
    // each sun light's own `ground_reflectance` (by label), applied once all are read.
    std::optional<double> sky_ground_reflectance;
    std::map<std::string, std::optional<double>> sun_ground_reflectance;
    // A Radiance gendaylit sky's own day of the year (the next parse_light only).
    std::optional<int> perez_day_of_year;

    struct SunAt {
        double altitude_deg = 0.0, azimuth_deg = 0.0;
        std::string when;  // for messages: "at TIME" or "as given"
    };
    // The sun's position a sun or sky light refers to: its own `sun_altitude_deg` and
    // `sun_azimuth_deg`, or the [site] at its `time` (NREL SPA, sun_position.hpp).
    SunAt sun_at(TableReader& r, const std::string& type) {
        const bool alt = r.has("sun_altitude_deg"), az = r.has("sun_azimuth_deg");
        if (alt != az)
            r.fail(alt ? "sun_altitude_deg" : "sun_azimuth_deg",
                   "give 'sun_altitude_deg' and 'sun_azimuth_deg' together");
        if (alt) {
            SunAt s{*r.number("sun_altitude_deg"), *r.number("sun_azimuth_deg"), "as given"};
            if (!(s.altitude_deg >= -90.0 && s.altitude_deg <= 90.0))
                r.fail("sun_altitude_deg", "must lie in [-90, 90]");
            if (!(s.azimuth_deg >= 0.0 && s.azimuth_deg <= 360.0))
                r.fail("sun_azimuth_deg", "must lie in [0, 360] (clockwise from north: 90 east, 180 south)");
            return s;
        }
        const Site& site = scene.site;
        if (!site.time)
            r.fail_entry("type '" + type +
                         "' needs the sun's position: 'sun_altitude_deg' and 'sun_azimuth_deg', or a [site] with "
                         "'latitude_deg', 'longitude_deg', 'utc_offset_h' and 'time'");
        try {
            const SunPosition p = sun_position(*site.time, site.sun_site);
            return {p.altitude_deg, p.azimuth_deg, "at " + site.time_text};
        } catch (const std::invalid_argument& e) {
            throw InputError(fname + ": [site]: " + e.what());
        }
    }

    void read_sun(TableReader& r, Light& l, const std::string&) {
        SunLight k;
        const SunAt s = sun_at(r, "sun");
        k.sun_altitude_deg = s.altitude_deg;
        k.sun_azimuth_deg = s.azimuth_deg;
        const auto e = r.number("direct_normal_lx");
        if (!e) r.fail_entry("type 'sun' needs 'direct_normal_lx'");
        if (!(*e > 0.0)) r.fail("direct_normal_lx", "must be positive, got " + fmt_number(*e));
        k.illuminance_lx = *e * l.dimming;
        k.horizon = scene.site.horizon();
        k.aim = -k.horizon.to_world(sky_direction_deg(s.altitude_deg, s.azimuth_deg));
        k.frame = Frame::around(k.aim);
        k.cos_half_angle = std::cos(kSunHalfAngleDeg * kPi / 180.0);
        if (!(s.altitude_deg > 0.0)) {
            scene.warnings.push_back(l.label + ": the sun is below the horizon " + s.when + " (altitude " +
                                     fmt_number(std::round(s.altitude_deg * 100.0) / 100.0) +
                                     " degrees): it emits nothing");
            k.illuminance_lx = 0.0;
        }
        // E_n sin(h): the cone's mean direction is the aim, so this is exact for the disc.
        l.unobstructed_horizontal_lx = k.illuminance_lx * std::max(0.0, std::sin(s.altitude_deg * kPi / 180.0));
        sun_ground_reflectance[l.label] = ground_reflectance(r);
        l.kind = std::move(k);
    }

    std::optional<double> ground_reflectance(TableReader& r) {
        const auto rho = r.number("ground_reflectance");
        if (rho && !(*rho >= 0.0 && *rho <= 1.0)) r.fail("ground_reflectance", "must lie in [0, 1]");
        return rho;
    }

    void read_sky(TableReader& r, Light& l, const std::string&) {
        SkyLight k;
        const auto model = r.string("sky");
        if (!model) r.fail_entry("type 'sky' needs 'sky' (\"cie\", \"perez\" or \"uniform\")");
        std::optional<SkyModel> sky;
        std::optional<double> model_zenith_cd_m2;  // a Perez sky's own
        if (*model == "cie") {
            const auto type = r.integer("cie_type");
            if (!type)
                r.fail_entry("sky = \"cie\" needs 'cie_type' (1 to 15: the CIE standard general skies; 16: "
                             "the traditional CIE overcast sky)");
            if (*type < 1 || *type > 16) r.fail("cie_type", "must be 1 to 16, got " + std::to_string(*type));
            k.description = "CIE type " + std::to_string(*type);
            if (*type == 16) {
                sky = SkyModel::cie(16, 0.0, 0.0);
            } else {
                const SunAt s = sun_at(r, "sky");
                if (s.altitude_deg < 0.0)
                    r.fail(r.has("sun_altitude_deg") ? "sun_altitude_deg" : "cie_type",
                           "the sun is below the horizon " + s.when + " (altitude " +
                               fmt_number(std::round(s.altitude_deg * 100.0) / 100.0) +
                               " degrees): the CIE general skies (types 1 to 15) are defined for a sun above it; "
                               "use cie_type 16 or sky = \"uniform\"");
                k.sun_altitude_deg = s.altitude_deg;
                k.sun_azimuth_deg = s.azimuth_deg;
                sky = SkyModel::cie(static_cast<int>(*type), (90.0 - s.altitude_deg) * kPi / 180.0,
                                    s.azimuth_deg * kPi / 180.0);
            }
        } else if (*model == "perez") {
            const PerezSky perez = read_perez(r, l.label, k);
            sky = perez.model();
            model_zenith_cd_m2 = perez.zenith_luminance_cd_m2();
        } else if (*model == "uniform") {
            sky = SkyModel::uniform();
            k.description = "uniform";
        } else {
            r.fail("sky", "must be \"cie\", \"perez\" or \"uniform\", got '" + *model + "'");
        }
        const bool by_horizontal = r.has("diffuse_horizontal_lx"), by_zenith = r.has("zenith_luminance_cd_m2");
        const double per_zenith_sr = sky->horizontal_illuminance_per_zenith_luminance_sr();
        double zenith_cd_m2 = 0.0;
        if (model_zenith_cd_m2) {
            if (by_horizontal || by_zenith)
                r.fail(by_horizontal ? "diffuse_horizontal_lx" : "zenith_luminance_cd_m2",
                       "a Perez sky's brightness comes from its irradiances and the Perez efficacy; drop this key");
            zenith_cd_m2 = *model_zenith_cd_m2 * l.dimming;
        } else {
            if (by_horizontal == by_zenith)
                r.fail_entry("type 'sky' needs one of 'diffuse_horizontal_lx' and 'zenith_luminance_cd_m2'");
            const char* key = by_horizontal ? "diffuse_horizontal_lx" : "zenith_luminance_cd_m2";
            const double v = *r.number(key);
            if (!(v > 0.0 && std::isfinite(v))) r.fail(key, "must be positive, got " + fmt_number(v));
            zenith_cd_m2 = (by_horizontal ? v / per_zenith_sr : v) * l.dimming;
        }
        l.unobstructed_horizontal_lx = zenith_cd_m2 * per_zenith_sr;
        const double rho = ground_reflectance(r).value_or(0.0);
        if (!sky_ground_reflectance) sky_ground_reflectance = rho;
        // Radiance's ground glow: a uniform lower hemisphere of luminance rho E_h / pi.
        k.sky = std::make_shared<const SkyDirections>(sky, zenith_cd_m2, rho * l.unobstructed_horizontal_lx / kPi);
        k.horizon = scene.site.horizon();
        l.kind = std::move(k);
    }

    // sky = "perez": the hour's sky from its irradiances and dew point (perez_sky.hpp); the
    // day of the year from a Radiance gendaylit line, else the [site]'s time, else day 150.
    PerezSky read_perez(TableReader& r, const std::string& label, SkyLight& k) {
        const SunAt s = sun_at(r, "sky");
        if (!(s.altitude_deg > 0.0))
            r.fail(r.has("sun_altitude_deg") ? "sun_altitude_deg" : "sky",
                   "the sun is not above the horizon " + s.when + " (altitude " +
                       fmt_number(std::round(s.altitude_deg * 100.0) / 100.0) +
                       " degrees): the Perez sky is defined for a sun above it");
        k.sun_altitude_deg = s.altitude_deg;
        k.sun_azimuth_deg = s.azimuth_deg;
        PerezSkyInput in;
        in.sun_zenith_rad = (90.0 - s.altitude_deg) * kPi / 180.0;
        in.sun_azimuth_rad = s.azimuth_deg * kPi / 180.0;
        const auto required = [&r](const char* key) {
            const auto v = r.number(key);
            if (!v) r.fail_entry(std::string("sky = \"perez\" needs '") + key + "'");
            if (!std::isfinite(*v)) r.fail(key, "must be finite");
            return *v;
        };
        in.diffuse_horizontal_w_m2 = required("diffuse_horizontal_w_m2");
        if (!(in.diffuse_horizontal_w_m2 > 0.0 && in.diffuse_horizontal_w_m2 <= 1367.0))
            r.fail("diffuse_horizontal_w_m2", "must lie in (0, 1367], got " + fmt_number(in.diffuse_horizontal_w_m2));
        in.direct_normal_w_m2 = required("direct_normal_w_m2");
        if (!(in.direct_normal_w_m2 >= 0.0 && in.direct_normal_w_m2 <= 1367.0))
            r.fail("direct_normal_w_m2", "must lie in [0, 1367], got " + fmt_number(in.direct_normal_w_m2));
        in.dew_point_c = required("dew_point_c");
        if (!(in.dew_point_c >= -90.0 && in.dew_point_c <= 60.0))
            r.fail("dew_point_c", "must lie in [-90, 60], got " + fmt_number(in.dew_point_c));
        if (perez_day_of_year) {
            in.day_of_year = *perez_day_of_year;
        } else if (scene.site.time) {
            const LocalStandardTime& t = *scene.site.time;
            in.day_of_year = day_of_year(t.year, t.month, t.day);
        }
        const PerezSky perez(in);
        const std::string condition = "epsilon " + fmt_number(std::round(perez.epsilon() * 1000.0) / 1000.0) +
                                      ", Delta " + fmt_number(std::round(perez.delta() * 1000.0) / 1000.0);
        k.description = "Perez (" + condition + ")";
        if (perez.clamped())
            scene.warnings.push_back(label + ": the Perez sky's " + condition +
                                     " lie outside the fitted range (epsilon 1-12, Delta 0.01-0.6): modelled at the "
                                     "nearest edge");
        return perez;
    }

    // The sun's light reflected by the ground, a uniform lower hemisphere of luminance
    // rho E_n sin(h) / pi, as its own emitter in the sun's group.
    void add_sun_ground_glow(std::vector<Light>& lights) {
        const std::size_t n = lights.size();
        for (std::size_t i = 0; i < n; ++i) {
            const Light& sun = lights[i];
            const SunLight* disc = sun.as<SunLight>();
            if (disc == nullptr) continue;
            const double rho = sun_ground_reflectance[sun.label].value_or(sky_ground_reflectance.value_or(0.0));
            if (!(rho > 0.0 && sun.unobstructed_horizontal_lx > 0.0)) continue;
            SkyLight k;
            k.description = "ground glow of " + sun.label + " (reflectance " + fmt_number(rho) + ")";
            k.sky = std::make_shared<const SkyDirections>(std::nullopt, 0.0,
                                                          rho * sun.unobstructed_horizontal_lx / kPi);
            k.horizon = disc->horizon;
            k.sun_altitude_deg = disc->sun_altitude_deg;
            k.sun_azimuth_deg = disc->sun_azimuth_deg;
            Light glow = sun;
            glow.label = sun.label + " ground glow";
            glow.unobstructed_horizontal_lx = 0.0;
            glow.kind = std::move(k);
            lights.push_back(std::move(glow));
        }
    }

    // `group`: the index of the entry's light group. Without the key the light is in the
    // default group, which therefore exists only if some light has no `group`.
    std::size_t group_of(TableReader& r) {
        const auto name = r.string("group");
        if (name) check_group_name(r, "group", *name);
        return group_named(name.value_or(Scene::kDefaultLightGroup));
    }

    std::size_t group_named(const std::string& group) {
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

    // A [[light]] type's reader: the kind's own keys into `l`; `type` for messages.
    using KindReader = void (LightReader::*)(TableReader& r, Light& l, const std::string& type);
    struct KindEntry {
        const char* type;
        KindReader read;
        bool at_positions;  // copies at `positions` or on a `grid`
    };
    // The [[light]] types, one reader each (light.hpp says where a new kind goes).
    static const KindEntry kKinds[6];

    // `flux_lm` or another positive amount the type needs.
    double required_positive(TableReader& r, const char* key, const std::string& type) {
        const auto f = r.number(key);
        if (!f) r.fail_entry("type '" + type + "' needs '" + key + "'");
        if (!(*f > 0.0)) r.fail(key, "must be positive, got " + std::to_string(*f));
        return *f;
    }

    void read_point(TableReader& r, Light& l, const std::string& type) {
        PointLight k;
        k.frame = placement_frame(r, "aim");
        if (r.has("ies") && r.has("photometry")) r.fail("photometry", "give 'photometry' or 'ies', not both");
        const std::string file_key = r.has("ies") ? "ies" : "photometry";
        if (const auto file = r.string(file_key)) {
            read_photometric(r, file_key, *file, k, l);
        } else {
            for (const char* key : {"emission", "lamp_set", "lamp_factor", "multiplier"})
                if (r.has(key)) r.fail(key, "applies to a light with 'photometry' (or 'ies') only");
            l.flux_lm = required_positive(r, "flux_lm", type) * l.dimming;
        }
        l.kind = std::move(k);
    }

    // A point light with a luminaire's photometry: the file's flux times the light's factors.
    void read_photometric(TableReader& r, const std::string& file_key, const std::string& file, PointLight& k,
                          Light& l) {
        k.multiplier = r.number("multiplier").value_or(1.0);
        if (!(k.multiplier > 0.0)) r.fail("multiplier", "must be positive");
        k.lamp_factor = factor(r, "lamp_factor", 1.0, 100.0);
        if (r.has("flux_lm"))
            r.fail("flux_lm", "with '" + file_key + "' the flux comes from the file (use 'multiplier')");
        const auto set = r.integer("lamp_set").value_or(1);
        if (set < 1 || set > 20) r.fail("lamp_set", "must lie in [1, 20]");
        std::tie(k.photometry, k.distribution) = photometry_of(r, file_key, file, static_cast<int>(set));
        const std::string emission = r.string("emission").value_or("opening");
        if (emission == "opening") k.opening = k.photometry->opening;
        else if (emission != "point") r.fail("emission", "must be \"opening\" or \"point\", got '" + emission + "'");
        // The file's own flux (exact for its interpolant), not the sampling table's, with
        // the lamp's output at this tilt (LM-63 TILT data).
        if (!k.photometry->tilt.empty()) k.tilt_factor = k.photometry->tilt.at(tilt_from_nadir_deg(k.frame));
        l.flux_lm = k.photometry->flux_lm() * k.multiplier * k.lamp_factor * l.dimming * k.tilt_factor;
        if (!(l.flux_lm > 0.0))
            r.fail(file_key, k.tilt_factor > 0.0 ? "the photometry carries no flux"
                                                 : "the file's TILT multiplier is 0 at this luminaire's tilt of " +
                                                       fmt_number(tilt_from_nadir_deg(k.frame)) + " degrees");
        if (!std::isfinite(l.flux_lm)) r.fail("multiplier", "the flux of the file times the multiplier is too large");
    }

    // The file's photometry and sampling table. Lights sharing a file share them (about
    // 1 MB each: one copy keeps it in cache).
    PhotometryPair photometry_of(TableReader& r, const std::string& file_key, const std::string& file, int set) {
        const std::string key = fs::weakly_canonical(load.resolve(file)).string() + "#" + std::to_string(set);
        if (const auto cached = photometry_cache.find(key); cached != photometry_cache.end()) return cached->second;
        Photometry photometry;
        try {
            photometry = load_photometry(load.resolve(file), set);
        } catch (const InputError& e) {  // say which scene entry named the file
            r.fail(r.has("lamp_set") && std::string(e.what()).find("lamp set") != std::string::npos ? "lamp_set"
                                                                                                    : file_key,
                   e.what());
        }
        std::shared_ptr<const PhotometryDistribution> dist;
        try {
            dist = std::make_shared<const PhotometryDistribution>(photometry);
        } catch (const std::invalid_argument&) {  // no light on the sampling grid
            r.fail(file_key, load.resolve(file).string() +
                                 ": its light lies in too narrow a beam for the 0.5 degree sampling grid");
        }
        for (const std::string& note : photometry.notes) scene.warnings.push_back(note);
        PhotometryPair pair{std::make_shared<const Photometry>(std::move(photometry)), std::move(dist)};
        photometry_cache.emplace(key, pair);
        return pair;
    }

    void read_spot(TableReader& r, Light& l, const std::string& type) {
        SpotLight k;
        l.flux_lm = required_positive(r, "flux_lm", type) * l.dimming;
        if (r.has("aim") && r.has("direction")) r.fail("aim", "give 'direction' or 'aim', not both");
        k.frame = placement_frame(r, r.has("aim") ? "aim" : "direction");
        const auto half = r.number("half_angle_deg");
        if (!half) r.fail_entry("type 'spot' needs 'half_angle_deg'");
        if (!(*half > 0.0 && *half <= 180.0)) r.fail("half_angle_deg", "must lie in (0, 180]");
        k.cos_half_angle = std::cos(*half * kPi / 180.0);
        l.kind = std::move(k);
    }

    void read_area(TableReader& r, Light& l, const std::string& type) {
        AreaLight k;
        l.flux_lm = required_positive(r, "flux_lm", type) * l.dimming;
        const auto shape = r.string("shape");
        if (!shape) r.fail_entry("type 'area' needs 'shape' (the name of a [[shape]])");
        k.surface = shape_surface(load, r, "shape", *shape);
        l.kind = std::move(k);
    }

    void read_directional(TableReader& r, Light& l, const std::string& type) {
        DirectionalLight k;
        const auto d = r.vec3("direction");
        if (!d) r.fail_entry("type 'directional' needs 'direction'");
        k.aim = unit_vector(r, "direction", *d);
        k.frame = Frame::around(k.aim);
        k.illuminance_lx = required_positive(r, "illuminance_lx", type) * l.dimming;
        l.kind = std::move(k);
    }

    // `colour`: the light's share per band, normalised (all bands alike without it).
    std::vector<double> band_shares(TableReader& r, const toml::table& t) {
        const std::size_t nb = scene.bands.size();
        std::vector<double> share(nb, 1.0);
        if (r.has("colour")) {
            if (t["colour"].is_array()) share = *r.numbers("colour", nb);
            else share.assign(nb, *r.number("colour"));
            double sum = 0.0;
            for (double c : share) {
                if (!(c >= 0.0)) r.fail("colour", "shares must not be negative");
                sum += c;
            }
            if (!(sum > 0.0)) r.fail("colour", "needs a positive share in some band");
            if (!std::isfinite(sum)) r.fail("colour", "shares are too large");
        }
        double share_sum = 0.0;
        for (double c : share) share_sum += c;
        for (double& c : share) c /= share_sum;
        return share;
    }

    // `label`: the light's name in messages and results, "light i (type)" unless given
    // (a Radiance model's lights are named by their modifier).
    std::vector<Light> parse_light(const toml::table& t, std::size_t i, const std::string& label = "") {
        TableReader r(t, fname, label.empty() ? entry_name("light", i, t) : label, "light");
        Light l;
        const std::string type = r.string("type").value_or("");
        l.label = label.empty() ? "light " + std::to_string(i + 1) + " (" + type + ")" : label;
        l.group = group_of(r);  // shared by every copy at `positions` or on the `grid`
        const auto kind = std::find_if(std::begin(kKinds), std::end(kKinds),
                                       [&](const KindEntry& k) { return type == k.type; });
        std::vector<Vec3> positions{Vec3(0.0)};
        if (kind != std::end(kKinds) && kind->at_positions) positions = light_positions(r, type);
        l.maintenance_factor = factor(r, "maintenance_factor", scene.maintenance_factor, 1.0);
        l.dimming = factor(r, "dimming", 1.0, 1.0);
        if (kind == std::end(kKinds))
            r.fail("type", "unknown light type '" + type + "' (expected point, spot, area, directional, sun or sky)");
        (this->*kind->read)(r, l, type);
        l.band_share = band_shares(r, t);
        r.finish();
        std::vector<Light> out;
        for (std::size_t k = 0; k < positions.size(); ++k) {
            Light copy = l;
            std::visit(
                [&](auto& c) {
                    if constexpr (requires { c.position; }) c.position = positions[k];
                },
                copy.kind);
            if (positions.size() > 1) copy.label += " #" + std::to_string(k + 1);
            out.push_back(std::move(copy));
        }
        return out;
    }
};

// The [[light]] types, one reader each (light.hpp says where a new kind goes).
const LightReader::KindEntry LightReader::kKinds[6] = {
    {"point", &LightReader::read_point, true}, {"spot", &LightReader::read_spot, true},
    {"area", &LightReader::read_area, false},  {"directional", &LightReader::read_directional, false},
    {"sun", &LightReader::read_sun, false},    {"sky", &LightReader::read_sky, false},
};

// Distant lights cover the sphere around the box [lo, hi], started just outside it; their
// flux is what crosses their disks (a portal's light keeps its opening's).
void place_beams(Vec3 lo, Vec3 hi, std::vector<Light>& lights) {
    for (Light& l : lights) l.place(lo, hi);
}

// Every light emits a positive, finite flux except a sun below the horizon; the scene's
// total is positive and finite.
void check_fluxes(const std::string& fname, const std::vector<Light>& lights) {
    double total_flux = 0.0;
    std::string dark;
    bool dark_through_portal = false;
    for (const Light& l : lights) {
        total_flux += l.flux_lm;
        if (l.may_be_dark()) {
            dark = l.label;
            dark_through_portal = l.is<PortalLight>();
            continue;
        }
        if (!(l.flux_lm > 0.0 && std::isfinite(l.flux_lm)) || !std::isfinite(total_flux))
            throw InputError(fname + ": " + l.label + ": its flux (" + fmt_number(l.flux_lm) +
                             " lm) makes the total flux of the scene too large or not positive");
    }
    if (!(total_flux > 0.0))
        throw InputError(fname + ": no light emits: " + dark +
                         (dark_through_portal ? " sends nothing through its opening" : " is below the horizon") +
                         " and the scene has no other light (give a sky, or another time)");
}

}  // namespace

EmitterSurface triangles_surface(const Scene& scene, const std::vector<std::size_t>& triangles) {
    EmitterSurface s;
    for (const std::size_t tri : triangles) {
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
    if (s.area_m2 > 0.0 && std::isfinite(s.area_m2))
        for (double& c : s.cdf) c /= s.area_m2;
    return s;
}

EmitterSurface shape_surface(const SceneLoad& load, const TableReader& r, const std::string& key,
                             const std::string& name) {
    const auto it = load.named_shapes.find(name);
    if (it == load.named_shapes.end()) r.fail(key, "no [[shape]] is named '" + name + "'");
    std::vector<std::size_t> triangles;
    for (std::size_t tri = it->second.first; tri < it->second.second; ++tri) triangles.push_back(tri);
    EmitterSurface s = triangles_surface(load.scene, triangles);
    if (!(s.area_m2 > 0.0 && std::isfinite(s.area_m2)))
        r.fail(key, "shape '" + name + "' has no area to emit from (its triangles are degenerate)");
    return s;
}

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
    Scene& scene = load.scene;
    if (root.has("annual")) {
        if (!load.radiance_lights.empty())
            throw InputError(load.fname +
                             ": [annual] makes the scene's lights (sky patches and suns from the weather "
                             "file), and its Radiance model brings " +
                             load.radiance_lights[0].label + ": leave the model's sky and lights out of an annual run");
        if (!tables.empty())
            throw InputError(load.fname + ": [annual] makes the scene's lights (sky patches and suns from the weather "
                                          "file): remove its [[light]] tables");
        read_annual(load, root, lights, scene.light_groups);
        place_beams(scene.bounds_min, scene.bounds_max, lights);
        scene.lights = LightSet(std::move(lights));
        return;
    }
    for (std::size_t i = 0; i < tables.size(); ++i)
        for (Light& l : reader.parse_light(*tables[i], i)) lights.push_back(std::move(l));
    for (SceneLoad::RadianceLight& rl : load.radiance_lights) {
        if (!rl.table.empty()) {
            reader.perez_day_of_year = rl.day_of_year;
            for (Light& l : reader.parse_light(rl.table, lights.size(), rl.label)) lights.push_back(std::move(l));
            reader.perez_day_of_year.reset();
            continue;
        }
        rl.light.group = reader.group_named(Scene::kDefaultLightGroup);
        lights.push_back(std::move(rl.light));
    }
    if (lights.empty())
        throw InputError(load.fname + (root.has("radiance")
                                           ? ": the scene has no light: no [[light]], and its Radiance models have no "
                                             "light, glow or spotlight surface, no distant source and no !gensky or "
                                             "!gendaylit (add the sky file: luxtrace run sky.rad model.rad ...)"
                                           : ": the scene has no [[light]]"));
    reader.add_sun_ground_glow(lights);
    place_beams(scene.bounds_min, scene.bounds_max, lights);
    check_fluxes(load.fname, lights);
    scene.lights = LightSet(std::move(lights));
    scene.light_groups = std::move(reader.groups);
    if (!scene.lights.maintenance_factor_uniform())
        scene.warnings.push_back("maintenance factors differ between lights: results are initial values, and the "
                                 "maintained ones luxtrace reports use the flux-weighted mean factor (" +
                                 fmt_number(scene.lights.maintenance_factor()) + ")");
}

void cover_detectors_with_beams(SceneLoad& load) {
    Scene& scene = load.scene;
    const auto& lights = scene.lights.lights();
    if (std::none_of(lights.begin(), lights.end(), [](const Light& l) { return l.distant(); })) return;
    Vec3 lo = scene.bounds_min, hi = scene.bounds_max;
    for (const Detector& d : scene.detectors) {
        if (d.type == DetectorType::points) {  // every sensor's disc
            for (const Vec3& p : d.sensors.positions()) {
                lo = glm::min(lo, p - Vec3(d.radius_m));
                hi = glm::max(hi, p + Vec3(d.radius_m));
            }
            continue;
        }
        // The rectangle's corners; cylinders reach half their height off the plane.
        const double depth = d.cylinders() ? 0.5 * d.height_m : 0.0;
        for (const double a : {-0.5, 0.5})
            for (const double b : {-0.5, 0.5})
                for (const double c : {-1.0, 1.0}) {
                    const Vec3 p = d.center + a * d.size_u * d.u_axis + b * d.size_v * d.v_axis + c * depth * d.normal;
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
    }
    if (lo == scene.bounds_min && hi == scene.bounds_max) return;
    std::vector<Light> placed = lights;
    place_beams(lo, hi, placed);
    check_fluxes(load.fname, placed);
    scene.lights = LightSet(std::move(placed));
}

}  // namespace luxtrace::detail
