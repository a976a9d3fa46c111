// [site] and the sun and sky lights in the scene loader (src/scene/site_loader.cpp,
// src/scene/light_loader.cpp; docs/DAYLIGHT.md): the sun stands where NREL's SPA puts it
// for the site and time and where the scene's north says; beams carry exactly the flux
// that crosses their disks; ground glow is its own emitter; a sun below the horizon emits
// nothing; bad daylight input is an InputError naming the file, line and key.
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "luxtrace/light/sun_position.hpp"

#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace luxtrace {
namespace {

using namespace test_support;

const std::string kSite =
    "[site]\nlatitude_deg = 39.742476\nlongitude_deg = -105.1786\nutc_offset_h = -7\nelevation_m = 1830.14\n"
    "pressure_mbar = 820\ntemperature_c = 11\ndelta_t_s = 67\ntime = \"2003-10-17T12:30:30\"\n";
const std::string kSun = "[[light]]\ntype = \"sun\"\ndirect_normal_lx = 80000\n";
const std::string kOvercast =
    "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = 10000\n";

const std::string kPerez = "[[light]]\ntype = \"sky\"\nsky = \"perez\"\nsun_altitude_deg = 50\nsun_azimuth_deg = 180\n"
                           "diffuse_horizontal_w_m2 = 120\ndirect_normal_w_m2 = 600\ndew_point_c = 12\n";

double deg(double d) { return d * kPi / 180.0; }

TEST_F(Loader, SunFromTheSiteIsSpasTestCase) {
    // The report's example through the scene file: zenith 50.111622, azimuth 194.340241.
    const Scene s = load(kSite + kMat + kFloor + kSun);
    const Light& light = s.lights.lights().at(0);
    ASSERT_TRUE(light.is<SunLight>());
    const SunLight& sun = *light.as<SunLight>();
    EXPECT_NEAR(sun.sun_altitude_deg, 90.0 - 50.111622, 1e-5);
    EXPECT_NEAR(sun.sun_azimuth_deg, 194.340241, 1e-5);
    // Travelling away from the sun: north +y, east +x, so from SSW towards NNE and down.
    const Vec3 to_sun(std::sin(deg(50.111622)) * std::sin(deg(194.340241)),
                      std::sin(deg(50.111622)) * std::cos(deg(194.340241)), std::cos(deg(50.111622)));
    expect_vec(sun.aim, -to_sun, 1e-6);
    EXPECT_NEAR(light.unobstructed_horizontal_lx, 80000.0 * std::cos(deg(50.111622)), 1e-3);
    EXPECT_NEAR(light.flux_lm, 80000.0 * kPi * sun.beam.radius * sun.beam.radius, 1e-9 * light.flux_lm);
    EXPECT_NEAR(sun.cos_half_angle, std::cos(deg(0.533 / 2.0)), 1e-12);
}

TEST_F(Loader, NorthTurnsTheSky) {
    // With north = +x, east is -y: a sun due east travels towards +y.
    const Scene s = load("[site]\nnorth = [2, 0, 0]\n" + kMat + kFloor +
                         "[[light]]\ntype = \"sun\"\ndirect_normal_lx = 1\nsun_altitude_deg = 0.5\n"
                         "sun_azimuth_deg = 90\n");
    const SunLight& sun = *s.lights.lights().at(0).as<SunLight>();
    expect_vec(sun.aim, Vec3(0, std::cos(deg(0.5)), -std::sin(deg(0.5))), 1e-12);
    expect_vec(sun.horizon.to_world(Vec3(0, 1, 0)), Vec3(1, 0, 0), 1e-15);  // north
}

TEST_F(Loader, SkyFluxIsWhatCrossesItsDiskAndGroundGlowIsItsOwnEmitter) {
    // Sky flux = pi R^2 x integral of L (sky_directions.hpp); its E_h,ext is the sky's own;
    // the sun's ground glow is a lower hemisphere of rho E_n sin h / pi in the sun's group.
    const Scene s = load(kMat + kFloor + kOvercast + "ground_reflectance = 0.2\ngroup = \"sky\"\n" + kSun +
                         "sun_altitude_deg = 30\nsun_azimuth_deg = 180\ngroup = \"sun\"\n");
    const auto& L = s.lights.lights();
    ASSERT_EQ(L.size(), 3u);
    ASSERT_TRUE(L[0].is<SkyLight>());
    const SkyLight& sky = *L[0].as<SkyLight>();
    EXPECT_DOUBLE_EQ(L[0].unobstructed_horizontal_lx, 10000.0);
    const double lz = 10000.0 / SkyModel::cie(16, 0, 0).horizontal_illuminance_per_zenith_luminance_sr();
    // The overcast sky's integral of L over the hemisphere: L_z 2 pi (1/3 + 2/3 x 1/2),
    // plus the ground glow 2 pi x 0.2 x 10000 / pi.
    const double integral = lz * 2.0 * kPi * (1.0 / 3.0 + 1.0 / 3.0) + 2.0 * 0.2 * 10000.0;
    EXPECT_NEAR(sky.sky->luminance_integral_cd_m2_sr() / integral, 1.0, 1e-6);
    EXPECT_NEAR(L[0].flux_lm, kPi * sky.beam.radius * sky.beam.radius * sky.sky->luminance_integral_cd_m2_sr(),
                1e-9 * L[0].flux_lm);
    const Light& glow = L[2];
    ASSERT_TRUE(glow.is<SkyLight>());
    EXPECT_EQ(glow.label, "light 2 (sun) ground glow");
    EXPECT_EQ(s.light_groups.at(glow.group), "sun");
    EXPECT_EQ(glow.unobstructed_horizontal_lx, 0.0);
    EXPECT_NEAR(glow.as<SkyLight>()->sky->luminance_integral_cd_m2_sr(), 2.0 * 0.2 * 80000.0 * 0.5, 1e-6);
    EXPECT_NEAR(L[1].unobstructed_horizontal_lx, 40000.0, 1e-9);
}

TEST_F(Loader, BeamsCoverEveryDetector) {
    // A detector far from the geometry still lies inside the beams' sphere.
    const Scene s = load(kMat + kFloor + kOvercast +
                         "[[detector]]\nname = \"far\"\ntype = \"illuminance\"\ncenter = [40, 0, 0]\n"
                         "normal = [0, 0, 1]\nup = [0, 1, 0]\nsize = [2, 2]\ncells = [1, 1]\n");
    const SkyLight& sky = *s.lights.lights().at(0).as<SkyLight>();
    for (const double x : {39.0, 41.0})
        for (const double y : {-1.0, 1.0}) EXPECT_LE(glm::length(Vec3(x, y, 0) - sky.beam.center), sky.beam.radius);
}

TEST_F(Loader, SunBelowTheHorizonEmitsNothingAndSaysSo) {
    const std::string night = "[site]\nlatitude_deg = 48\nlongitude_deg = 11\nutc_offset_h = 1\ntime = "
                              "\"2026-12-21T22:00\"\n";
    const Scene s = load(night + kMat + kFloor + kSun + kOvercast);
    EXPECT_EQ(s.lights.lights().at(0).flux_lm, 0.0);
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings.front().find("below the horizon at 2026-12-21T22:00"), std::string::npos)
        << s.warnings.front();
    // Alone it leaves nothing to trace.
    expect_bad(night + kMat + kFloor + kSun, "", {"no light emits", "light 1 (sun) is below the horizon"});
}

