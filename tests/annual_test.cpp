// Annual daylight end to end (issue 24, docs/VALIDATION.md "Annual daylight"): the real
// luxtrace binary traces a year of skies from the Chicago TMY3 weather file as daylight
// coefficients, and every figure is judged by the run's own errors.
//  - An unobstructed upward sensor: every sky patch's coefficient is its projected solid
//    angle times what it emitted, the ground's is zero, and every hour's direct sun is the
//    weather file's direct normal illuminance (as the Perez model rebuilds it) times the
//    sine of the sun's altitude: chi-square over thousands of independent groups, and each
//    hour's total within a few sigma of the global horizontal illuminance.
//  - Coefficients times one hour's sky equal a run of that hour's sky light alone, for a
//    Perez and a CIE overcast sky, on a vertical sensor that sees sky and ground.
#include "luxtrace/core/math.hpp"
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

const std::string kWeather = std::string(LUXTRACE_TEST_DATA_DIR) + "/weather/chicago.epw";

fs::path run_scene(const test_support::ScratchDir& dir, const std::string& name, const std::string& text) {
    test_support::CommandOutcome o;
    const fs::path out = test_support::run_scene_text(dir, name, text, &o);
    EXPECT_EQ(o.code, 0) << o.out;
    return out;
}

// A 4 m x 4 m sensor of one cell at the origin facing `normal`, a small black square below
// it (the scene needs a surface), and the [annual] table.
std::string open_scene(const std::string& annual, const std::string& normal, const std::string& up,
                       std::uint64_t photons) {
    return "[annual]\n" + annual +
           "\n[[material]]\nname = \"black\"\nreflectance = 0\n"
           "[[shape]]\ntype = \"rectangle\"\ncenter = [0, 0, -0.5]\nnormal = [0, 0, 1]\nsize = [0.1, 0.1]\n"
           "material = \"black\"\n"
           "[[detector]]\nname = \"sensor\"\ncenter = [0, 0, 0]\nnormal = " +
           normal + "\nup = " + up +
           "\nsize = [4, 4]\ncells = [1, 1]\n[run]\nseed = 7\nphotons = " + std::to_string(photons) + "\n";
}

