// gensky and gendaylit lines mapped to luxtrace's sky and sun (issue 25 §1, docs/RADIANCE.md
// "Skies"): Radiance's azimuth convention (degrees west of south), the sun's position from
// a date against NREL's SPA, the brightness formulas of gensky.1 / gensky.c, the units at
// 179 lm/W (Honeybee's 558.659 W/m2 is 100 klx), the Perez inputs of gendaylit, the
// enclosing xform, and every malformed line refused with its file and line.
#include "luxtrace/scene/radiance_sky.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/light/site.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "luxtrace/light/sun_position.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = kPi / 180.0;

// Each test process writes its own files (ctest runs the cases as parallel processes).
fs::path write_model(const std::string& text) {
    static const test_support::ScratchDir dir("radiance_sky");
    static int n = 0;
    const fs::path p = dir.path() / ("sky_" + std::to_string(++n) + ".rad");
    std::ofstream(p) << text;
    return p;
}

// The model of one line `!LINE` (after a comment line, so the command is on line 2).
RadianceSky sky_of(const std::string& line) {
    const RadianceModel m = read_radiance(write_model("# a sky\n!" + line + "\n"));
    EXPECT_EQ(m.sky_commands.size(), 1u);
    return map_radiance_sky(m, m.sky_commands.at(0));
}

