#pragma once
// A Radiance model's `!gensky ...` / `!gendaylit ...` line as the sky and sun luxtrace's
// daylight lights would need to give what Radiance would render from that line's output
// (issue 25 §1; docs/RADIANCE.md "Skies"). Nothing is run: the programs' formulas are
// reproduced (Radiance src/gen/gensky.c, sun.c, gendaylit.c and skybright.cal, cited in
// radiance_sky.cpp) and every approximation the mapping makes is said in `notes`.
//
// The values are plain: they are the keys of `[[light]] type = "sky"` and `type = "sun"`
// (docs/REFERENCE.md §2), so the caller makes the lights from them. Radiance radiance
// (W sr^-1 m^-2) becomes luminance at Radiance's 179 lm/W (kRadianceEfficacy_lm_per_W),
// which is what Radiance itself reports (rtrace -I times 179), so results compare.
// Azimuths are luxtrace's, clockwise from north (+y of the model) seen from above, after
// the command's enclosing !xform transforms.
#include "luxtrace/scene/radiance_reader.hpp"

#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

// The `[[light]] type = "sky"` keys.
struct RadianceSkyLight {
    std::string sky;   // "cie", "perez" or "uniform"
    int cie_type = 0;  // sky = "cie": 12 (gensky -s/+s), 7 (-i/+i, nearest), 16 (-c)
    // sky = "cie" or "uniform": exactly one of these two; sky = "perez": neither.
    std::optional<double> zenith_luminance_cd_m2;
    std::optional<double> diffuse_horizontal_lx;
    // sky = "perez": the hour's irradiances, dew point and the day of the year gendaylit
    // takes the extraterrestrial irradiance from (365 for -ang, where gendaylit's day is 0).
    double diffuse_horizontal_w_m2 = 0.0;
    double direct_normal_w_m2 = 0.0;
    double dew_point_c = 0.0;
    int day_of_year = 0;
    // The sun the sky is drawn around (also set for "uniform" and type 16, which ignore it).
    double sun_altitude_deg = 0.0;
    double sun_azimuth_deg = 0.0;
    double ground_reflectance = 0.2;
};

// The `[[light]] type = "sun"` keys.
struct RadianceSunLight {
    double direct_normal_lx = 0.0;
    double sun_altitude_deg = 0.0;
    double sun_azimuth_deg = 0.0;
};

struct RadianceSky {
    std::string command;  // "gensky 3 21 12 -a 40 ..." as written
    RadianceSkyLight sky;
    std::optional<RadianceSunLight> sun;  // none for gensky -s/-i/-c/-u, gendaylit -s, or no direct light
    std::vector<std::string> notes;       // each approximation the mapping made
    // One line for `luxtrace check`: "COMMAND -> CIE type 12 sky, zenith ... cd/m2, sun ...".
    std::string describe() const;
};

// Maps one of `model.sky_commands`. Throws InputError naming the line's file:line and the
// option for an option luxtrace cannot represent, a malformed argument, a sun the sky
// needs below the horizon, or an enclosing !xform that tilts the sky (anything but
// rotations about z, mirrors in x or y, scaling and translation).
RadianceSky map_radiance_sky(const RadianceModel& model, const RadianceCommand& cmd);

}  // namespace luxtrace
