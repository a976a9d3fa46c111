// [annual] -> Scene::annual and the lights of an annual daylight run (docs/ANNUAL.md,
// docs/REFERENCE.md §2): the weather file's sky patches, ground and hourly suns, each its
// own light group, emitting the year's sum of its hourly luminance (annual_sky.hpp).
#include "luxtrace/annual/annual_sky.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/sky_directions.hpp"
#include "scene_loader.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace luxtrace::detail {

namespace {

// How the grids get their light: [annual] direct, indirect, their rays, patches and the
// suns' groups.
void read_light_ways(TableReader& r, AnnualOptions& o) {
    if (const auto direct = r.string("direct")) {
        if (*direct != "photons" && *direct != "shadow_rays")
            r.fail("direct", "must be \"photons\" or \"shadow_rays\", got '" + *direct + "'");
        o.direct = *direct;
    }
    if (const auto indirect = r.string("indirect")) {
        if (*indirect != "photons" && *indirect != "gather")
            r.fail("indirect", "must be \"photons\" or \"gather\", got '" + *indirect + "'");
        if (*indirect == "gather" && !o.shadow_rays()) r.fail("indirect", "\"gather\" needs direct = \"shadow_rays\"");
        o.indirect = *indirect;
    }
    if (const auto patch = r.number("gather_patch_m")) {
        if (!(*patch > 0.0 && *patch <= 1e3)) r.fail("gather_patch_m", "must lie in (0, 1000] m");
        if (!o.gathers()) r.fail("gather_patch_m", "is for indirect = \"gather\"");
        o.gather_patch_m = *patch;
    }
    struct RaysKey {
        const char* key;
        int* rays;
        const char* zero;  // what 0 means, if allowed
    };
    for (const RaysKey k :
         {RaysKey{"direct_sky_rays", &o.direct_sky_rays, "about 9,216 per sensor"},
          RaysKey{"direct_sun_rays", &o.direct_sun_rays, nullptr}, RaysKey{"gather_rays", &o.gather_rays, nullptr}})
        if (const auto n = r.integer(k.key)) {
            if (!(AnnualOptions::valid_direct_rays(*n) || (k.zero != nullptr && *n == 0)))
                r.fail(k.key, std::string("must be the square of an even number, 4 to 4096 (4, 16, 36, 64, ...)") +
                                  (k.zero != nullptr ? std::string(", or 0 for ") + k.zero : "") + ", got " +
                                  std::to_string(*n));
            const bool gather_key = std::string(k.key) == "gather_rays";
            if (gather_key && !o.gathers()) r.fail(k.key, "is for indirect = \"gather\"");
            if (!gather_key && !o.shadow_rays()) r.fail(k.key, "is for direct = \"shadow_rays\"");
            *k.rays = static_cast<int>(*n);
        }
    // With the direct sun by shadow rays the suns' photons carry only their interreflected
    // light, which a week of one clock hour shares (docs/ANNUAL.md "Suns' light groups").
    o.sun_group_days = o.shadow_rays() ? AnnualOptions::kShadowRaySunGroupDays : 1;
    if (const auto days = r.integer("sun_group_days")) {
        if (*days < 1 || *days > 366)
            r.fail("sun_group_days", "must lie in 1 to 366 days, got " + std::to_string(*days));
        if (*days > 1 && !o.shadow_rays())
            r.fail("sun_group_days", "above 1 needs direct = \"shadow_rays\" (the direct sun stays each hour's own)");
        o.sun_group_days = static_cast<int>(*days);
    }
}

AnnualOptions read_options(SceneLoad& load, TableReader& r) {
    AnnualOptions o;
    const auto weather = r.string("weather");
    if (!weather) r.fail_entry("needs 'weather' (an EnergyPlus .epw or a Radiance .wea file)");
    o.weather = load.resolve(*weather).lexically_normal();
    if (const auto mf = r.integer("sky_mf")) {
        if (*mf < 1 || *mf > 6)
            r.fail("sky_mf",
                   "must be 1 (Tregenza's 145 patches) to 6 (Reinhart's subdivisions), got " + std::to_string(*mf));
        o.sky_mf = static_cast<int>(*mf);
    }
    if (const auto sky = r.string("sky")) {
        if (*sky != "perez" && *sky != "cie") r.fail("sky", "must be \"perez\" or \"cie\", got '" + *sky + "'");
        o.sky = *sky;
    }
    if (const auto type = r.integer("cie_type")) {
        if (o.sky != "cie") r.fail("cie_type", "is for sky = \"cie\"");
        if (*type < 1 || *type > 16) r.fail("cie_type", "must be 1 to 16, got " + std::to_string(*type));
        o.cie_type = static_cast<int>(*type);
    }
    if (const auto rho = r.number("ground_reflectance")) {
        if (!(*rho >= 0.0 && *rho <= 1.0)) r.fail("ground_reflectance", "must lie in [0, 1]");
        o.ground_reflectance = *rho;
    }
    if (const auto hours = r.numbers("occupied_hours", 2)) {
        if (!((*hours)[0] >= 0.0 && (*hours)[0] < (*hours)[1] && (*hours)[1] <= 24.0))
            r.fail("occupied_hours", "must be [from, to] with 0 <= from < to <= 24 (local standard time)");
        o.occupied_from_h = (*hours)[0];
        o.occupied_to_h = (*hours)[1];
    }
    if (const auto folder = r.string("ladybug_folder")) {
        if (folder->empty()) {
            o.write_ladybug = false;
        } else {
            o.ladybug_folder = load.resolve(*folder);
        }
    }
    read_light_ways(r, o);
    if (const auto year = r.integer("year")) {
        if (*year < 1900 || *year > 2200) r.fail("year", "must lie in 1900 to 2200");
        o.year = static_cast<int>(*year);
    }
    return o;
}

// The weather file's site, or the scene's [site] if it agrees with it.
void reconcile_site(SceneLoad& load, TableReader& r, const weather::WeatherFile& w) {
    Site& site = load.scene.site;
    const weather::WeatherSite& ws = w.site;
    if (!site.located) {
        site.located = true;
        site.sun_site.latitude_deg = ws.latitude_deg;
        site.sun_site.longitude_deg = ws.longitude_deg;
        site.sun_site.elevation_m = ws.elevation_m;
        site.utc_offset_h = ws.time_zone_h;
        return;
    }
    // A tenth of a degree is 11 km: the same place, whatever rounding the files use.
    auto differs = [&](const char* what, double scene, double file, double tolerance) {
        if (std::abs(scene - file) > tolerance) {
            char text[160];
            std::snprintf(text, sizeof text, "[site] %s is %g but the weather file %s says %g", what, scene,
                          w.path.c_str(), file);
            r.fail("weather", text);
        }
    };
    differs("latitude_deg", site.sun_site.latitude_deg, ws.latitude_deg, 0.1);
    differs("longitude_deg", site.sun_site.longitude_deg, ws.longitude_deg, 0.1);
    differs("utc_offset_h", site.utc_offset_h, ws.time_zone_h, 1e-6);
}

std::string padded(const char* prefix, std::size_t i, int width) {
    char text[32];
    std::snprintf(text, sizeof text, "%s%0*zu", prefix, width, i);
    return text;
}

// Sky patches: Radiance's bin numbers (sky_patches.hpp), 1-based; one group each.
void add_patch_lights(const AnnualSky& sky, const Frame& horizon, AnnualSetup& setup, std::vector<Light>& lights,
                      std::vector<std::string>& groups) {
    const SkyPatches& patches = sky.patches();
    const std::vector<double>& yearly = sky.yearly_luminance();
    setup.first_patch_group = 0;
    for (std::size_t i = 0; i < patches.count(); ++i) {
        groups.push_back(padded("sky_", i + 1, patches.count() >= 1000 ? 4 : 3));
        const SkyPatches::Patch& p = patches.patch(i);
        SkyPatchLight k;
        k.horizon = horizon;
        k.patch.mu_lo = std::sin(p.alt_lo_deg * kPi / 180.0);
        k.patch.mu_hi = std::sin(p.alt_hi_deg * kPi / 180.0);
        k.patch.az_lo_rad = p.az_lo_deg * kPi / 180.0;
        k.patch.az_width_rad = (p.az_hi_deg - p.az_lo_deg) * kPi / 180.0;
        k.luminance_cd_m2 = yearly[i];
        Light l;
        l.label = "sky patch " + std::to_string(i + 1);
        l.group = groups.size() - 1;
        l.band_share = {1.0};
        l.kind = std::move(k);
        if (yearly[i] > 0.0) lights.push_back(std::move(l));
    }
}

// The ground below the horizon, a uniform glow of the year's reflected light.
void add_ground_light(const AnnualSky& sky, const Frame& horizon, AnnualSetup& setup, std::vector<Light>& lights,
                      std::vector<std::string>& groups) {
    const std::vector<double>& yearly = sky.yearly_luminance();
    setup.ground_group = groups.size();
    groups.push_back("ground");
    if (const double ground = yearly[sky.ground_entry()]; ground > 0.0) {
        SkyLight k;
        k.horizon = horizon;
        k.sky = std::make_shared<const SkyDirections>(std::nullopt, 0.0, ground);
        k.description = "annual ground glow (reflectance " + fmt_number(setup.options.ground_reflectance) + ")";
        Light l;
        l.label = "annual ground";
        l.group = setup.ground_group;
        l.band_share = {1.0};
        l.kind = std::move(k);
        lights.push_back(std::move(l));
    }
}

// One sun per daylit hour with the sun up, in its own group, or in its row's
// (sun_group_days): "suns_DDD_HH", its first day and the clock hour.
void add_sun_lights(const AnnualSky& sky, const Frame& horizon, AnnualSetup& setup, std::vector<Light>& lights,
                    std::vector<std::string>& groups) {
    setup.first_sun_group = groups.size();
    setup.shared_sun_row = sun_rows_of_days(sky, setup.options.sun_group_days);
    const double cos_half = std::cos(kSunHalfAngleDeg * kPi / 180.0);
    for (std::size_t s = 0; s < sky.suns().size(); ++s) {
        const AnnualHour& h = sky.hours()[sky.suns()[s]];
        if (setup.shared_sun_row.empty()) {
            groups.push_back(padded("sun_", sky.suns()[s] + 1, 4));
        } else if (setup.first_sun_group + setup.sun_row(s) == groups.size()) {
            const std::size_t hour = sky.suns()[s];
            groups.push_back(padded("suns_", hour / 24 + 1, 3) + padded("_", hour % 24, 2));
        }
        SunLight k;
        k.illuminance_lx = h.direct_normal_lx;
        k.sun_altitude_deg = h.sun_altitude_deg;
        k.sun_azimuth_deg = h.sun_azimuth_deg;
        k.cos_half_angle = cos_half;
        k.horizon = horizon;
        k.aim = -horizon.to_world(sky_direction_deg(h.sun_altitude_deg, h.sun_azimuth_deg));
        k.frame = Frame::around(k.aim);
        Light l;
        l.label = "sun of hour " + std::to_string(sky.suns()[s] + 1);
        l.group = setup.sun_group(static_cast<int>(s));
        l.annual_sun = static_cast<std::int64_t>(s);
        l.band_share = {1.0};
        l.kind = std::move(k);
        lights.push_back(std::move(l));
    }
}

void add_annual_lights(const AnnualSky& sky, const Frame& horizon, AnnualSetup& setup, std::vector<Light>& lights,
                       std::vector<std::string>& groups) {
    groups.clear();
    add_patch_lights(sky, horizon, setup, lights, groups);
    add_ground_light(sky, horizon, setup, lights, groups);
    add_sun_lights(sky, horizon, setup, lights, groups);
}

}  // namespace