TEST(Annual, UnobstructedSensorSeesEachHourOfTheWeatherFile) {
    test_support::ScratchDir dir("annual_open");
    const fs::path out = run_scene(dir, "open",
                                   open_scene("weather = \"" + kWeather + "\"\nground_reflectance = 0.2\n", "[0, 0, 1]",
                                              "[0, 1, 0]", 20'000'000));
    const ResultReader r(out);
    const double e0 = r.attr_f64("/", "flux_per_photon_lm");
    const double area = 16.0;
    const std::string c = "/annual/detectors/sensor/coefficients";
    const std::vector<std::uint64_t> n = r.u64(c + "/count"), q = r.u64(c + "/sumsq");
    const std::uint64_t photons = r.attr_u64("/", "photons");
    const std::size_t ground = r.attr_u64(c, "ground_group"), first_sun = r.attr_u64(c, "first_sun_group");
    const std::vector<double> yearly = r.f64("/annual/yearly_luminance_cd_m2_h");
    const std::vector<double> projected = r.f64("/annual/patch_projected_solid_angle_sr");
    ASSERT_EQ(projected.size() + 1, yearly.size());
    ASSERT_EQ(ground, projected.size());
    // Each patch's coefficient: its yearly luminance times its projected solid angle.
    auto z_of = [&](std::size_t g, double expected) {
        const double nn = static_cast<double>(n[g]), qq = static_cast<double>(q[g]);
        const double k = e0 / area;
        const double sigma = k * std::sqrt(std::max(qq - nn * nn / static_cast<double>(photons), 1.0));
        return (k * nn - expected) / sigma;
    };
    double chi2 = 0.0;
    for (std::size_t p = 0; p < projected.size(); ++p) {
        const double z = z_of(p, yearly[p] * projected[p]);
        EXPECT_LT(std::abs(z), 5.0) << "patch " << p;
        chi2 += z * z;
    }
    const double dof = static_cast<double>(projected.size());
    std::cout << "[annual] sky patch coefficients: chi2/dof " << chi2 / dof << " over " << dof << " patches\n";
    EXPECT_NEAR(chi2 / dof, 1.0, 4.0 * std::sqrt(2.0 / dof)) << "chi2 " << chi2 << " over " << dof << " patches";
    EXPECT_EQ(n[ground], 0u) << "an upward sensor sees no ground";

    // Every hour's direct sun (its own group, independent of the others).
    const std::vector<double> alt = r.f64("/annual/sun_altitude_deg"), dn = r.f64("/annual/direct_normal_lx");
    const std::vector<double> global = r.f64("/annual/global_horizontal_lx");
    const std::vector<double> direct = r.f64("/annual/detectors/sensor/direct_sun_lx");
    const std::vector<double> direct_sigma = r.f64("/annual/detectors/sensor/direct_sun_sigma_lx");
    const std::vector<double> total = r.f64("/annual/detectors/sensor/illuminance_lx");
    const std::vector<double> total_sigma = r.f64("/annual/detectors/sensor/illuminance_sigma_lx");
    const std::vector<std::uint64_t> sun_group = r.u64("/annual/sun_group");
    ASSERT_EQ(alt.size(), 8760u);
    double sum_z = 0.0, sum_z2 = 0.0, suns = 0.0, far = 0.0, daylit = 0.0, sum_d = 0.0, sum_var = 0.0;
    for (std::size_t h = 0; h < alt.size(); ++h) {
        if (global[h] > 0.0) {
            daylit += 1.0;
            if (std::abs(total[h] - global[h]) > 4.0 * total_sigma[h]) far += 1.0;
        }
        // A z is normal where the counts are not few: the sun above 5 degrees gives this
        // sensor about 60 registrations an hour and more (lower suns read 0 to a few).
        if (sun_group[h] == ~std::uint64_t{0} || alt[h] < 5.0) continue;
        EXPECT_GE(sun_group[h], first_sun);
        const double d = direct[h] - dn[h] * std::sin(alt[h] * kPi / 180.0), z = d / direct_sigma[h];
        sum_d += d;
        sum_var += direct_sigma[h] * direct_sigma[h];
        sum_z += z;
        sum_z2 += z * z;
        suns += 1.0;
    }
    ASSERT_GT(suns, 3500.0);
    // The hours pooled: sum of differences over the root of the summed variances (each
    // hour's z is biased by about -1 / (2 sqrt(count)), as its sigma comes from its count).
    const double pooled = sum_d / std::sqrt(sum_var);
    const double mean = sum_z / suns, var = sum_z2 / suns - mean * mean;
    std::cout << "[annual] direct sun of " << suns << " hours: pooled z " << pooled << ", z variance " << var << "; "
              << far << " of " << daylit << " daylit hours' totals beyond 4 sigma\n";
    EXPECT_LT(std::abs(pooled), 4.0) << "direct sun pooled over " << suns << " hours";
    EXPECT_NEAR(var, 1.0, 0.1) << "direct sun z variance over " << suns << " hours";
    // Hours share the sky's coefficients, so their z are correlated, but each is N(0, 1).
    EXPECT_LT(far / daylit, 0.005) << far << " of " << daylit << " daylit hours beyond 4 sigma";
}

// The hour of the weather file with the most diffuse light and no direct sun.
std::size_t overcast_hour(const ResultReader& r) {
    const std::vector<double> diffuse = r.f64("/annual/diffuse_horizontal_lx"), dn = r.f64("/annual/direct_normal_lx");
    std::size_t best = 0;
    for (std::size_t h = 0; h < diffuse.size(); ++h)
        if (dn[h] == 0.0 && diffuse[h] > diffuse[best]) best = h;
    return best;
}

struct Reading {
    double value = 0.0, sigma = 0.0;
};

Reading grid_mean(const ResultReader& r) {
    const double v = r.attr_f64("/detectors/sensor", "mean_value");
    return {v, v * r.attr_f64("/detectors/sensor", "mean_sigma_rel")};
}

