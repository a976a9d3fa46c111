// [site] -> Scene::site (docs/REFERENCE.md §2): the geographic site, local standard time and
// the scene's north, for the sun's position (docs/DAYLIGHT.md).
#include "luxtrace/core/error.hpp"
#include "scene_loader.hpp"

#include <cmath>

namespace luxtrace::detail {

void read_site(SceneLoad& load, TableReader& root) {
    const toml::table* t = root.table("site");
    if (t == nullptr) return;
    TableReader r(*t, load.fname, "[site]", "site");
    Site& site = load.scene.site;
    auto in_range = [&](const char* key, double lo, double hi, double fallback) {
        const double v = r.number(key).value_or(fallback);
        if (!(v >= lo && v <= hi)) r.fail(key, "must lie in [" + fmt_number(lo) + ", " + fmt_number(hi) + "]");
        return v;
    };
    const int located = int(r.has("latitude_deg")) + int(r.has("longitude_deg")) + int(r.has("utc_offset_h"));
    if (located != 0 && located != 3)
        r.fail_entry("give 'latitude_deg', 'longitude_deg' and 'utc_offset_h' together (the sun's position needs all "
                     "three)");
    site.located = located == 3;
    site.sun_site.latitude_deg = in_range("latitude_deg", -90.0, 90.0, 0.0);
    site.sun_site.longitude_deg = in_range("longitude_deg", -180.0, 180.0, 0.0);  // east positive
    site.utc_offset_h = in_range("utc_offset_h", -18.0, 18.0, 0.0);
    site.sun_site.elevation_m = in_range("elevation_m", -1000.0, 10000.0, 0.0);
    site.sun_site.pressure_mbar = in_range("pressure_mbar", 100.0, 1200.0, site.sun_site.pressure_mbar);
    site.sun_site.temperature_c = in_range("temperature_c", -90.0, 60.0, site.sun_site.temperature_c);
    site.sun_site.delta_t_s = in_range("delta_t_s", -8000.0, 8000.0, site.sun_site.delta_t_s);
    if (const auto north = r.vec3("north")) {
        if (std::abs(north->z) > 1e-9 * glm::length(*north)) r.fail("north", "must be horizontal (z = 0): up is +z");
        site.north = unit_vector(r, "north", *north);
    }
    if (r.has("time")) {
        const auto text = r.string("time");
        if (!text) r.fail("time", "expected a string \"YYYY-MM-DDTHH:MM\" of local standard time");
        const auto time = parse_local_time(*text);
        if (!time)
            r.fail("time", "'" + *text +
                               "' is not a local standard time \"YYYY-MM-DDTHH:MM\" or \"YYYY-MM-DDTHH:MM:SS\" (a "
                               "date that exists, a time from 00:00 to 24:00)");
        site.time = *time;
        site.time->utc_offset_h = site.utc_offset_h;
        site.time_text = *text;
        if (!site.located)
            r.fail("time", "needs 'latitude_deg', 'longitude_deg' and 'utc_offset_h' for the sun's position");
    }
    r.finish();
}

}  // namespace luxtrace::detail