void read_annual(SceneLoad& load, TableReader& root, std::vector<Light>& lights, std::vector<std::string>& groups) {
    TableReader r(*root.table("annual"), load.fname, "[annual]", "annual");
    Scene& scene = load.scene;
    if (scene.band_count() != 1)
        r.fail_entry("annual daylight is photometric: the scene must have one band (bands = [\"Y\"])");
    AnnualSetup setup;
    setup.options = read_options(load, r);
    weather::WeatherFile w;
    // The weather file's own errors name its file and line; the scene's key says which file.
    try {
        w = weather::read_weather_file(setup.options.weather.string());
    } catch (const std::exception& e) {
        r.fail("weather", e.what());
    }
    reconcile_site(load, r, w);
    std::shared_ptr<const AnnualSky> sky;
    try {
        sky = std::make_shared<const AnnualSky>(w, scene.site.sun_site, scene.site.utc_offset_h, setup.options,
                                                load.sky_share);
    } catch (const InputError& e) {
        r.fail("weather", e.what());
    }
    r.finish();
    if (sky->daylit_hours() == 0) r.fail("weather", w.path + " has no hour with the sun up and daylight");
    add_annual_lights(*sky, scene.site.horizon(), setup, lights, groups);
    setup.sky = std::move(sky);
    scene.annual = std::move(setup);
}

}  // namespace luxtrace::detail