TEST_F(Loader, BadDaylightInput) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 17\ndiffuse_horizontal_lx = 1\n",
               "cie_type", {"key 'cie_type'", "1 to 16"});
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"sky\"\nsky = \"hosek\"\ndiffuse_horizontal_lx = 1\n",
               "sky =", {"key 'sky'", "\"cie\", \"perez\" or \"uniform\""});
    expect_bad(kMat + kFloor + kPerez + "diffuse_horizontal_lx = 1\n", "diffuse_horizontal_lx",
               {"key 'diffuse_horizontal_lx'", "drop this key"});
    expect_bad(kMat + kFloor + kPerez.substr(0, kPerez.find("dew_point_c")), "[[light]]", {"needs 'dew_point_c'"});
    std::string negative_direct = kPerez;
    negative_direct.replace(negative_direct.find("= 600"), 5, "= -3");
    expect_bad(kMat + kFloor + negative_direct, "direct_normal_w_m2", {"key 'direct_normal_w_m2'", "[0, 1367]"});
    expect_bad(kMat + kFloor + kOvercast + "zenith_luminance_cd_m2 = 3\n", "[[light]]",
               {"one of 'diffuse_horizontal_lx' and 'zenith_luminance_cd_m2'"});
    expect_bad(kMat + kFloor + kOvercast + "ground_reflectance = 1.5\n", "ground_reflectance",
               {"key 'ground_reflectance'", "[0, 1]"});
    expect_bad("[site]\nlatitude_deg = 48\nlongitude_deg = 11\nutc_offset_h = 1\ntime = \"2026-02-30T12:00\"\n" + kMat +
                   kFloor + kSun,
               "time", {"key 'time'", "2026-02-30T12:00", "is not a local standard time"});
    expect_bad("[site]\nlatitude_deg = 48\nlongitude_deg = 11\nutc_offset_h = 1\ntime = \"noon\"\n" + kMat + kFloor +
                   kSun,
               "time", {"key 'time'"});
    expect_bad("[site]\nlatitude_deg = 48\nlongitude_deg = 11\n" + kMat + kFloor + kSun, "[site]",
               {"'utc_offset_h'", "together"});
    expect_bad("[site]\nlatitude_deg = 95\nlongitude_deg = 11\nutc_offset_h = 1\n" + kMat + kFloor + kSun,
               "latitude_deg", {"key 'latitude_deg'", "[-90, 90]"});
    expect_bad(kMat + kFloor + kSun, "[[light]]", {"needs the sun's position", "[site]"});
    expect_bad(kMat + kFloor + kSun + "sun_altitude_deg = 30\n", "sun_altitude_deg", {"'sun_azimuth_deg' together"});
    expect_bad("[site]\nnorth = [0, 1, 1]\n" + kMat + kFloor + kOvercast, "north", {"key 'north'", "horizontal"});
    expect_bad(kMat + kFloor +
                   "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 12\nsun_altitude_deg = -5\n"
                   "sun_azimuth_deg = 180\ndiffuse_horizontal_lx = 1\n",
               "sun_altitude_deg", {"below the horizon", "cie_type 16"});
    // A key of another light type.
    expect_bad(kMat + kFloor + kOvercast + "direct_normal_lx = 5\n", "direct_normal_lx", {"key 'direct_normal_lx'"});
}