void expect_hour_matches_sky_run(const std::string& annual_sky, const std::string& sky_light_keys, int mf) {
    test_support::ScratchDir dir("annual_hour");
    // A south-facing vertical sensor: sky and ground, the sun's side of the sky.
    const std::string normal = "[0, -1, 0]", up = "[0, 0, 1]";
    const fs::path annual = run_scene(dir, "annual",
                                      open_scene("weather = \"" + kWeather + "\"\nground_reflectance = 0.2\nsky_mf = " +
                                                     std::to_string(mf) + "\n" + annual_sky,
                                                 normal, up, 12'000'000));
    const ResultReader a(annual);
    const std::size_t h = overcast_hour(a);
    const std::vector<double> e = a.f64("/annual/detectors/sensor/illuminance_lx");
    const std::vector<double> s = a.f64("/annual/detectors/sensor/illuminance_sigma_lx");
    const std::vector<double> month = a.f64("/annual/month"), day = a.f64("/annual/day"), mid = a.f64("/annual/hour");
    const std::vector<double> diffuse = a.f64("/annual/diffuse_horizontal_lx");
    const std::vector<double> diffuse_w = a.f64("/annual/weather_diffuse_horizontal_w_m2");
    const std::vector<double> direct_w = a.f64("/annual/weather_direct_normal_w_m2");
    const std::vector<double> dew = a.f64("/annual/weather_dew_point_c");
    char when[64];
    const int minutes = static_cast<int>(std::lround(mid[h] * 60.0));
    std::snprintf(when, sizeof when, "2017-%02d-%02dT%02d:%02d", static_cast<int>(month[h]), static_cast<int>(day[h]),
                  minutes / 60, minutes % 60);
    std::string keys = sky_light_keys;
    const std::string perez = "sky = \"perez\"\ndiffuse_horizontal_w_m2 = " + std::to_string(diffuse_w[h]) +
                              "\ndirect_normal_w_m2 = " + std::to_string(direct_w[h]) +
                              "\ndew_point_c = " + std::to_string(dew[h]);
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"@DIFFUSE_LX", std::to_string(diffuse[h])},
                                   std::pair<std::string, std::string>{"@PEREZ", perez}})
        if (const auto at = keys.find(from); at != std::string::npos) keys.replace(at, from.size(), to);
    const std::string sky_scene =
        "[site]\nlatitude_deg = " + std::to_string(a.attr_f64("/annual", "latitude_deg")) +
        "\nlongitude_deg = " + std::to_string(a.attr_f64("/annual", "longitude_deg")) +
        "\nutc_offset_h = " + std::to_string(a.attr_f64("/annual", "utc_offset_h")) + "\ntime = \"" + when +
        "\"\n[[light]]\ntype = \"sky\"\nground_reflectance = 0.2\n" + keys +
        "\n[[material]]\nname = \"black\"\nreflectance = 0\n"
        "[[shape]]\ntype = \"rectangle\"\ncenter = [0, 0, -0.5]\nnormal = [0, 0, 1]\nsize = [0.1, 0.1]\n"
        "material = \"black\"\n[[detector]]\nname = \"sensor\"\ncenter = [0, 0, 0]\nnormal = " +
        normal + "\nup = " + up + "\nsize = [4, 4]\ncells = [1, 1]\n[run]\nseed = 3\nphotons = 2000000\n";
    const ResultReader d(run_scene(dir, "hour", sky_scene));
    const Reading direct = grid_mean(d);
    const double z = (e[h] - direct.value) / std::hypot(s[h], direct.sigma);
    std::cout << "[annual] MF " << mf << ", hour " << h + 1 << ": coefficients " << e[h] << " +- " << s[h]
              << " lx, sky run " << direct.value << " +- " << direct.sigma << " lx, z " << z << "\n";
    EXPECT_LT(std::abs(z), 4.0) << "hour " << h + 1 << " (" << when << "): coefficients " << e[h] << " +- " << s[h]
                                << " lx, sky run " << direct.value << " +- " << direct.sigma << " lx";
}

TEST(Annual, CoefficientsTimesAnHourEqualThatHoursPerezSky) {
    // The hour's Perez sky from its irradiances, as the annual run builds it.
    expect_hour_matches_sky_run("", "@PEREZ", 4);
}