// The message of the InputError the line raises ("" if none).
std::string error_of(const std::string& line) {
    try {
        sky_of(line);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

double solid_angle_sr(double full_angle_deg) { return 2.0 * kPi * (1.0 - std::cos(0.5 * full_angle_deg * kDeg)); }

TEST(RadianceSky, AngAzimuthIsDegreesWestOfSouth) {
    // gensky.1: "the azimuth is measured in degrees west of South"; luxtrace's clockwise from north.
    const struct {
        double radiance_deg, luxtrace_deg;
    } cases[] = {{0.0, 180.0}, {90.0, 270.0}, {-90.0, 90.0}, {180.0, 0.0}, {-40.0, 140.0}, {45.0, 225.0}};
    for (const auto& c : cases) {
        const RadianceSky s = sky_of("gensky -ang 35 " + std::to_string(c.radiance_deg) + " +s");
        EXPECT_NEAR(s.sky.sun_altitude_deg, 35.0, 1e-9);
        EXPECT_NEAR(std::fmod(s.sky.sun_azimuth_deg + 360.0 - c.luxtrace_deg, 360.0), 0.0, 1e-9) << c.radiance_deg;
        ASSERT_TRUE(s.sun);
        EXPECT_NEAR(s.sun->sun_azimuth_deg, s.sky.sun_azimuth_deg, 0.0);
        // The same direction gensky writes for its source: x east, y north, (-sin A cos h, -cos A cos h, sin h).
        const Vec3 d = sky_direction_deg(s.sky.sun_altitude_deg, s.sky.sun_azimuth_deg);
        const double a = c.radiance_deg * kDeg, h = 35.0 * kDeg;
        EXPECT_NEAR(d.x, -std::sin(a) * std::cos(h), 1e-12);
        EXPECT_NEAR(d.y, -std::cos(a) * std::cos(h), 1e-12);
    }
}

TEST(RadianceSky, HoneybeeDaylightFactorSkyIsOneHundredKilolux) {
    // Honeybee writes `gensky -c -B 558.659` for daylight factors: 558.659 W/m2 x 179 lm/W = 100 klx.
    const RadianceSky s = sky_of("gensky 9 21 12 -a 42 -o 71 -m 75 -c -B 558.659");
    EXPECT_EQ(s.sky.sky, "cie");
    EXPECT_EQ(s.sky.cie_type, 16);
    ASSERT_TRUE(s.sky.diffuse_horizontal_lx);
    EXPECT_FALSE(s.sky.zenith_luminance_cd_m2);
    EXPECT_NEAR(*s.sky.diffuse_horizontal_lx, 100000.0, 0.05);
    EXPECT_FALSE(s.sun);
    EXPECT_DOUBLE_EQ(s.sky.ground_reflectance, 0.2);  // gensky's default -g
    // gensky's overcast normalisation 0.777778 is the exact E_h / (pi L_z) of the CIE overcast
    // sky L = L_z (1 + 2 cos Z) / 3, so its -B and luxtrace's diffuse_horizontal_lx agree.
    EXPECT_NEAR(SkyModel::cie(16, 0, 0).horizontal_illuminance_per_zenith_luminance_sr() / kPi, 0.777778, 1e-6);
}

TEST(RadianceSky, SkyTypesAndSuns) {
    EXPECT_EQ(sky_of("gensky -ang 40 0 +s").sky.cie_type, 12);  // the CIE clear sky of skybright.cal
    EXPECT_TRUE(sky_of("gensky -ang 40 0 +s").sun);
    EXPECT_FALSE(sky_of("gensky -ang 40 0 -s").sun);
    EXPECT_EQ(sky_of("gensky -ang 40 0 -i").sky.cie_type, 7);
    EXPECT_FALSE(sky_of("gensky -ang 40 0 -i").sun);
    EXPECT_FALSE(sky_of("gensky -ang 40 0 -c").sun);
    EXPECT_EQ(sky_of("gensky -ang 40 0 -u").sky.sky, "uniform");
    EXPECT_FALSE(sky_of("gensky -ang 40 0 -u").sun);
    // gensky.c: the +i sun is 15 % of the +s sun ("somewhat subdued", gensky.1).
    EXPECT_NEAR(sky_of("gensky -ang 40 0 +i").sun->direct_normal_lx /
                    sky_of("gensky -ang 40 0 +s").sun->direct_normal_lx,
                0.15, 1e-12);
    // -r 0: "no sun description is produced" (gensky.1).
    EXPECT_FALSE(sky_of("gensky -ang 40 0 +s -r 0").sun);
    // The last sky option counts, as gensky reads them in order.
    EXPECT_EQ(sky_of("gensky -ang 40 0 -c +s").sky.cie_type, 12);
}

TEST(RadianceSky, DefaultBrightnessFollowsGenskysFormulas) {
    // gensky.c: clear zenith (1.376 T - 1.81) tan(h) + 0.38 kcd/m2 (T = 2.45 by default),
    // overcast 8.6 sin(h) + 0.123 kcd/m2, intermediate their mean; written as radiance at
    // 203 lm/W, which Radiance reads back at 179 lm/W.
    const double back = 179.0 / 203.0 * 1000.0;
    EXPECT_NEAR(*sky_of("gensky -ang 45 0 +s").sky.zenith_luminance_cd_m2, (1.376 * 2.45 - 1.81 + 0.38) * back, 1e-9);
    EXPECT_NEAR(*sky_of("gensky -ang 45 0 +s -t 4").sky.zenith_luminance_cd_m2, (1.376 * 4 - 1.81 + 0.38) * back, 1e-9);
    EXPECT_NEAR(*sky_of("gensky -ang 30 0 -c").sky.zenith_luminance_cd_m2, (8.6 * 0.5 + 0.123) * back, 1e-9);
    EXPECT_NEAR(*sky_of("gensky -ang 30 0 -u").sky.zenith_luminance_cd_m2, (8.6 * 0.5 + 0.123) * back, 1e-9);
    // -b is the zenith radiance itself, -B the diffuse horizontal irradiance.
    EXPECT_NEAR(*sky_of("gensky -ang 30 0 +s -b 20").sky.zenith_luminance_cd_m2, 20.0 * 179.0, 1e-9);
    EXPECT_NEAR(*sky_of("gensky -ang 30 0 -s -B 100").sky.diffuse_horizontal_lx, 100.0 * 179.0, 1e-9);
    EXPECT_NEAR(*sky_of("gensky -ang 30 0 -i -B 100").sky.diffuse_horizontal_lx, 100.0 * 179.0, 1e-9);
}

TEST(RadianceSky, SunBrightnessFollowsGenskysFormulaAndItsIrradiances) {
    // Default solar radiance 1.5e9 / 208 (1.147 - 0.147 / max(sin h, 0.16)) W/sr/m2 of a 0.5 deg source.
    const double h = 45.0 * kDeg;
    const double radiance = 1.5e9 / 208.0 * (1.147 - 0.147 / std::sin(h));
    EXPECT_NEAR(sky_of("gensky -ang 45 0 +s").sun->direct_normal_lx, 179.0 * radiance * solid_angle_sr(0.5), 1e-6);
    // -r is that radiance; -R the direct horizontal irradiance, so the sun's horizontal
    // illuminance is 179 R (to gensky's rounding of the solid angle to 5.98e-5 sr).
    EXPECT_NEAR(sky_of("gensky -ang 45 0 +s -r 1e6").sun->direct_normal_lx, 179.0e6 * solid_angle_sr(0.5), 1e-6);
    const RadianceSky r = sky_of("gensky -ang 30 0 +s -R 400");
    EXPECT_NEAR(r.sun->direct_normal_lx * std::sin(30.0 * kDeg) / (179.0 * 400.0), 1.0, 3e-4);
}

// skybright.cal's intermediate sky (Matsuura), L / L_z without its F2 normalisation, for
// a point at zenith angle eta, gamma from the sun, the sun at zenith angle zt.
double gensky_intermediate(double eta, double gamma, double zt) {
    return ((1.35 * std::sin(5.631 - 3.59 * eta) + 3.12) * std::sin(4.396 - 2.6 * zt) + 6.37 - eta) / 2.326 *
           std::exp(gamma * -0.563 * ((2.629 - eta) * (1.562 - zt) + 0.812));
}

TEST(RadianceSky, IntermediateSkyIsNearestToCieType7AndKeepsGenskysHorizontalIlluminance) {
    for (const double h_deg : {20.0, 35.0, 50.0}) {
        const double zt = (90.0 - h_deg) * kDeg;
        // Midpoint sums over the upper hemisphere, cosine-weighted.
        double gensky_integral = 0.0;
        std::vector<double> err(16, 0.0);
        double norm = 0.0;
        constexpr int nz = 90, na = 180;
        for (int i = 0; i < nz; ++i)
            for (int j = 0; j < na; ++j) {
                const double z = (i + 0.5) * (kPi / 2.0) / nz, az = (j + 0.5) * 2.0 * kPi / na;
                const double w = std::sin(z) * std::cos(z) * (kPi / 2.0 / nz) * (2.0 * kPi / na);
                const double cg = std::cos(z) * std::cos(zt) + std::sin(z) * std::sin(zt) * std::cos(az - kPi);
                const double l = gensky_intermediate(z, std::acos(std::clamp(cg, -1.0, 1.0)), zt);
                gensky_integral += l * w;
                const double rel = l / gensky_intermediate(0.0, zt, zt);
                norm += w * rel * rel;
                for (int t = 1; t <= 15; ++t) {
                    const double m = SkyModel::cie(t, zt, kPi).relative_luminance(z, az);
                    err[static_cast<std::size_t>(t)] += w * (m - rel) * (m - rel);
                }
            }
        int best = 1;
        for (int t = 2; t <= 15; ++t)
            if (err[static_cast<std::size_t>(t)] < err[static_cast<std::size_t>(best)]) best = t;
        EXPECT_EQ(best, 7) << "sun altitude " << h_deg;
        EXPECT_LT(std::sqrt(err[7] / norm), 0.25);

        // gensky's polynomial fit of the horizontal irradiance (normsc / F2) against the
        // integral of its own distribution: -i -b 1 gives E_h / (179 pi) = normfactor.
        const double h = h_deg * kDeg;
        const double f2 = (2.739 + 0.9891 * std::sin(0.3119 + 2.6 * h)) *
                          std::exp(-(kPi / 2.0 - h) * (0.4441 + 1.48 * h));
        const RadianceSky s = sky_of("gensky -ang " + std::to_string(h_deg) + " 0 -i -b 1");
        EXPECT_NEAR(*s.sky.diffuse_horizontal_lx / 179.0, gensky_integral / f2, 0.03 * gensky_integral / f2)
            << "sun altitude " << h_deg;
    }
}

TEST(RadianceSky, SunPositionFromTheDateAgreesWithSpa) {
    // Golden, Colorado (39.74 N, 105.18 W, UTC-7): gensky's longitudes and meridians are
    // positive west. Its IES Handbook formulas hold to about a degree; with -y, Michalsky's
    // almanac algorithm to about 0.01 deg (against SPA's altitude before refraction, which
    // gensky does not add).
    const SunSite site{39.74, -105.18};
    const struct {
        int month, day;
        double hour;
    } cases[] = {{3, 21, 9.5}, {6, 21, 12.0}, {9, 10, 15.25}, {12, 21, 11.0}, {2, 5, 14.0}};
    for (const auto& c : cases) {
        const int minute = static_cast<int>(std::round((c.hour - std::floor(c.hour)) * 60.0));
        const SunPosition spa = sun_position({2021, c.month, c.day, static_cast<int>(c.hour), minute, 0.0, -7.0}, site);
        const std::string date = "gensky " + std::to_string(c.month) + " " + std::to_string(c.day) + " " +
                                 std::to_string(c.hour) + " -a 39.74 -o 105.18 -m 105 +s";
        const RadianceSky simple = sky_of(date), almanac = sky_of(date + " -y 2021");
        EXPECT_NEAR(simple.sky.sun_altitude_deg, spa.altitude_deg, 1.0) << date;
        EXPECT_NEAR(simple.sky.sun_azimuth_deg, spa.azimuth_deg, 1.5) << date;
        EXPECT_NEAR(almanac.sky.sun_altitude_deg, spa.spa.elevation_unrefracted, 0.02) << date;
        EXPECT_NEAR(almanac.sky.sun_azimuth_deg, spa.azimuth_deg, 0.02) << date;
    }
    // The hour's forms: H:MM, a time zone naming the meridian (overriding -m), solar time.
    const RadianceSky decimal = sky_of("gensky 5 4 14.5 -a 40 -o 100 -m 105 +s");
    const RadianceSky colon = sky_of("gensky 5 4 14:30 -a 40 -o 100 -m 105 +s");
    const RadianceSky zone = sky_of("gensky 5 4 14:30MST -a 40 -o 100 -m 90 +s");
    EXPECT_DOUBLE_EQ(colon.sky.sun_azimuth_deg, decimal.sky.sun_azimuth_deg);
    EXPECT_DOUBLE_EQ(zone.sky.sun_azimuth_deg, decimal.sky.sun_azimuth_deg);
    // At solar noon the sun stands due south of a northern site, at 90 - latitude + declination.
    const RadianceSky noon = sky_of("gensky 3 21 +12 -a 40 -o 30 +s");
    EXPECT_NEAR(noon.sky.sun_azimuth_deg, 180.0, 1e-9);
    EXPECT_NEAR(noon.sky.sun_altitude_deg, 50.0, 0.5);
    // ... and due north of a southern one.
    EXPECT_NEAR(sky_of("gensky 3 21 +12 -a -30 +s").sky.sun_azimuth_deg, 0.0, 1e-9);
}

TEST(RadianceSky, SunNearTheZenithIsLoweredTo87DegreesAsGenskyDoes) {
    const RadianceSky s = sky_of("gensky -ang 89 0 +s");
    EXPECT_NEAR(s.sky.sun_altitude_deg, 87.0, 1e-9);
    EXPECT_NEAR(s.sun->sun_altitude_deg, 87.0, 1e-9);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.describe().find("87 deg"), std::string::npos);
    EXPECT_NEAR(sky_of("gensky -ang 89 0 -c").sky.sun_altitude_deg, 89.0, 1e-9);  // not for the overcast sky
}

TEST(RadianceSky, GendaylitGivesThePerezSkysInputs) {
    const RadianceSky w = sky_of("gendaylit 6 21 12 -a 45 -o 0 -m 0 -W 800 120");
    EXPECT_EQ(w.sky.sky, "perez");
    EXPECT_FALSE(w.sky.zenith_luminance_cd_m2);
    EXPECT_FALSE(w.sky.diffuse_horizontal_lx);
    EXPECT_DOUBLE_EQ(w.sky.direct_normal_w_m2, 800.0);
    EXPECT_DOUBLE_EQ(w.sky.diffuse_horizontal_w_m2, 120.0);
    EXPECT_EQ(w.sky.day_of_year, 172);
    // gendaylit's default precipitable water is 2 cm (Td = 10.97353115 C in gendaylit.c).
    EXPECT_NEAR(precipitable_water_cm(w.sky.dew_point_c), 2.0, 1e-8);
    // The sun: the direct normal irradiance at Perez's direct efficacy.
    ASSERT_TRUE(w.sun);
    PerezSkyInput in;
    in.sun_zenith_rad = (90.0 - w.sky.sun_altitude_deg) * kDeg;
    in.diffuse_horizontal_w_m2 = 120.0;
    in.direct_normal_w_m2 = 800.0;
    in.dew_point_c = w.sky.dew_point_c;
    in.day_of_year = 172;
    const PerezSky perez(in, false);
    EXPECT_NEAR(w.sun->direct_normal_lx, 800.0 * perez.direct_efficacy_lm_w(), 1e-9);
    EXPECT_NEAR(sky_of("gendaylit 6 21 12 -a 45 -o 0 -m 0 -W 800 120 -d 20").sky.dew_point_c, 20.0, 0.0);

    // -G: direct horizontal, so direct normal = G / sin h.
    const RadianceSky g = sky_of("gendaylit -ang 30 0 -G 400 120");
    EXPECT_NEAR(g.sky.direct_normal_w_m2, 800.0, 1e-9);
    EXPECT_EQ(g.sky.day_of_year, 365);  // gendaylit -ang: day 0, the same day angle as 365
    // -P epsilon delta: the irradiances whose Perez clearness and brightness they are.
    const RadianceSky p = sky_of("gendaylit -ang 40 10 -P 3.5 0.2");
    const double z = 50.0 * kDeg;
    EXPECT_NEAR(perez_sky_clearness(p.sky.diffuse_horizontal_w_m2, p.sky.direct_normal_w_m2, z), 3.5, 1e-9);
    EXPECT_NEAR(perez_sky_brightness(p.sky.diffuse_horizontal_w_m2, z, 365), 0.2, 1e-12);
    // ... within gendaylit's range: epsilon in [1, 12.01), Delta in [0.01, 0.6].
    const RadianceSky clamped = sky_of("gendaylit -ang 40 10 -P 0.5 0.9");
    EXPECT_NEAR(clamped.sky.direct_normal_w_m2, 0.0, 1e-12);
    EXPECT_NEAR(perez_sky_brightness(clamped.sky.diffuse_horizontal_w_m2, z, 365), 0.6, 1e-12);
    // -E: Erbs splits the global irradiance, which the parts add up to again.
    const RadianceSky e = sky_of("gendaylit -ang 50 0 -E 600");
    EXPECT_NEAR(e.sky.diffuse_horizontal_w_m2 + e.sky.direct_normal_w_m2 * std::sin(50.0 * kDeg), 600.0, 1e-9);
    EXPECT_GT(e.sky.diffuse_horizontal_w_m2, 0.0);
    // No sun with -s, or for an overcast sky (epsilon 1: no direct light).
    EXPECT_FALSE(sky_of("gendaylit -ang 30 0 -W 800 120 -s").sun);
    EXPECT_FALSE(sky_of("gendaylit -ang 30 0 -W 0 120").sun);
}

TEST(RadianceSky, EnclosingXformTurnsTheSkyAboutTheZenith) {
    const fs::path inner = write_model("!gensky -ang 30 0 +s\n");
    const std::string name = inner.filename().string();
    auto placed = [&](const std::string& xform) {
        const RadianceModel m = read_radiance(write_model("!xform " + xform + " " + name + "\n"));
        return map_radiance_sky(m, m.sky_commands.at(0));
    };
    // South turned 90 deg counter-clockwise (seen from above) is east.
    EXPECT_NEAR(placed("-rz 90").sky.sun_azimuth_deg, 90.0, 1e-9);
    EXPECT_NEAR(placed("-rz 90").sun->sun_azimuth_deg, 90.0, 1e-9);
    EXPECT_NEAR(placed("-rz -30 -t 5 0 1 -s 2").sky.sun_azimuth_deg, 210.0, 1e-9);
    EXPECT_NEAR(placed("-my").sky.sun_azimuth_deg, 0.0, 1e-9);  // mirrored north-south
    EXPECT_NEAR(placed("-rz 90").sky.sun_altitude_deg, 30.0, 1e-9);
    const fs::path west = write_model("!gensky -ang 30 90 +s\n");
    const RadianceModel mx = read_radiance(write_model("!xform -mx " + west.filename().string() + "\n"));
    EXPECT_NEAR(map_radiance_sky(mx, mx.sky_commands.at(0)).sky.sun_azimuth_deg, 90.0, 1e-9);  // west to east
    // A tilt is refused, naming the line.
    const RadianceModel tilted = read_radiance(write_model("!xform -rx 10 " + name + "\n"));
    try {
        map_radiance_sky(tilted, tilted.sky_commands.at(0));
        ADD_FAILURE() << "a tilted sky was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(tilted.where(tilted.sky_commands[0].at)), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("tilts"), std::string::npos);
    }
}

TEST(RadianceSky, MalformedLinesNameTheFileLineAndOption) {
    const struct {
        const char* line;
        const char* says;
    } cases[] = {
        {"gensky 13 21 12", "month"},
        {"gensky 3 32 12", "day"},
        {"gensky 3 21 noon", "hour"},
        {"gensky 3 21 12XYZ", "unknown time zone"},
        {"gensky 3 21 12 -a", "-a is missing"},
        {"gensky 3 21 12 -a forty", "-a must be a number"},
        {"gensky 3 21 12 -q", "unknown option '-q'"},
        {"gensky -ang 30", "azimuth is missing"},
        {"gensky -ang 30 0 -g 1.5", "-g"},
        {"gensky 12 21 20 -a 40 +s", "below the horizon"},
        {"gensky -ang 30 0 -c -b 0", "dark"},
        {"gendaylit 3 21 12 -L 80000 20000", "-L"},
        {"gendaylit 3 21 12 -W 800 120 -O 1", "-O 1"},
        {"gendaylit 3 21 12 -W 800 120 -C", "-C"},
        {"gendaylit 3 21 12:30 -W 800 120", "H:MM"},
        {"gendaylit 3 21 12", "-W, -G, -P or -E"},
        {"gendaylit -ang 30 0 -W 1500 100", "direct normal"},
        {"gendaylit -ang 30 0 -W 800 0", "diffuse horizontal"},
        {"gendaylit 6 21 23 -a 45 -W 800 120", "below the horizon"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of(c.line);
        EXPECT_NE(e.find(".rad:2: "), std::string::npos) << c.line << " -> " << e;
        EXPECT_NE(e.find(c.says), std::string::npos) << c.line << " -> " << e;
    }
}

TEST(RadianceSky, DescribeSaysTheSkyTheSunAndTheApproximations) {
    const std::string d = sky_of("gensky 3 21 12 -a 40 -o 105 -m 105 +s").describe();
    EXPECT_EQ(d.rfind("gensky 3 21 12 -a 40 -o 105 -m 105 +s -> CIE type 12 sky, zenith ", 0), 0u) << d;
    EXPECT_NE(d.find("sun light, direct normal"), std::string::npos) << d;
    EXPECT_NE(d.find("203 lm/W"), std::string::npos) << d;
    EXPECT_NE(sky_of("gendaylit -ang 30 0 -W 800 120").describe().find("Perez sky (direct normal 800.0 W/m2"),
              std::string::npos);
}

}  // namespace
}  // namespace luxtrace