TEST_F(Loader, PerezSkyGivesItsDiffuseIlluminance) {
    // The light's unobstructed horizontal illuminance is the Perez model's diffuse
    // illuminance for the hour, on the [site]'s day (2003-10-17 = day 290), scaled by dimming.
    const Scene s = load(kSite + kMat + kFloor + kPerez + "dimming = 0.5\n");
    const Light& l = s.lights.lights().at(0);
    PerezSkyInput in;
    in.sun_zenith_rad = deg(40.0);
    in.sun_azimuth_rad = deg(180.0);
    in.diffuse_horizontal_w_m2 = 120.0;
    in.direct_normal_w_m2 = 600.0;
    in.dew_point_c = 12.0;
    in.day_of_year = 290;
    const PerezSky perez(in);
    EXPECT_NEAR(l.unobstructed_horizontal_lx, 0.5 * perez.diffuse_horizontal_illuminance_lx(),
                1e-9 * l.unobstructed_horizontal_lx);
    const std::string& description = l.as<SkyLight>()->description;
    EXPECT_NE(description.find("Perez (epsilon"), std::string::npos) << description;
    EXPECT_TRUE(s.warnings.empty());
    // A sky too thin for the fitted range (Delta < 0.01) is modelled at its edge, with a warning.
    std::string thin = kPerez;
    thin.replace(thin.find("= 120"), 5, "= 5");
    const Scene t = load(kMat + kFloor + thin);
    ASSERT_EQ(t.warnings.size(), 1u);
    EXPECT_NE(t.warnings.front().find("outside the fitted range"), std::string::npos) << t.warnings.front();
    EXPECT_EQ(day_of_year(2003, 10, 17), 290);
    EXPECT_EQ(day_of_year(2024, 3, 1), 61);
    EXPECT_EQ(day_of_year(2023, 12, 31), 365);
}

TEST(LocalTime, ParsesWhatExistsOnly) {
    const auto t = parse_local_time("2024-02-29T23:59:30");
    ASSERT_TRUE(t);
    EXPECT_EQ(t->year, 2024);
    EXPECT_EQ(t->month, 2);
    EXPECT_EQ(t->day, 29);
    EXPECT_EQ(t->hour, 23);
    EXPECT_EQ(t->minute, 59);
    EXPECT_EQ(t->second, 30.0);
    EXPECT_TRUE(parse_local_time("2026-06-21 12:00"));
    EXPECT_TRUE(parse_local_time("2026-06-21T24:00"));
    for (const char* bad :
         {"2023-02-29T12:00", "2026-13-01T12:00", "2026-06-21T24:01", "2026-06-21T12:60", "2026-6-21T12:00",
          "2026-06-21T12", "2026-06-21T12:00Z", "2026-06-21T12:00:5", "2026-06-21T12:00:00.5", "", "noon"})
        EXPECT_FALSE(parse_local_time(bad)) << bad;
}

}  // namespace
}  // namespace luxtrace