TEST(Annual, CoefficientsTimesAnHourEqualThatHoursCieSky) {
    expect_hour_matches_sky_run("sky = \"cie\"\ncie_type = 16\n",
                                "sky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = @DIFFUSE_LX", 4);
}

}  // namespace
}  // namespace luxtrace

namespace luxtrace {
namespace {

// A 4 m cube room with a 2 m x 1 m open south window (a portal) and a work-plane grid.
std::string window_room(const std::string& extra, std::uint64_t photons) {
    auto wall = [](const std::string& center, const std::string& normal, const std::string& size) {
        return "[[shape]]\ntype = \"rectangle\"\ncenter = " + center + "\nnormal = " + normal + "\nsize = " + size +
               "\nmaterial = \"wall\"\n";
    };
    return "[annual]\nweather = \"" + kWeather + "\"\n" + extra +
           "\n[[material]]\nname = \"wall\"\nreflectance = 0.5\n"
           "[[material]]\nname = \"open\"\ntype = \"glass\"\nior = 1\n" +
           wall("[2, 2, 0]", "[0, 0, 1]", "[4, 4]") + wall("[2, 2, 4]", "[0, 0, -1]", "[4, 4]") +
           wall("[0, 2, 2]", "[1, 0, 0]", "[4, 4]") + wall("[4, 2, 2]", "[-1, 0, 0]", "[4, 4]") +
           wall("[2, 4, 2]", "[0, -1, 0]", "[4, 4]") + wall("[2, 0, 0.75]", "[0, 1, 0]", "[4, 1.5]") +
           wall("[2, 0, 3.25]", "[0, 1, 0]", "[4, 1.5]") + wall("[0.5, 0, 2]", "[0, 1, 0]", "[1, 1]") +
           wall("[3.5, 0, 2]", "[0, 1, 0]", "[1, 1]") +
           "[[shape]]\nname = \"window\"\ntype = \"rectangle\"\ncenter = [2, 0, 2]\nnormal = [0, 1, 0]\nsize = [2, 1]\n"
           "material = \"open\"\n[[portal]]\nshape = \"window\"\n"
           "[[detector]]\nname = \"desk\"\ncenter = [2, 2, 0.8]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\nsize = [3.6, "
           "3.6]\n"
           "cells = [6, 6]\n[run]\nseed = 11\nphotons = " +
           std::to_string(photons) + "\n";
}

TEST(Annual, RunStopsWhenAnAnnualMetricsErrorIsReached) {
    test_support::ScratchDir dir("annual_target");
    const fs::path scene = dir.path() / "room.toml", out = dir.path() / "room.h5";
    std::ofstream(scene) << window_room("", 100'000'000'000ull)
                         << "report_every_photons = 2000000\n"
                            "[[run.target]]\non = \"annual:desk:mean_da\"\nabsolute_error = 0.01\n";
    const auto o = test_support::run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                              "\" --quiet --threads 2");
    ASSERT_EQ(o.code, 0) << o.out;
    const ResultReader r(out);
    EXPECT_EQ(r.attr_str("/", "stop_reason").rfind("target annual:desk:mean_da", 0), 0u)
        << r.attr_str("/", "stop_reason");
    // The final result's own (32-replicate) figure is within about the goal.
    const std::string g = "/annual/detectors/desk";
    const double sigma = r.attr_f64(g, "mean_da_sigma"), bias = r.attr_f64(g, "mean_da_bias");
    EXPECT_LT(std::hypot(sigma, bias), 0.015) << "sigma " << sigma << " bias " << bias;
    EXPECT_GT(r.attr_f64(g, "mean_da"), 0.0);
    // The Ladybug results folder beside the result.
    EXPECT_TRUE(fs::is_regular_file(dir.path() / "room_ladybug" / "grids_info.json"));
    EXPECT_TRUE(
        fs::is_regular_file(dir.path() / "room_ladybug" / "__static_apertures__" / "default" / "total" / "desk.npy"));
}

}  // namespace
}  // namespace luxtrace
