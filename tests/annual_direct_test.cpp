// Annual daylight with the direct light by shadow rays ([annual] direct = "shadow_rays",
// issue 37) against the all-photon run of the same room, end to end: a side-lit room
// behind glazing, with an obstruction outside that shades the low sun and sky and a
// glossy floor that sends sunlight on by reflection. Both ways estimate the same light,
// so per work-plane cell the year's exposure (plain detector plus the shadow rays' direct
// exposure, against the plain detector) agrees within the two runs' errors, and so does
// each hour's direct sun. Different seeds: the runs' noise is independent. The same holds
// with the light after a diffuse reflection gathered ([annual] indirect = "gather"): the
// floor's 4 m triangles cut into patches, the glossy floor's specular part still counted
// by the cells.
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

const std::string kWeather = std::string(LUXTRACE_TEST_DATA_DIR) + "/weather/chicago.epw";

std::string room(const std::string& direct, int seed, const std::string& indirect = "photons",
                 const std::string& more = "") {
    auto rect = [](const std::string& center, const std::string& normal, const std::string& size,
                   const std::string& material) {
        return "[[shape]]\ntype = \"rectangle\"\ncenter = " + center + "\nnormal = " + normal + "\nsize = " + size +
               "\nmaterial = \"" + material + "\"\n";
    };
    return "[site]\nlatitude_deg = 41.98\nlongitude_deg = -87.92\nutc_offset_h = -6\nnorth = [0, 1, 0]\n"
           "[annual]\nweather = \"" +
           kWeather + "\"\ndirect = \"" + direct + "\"\nindirect = \"" + indirect + "\"\n" + more +
           "[[material]]\nname = \"wall\"\nreflectance = 0.5\n"
           "[[material]]\nname = \"glossy\"\ntype = \"general\"\ndiffuse_reflectance = 0.2\n"
           "specular_reflectance = 0.3\nroughness = 0.05\n"
           "[[material]]\nname = \"pane\"\ntype = \"glazing\"\ntransmittance = 0.8\nrefractive_index = 1.52\n" +
           rect("[2, 2, 0]", "[0, 0, 1]", "[4, 4]", "glossy") + rect("[2, 2, 3]", "[0, 0, -1]", "[4, 4]", "wall") +
           rect("[0, 2, 1.5]", "[1, 0, 0]", "[4, 3]", "wall") + rect("[4, 2, 1.5]", "[-1, 0, 0]", "[4, 3]", "wall") +
           rect("[2, 4, 1.5]", "[0, -1, 0]", "[4, 3]", "wall") + rect("[2, 0, 0.45]", "[0, 1, 0]", "[4, 0.9]", "wall") +
           rect("[2, 0, 2.7]", "[0, 1, 0]", "[4, 0.6]", "wall") +
           rect("[0.25, 0, 1.65]", "[0, 1, 0]", "[0.5, 1.5]", "wall") +
           rect("[3.75, 0, 1.65]", "[0, 1, 0]", "[0.5, 1.5]", "wall") +
           // The obstruction: a wall 6 m south, 4 m high, 8 m wide, both faces.
           rect("[2, -6, 2]", "[0, 1, 0]", "[8, 4]", "wall") + rect("[2, -6.01, 2]", "[0, -1, 0]", "[8, 4]", "wall") +
           "[[shape]]\nname = \"window\"\ntype = \"rectangle\"\ncenter = [2, 0, 1.65]\nnormal = [0, 1, 0]\n"
           "size = [3, 1.5]\nmaterial = \"pane\"\n"
           "[[detector]]\nname = \"desk\"\ncenter = [2, 2, 0.8]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\n"
           "size = [3.6, 3.6]\ncells = [6, 6]\n"
           "[run]\nseed = " +
           std::to_string(seed) + "\nphotons = 3000000\n";
}

// Per cell, the year's exposure and its standard error: the plain detector, plus the
// shadow rays' direct exposure and the gathered light where the run has them.
struct Year {
    std::vector<double> value, sigma;
};
Year year_of(const ResultReader& r) {
    Year y{r.f64("/detectors/desk/value"), r.f64("/detectors/desk/sigma_rel")};
    // A cell the plain detector saw nothing in has sigma_rel NaN: its plain part is 0.
    for (std::size_t c = 0; c < y.value.size(); ++c) y.sigma[c] = y.value[c] > 0.0 ? y.sigma[c] * y.value[c] : 0.0;
    const std::string g = "/annual/detectors/desk/";
    for (const std::string part : {"shadow_direct_sky", "shadow_direct_sun", "gathered_sky", "gathered_sun"}) {
        if (!r.has(g + part + "_lx_h")) continue;
        const std::vector<double> v = r.f64(g + part + "_lx_h"), s = r.f64(g + part + "_sigma_lx_h");
        for (std::size_t c = 0; c < y.value.size(); ++c) {
            y.value[c] += v[c];
            y.sigma[c] = std::hypot(y.sigma[c], s[c]);
        }
    }
    return y;
}

// Two runs' years agree per cell within their errors.
void expect_same_year(const Year& a, const Year& b, const std::string& what) {
    ASSERT_EQ(a.value.size(), b.value.size());
    double chi2 = 0.0, sum_z = 0.0, total_a = 0.0, total_b = 0.0, var_a = 0.0, var_b = 0.0;
    for (std::size_t c = 0; c < a.value.size(); ++c) {
        const double z = (b.value[c] - a.value[c]) / std::hypot(a.sigma[c], b.sigma[c]);
        chi2 += z * z;
        sum_z += z;
        total_a += a.value[c];
        total_b += b.value[c];
        var_a += std::pow(a.sigma[c] / a.value[c], 2);
        var_b += std::pow(b.sigma[c] / b.value[c], 2);
    }
    const double cells = static_cast<double>(a.value.size());
    std::cout << "[annual direct] " << what << ": year's exposure, " << a.value.size() << " cells: chi2/dof "
              << chi2 / cells << ", mean z " << sum_z / cells << ", totals " << total_b / total_a
              << "; mean relative error " << std::sqrt(var_a / cells) << " against " << std::sqrt(var_b / cells)
              << "\n";
    // chi2 of 36 cells: 99.9 % within [0.40, 2.0] times the dof.
    EXPECT_GT(chi2 / cells, 0.40) << what;
    EXPECT_LT(chi2 / cells, 2.0) << what;
    EXPECT_LT(std::abs(sum_z / std::sqrt(cells)), 3.5) << what;
}

// Two runs' hourly illuminances over the hours with a sun: the mean of z (their difference
// over its error) and of z^2; the errors are conservative here (two runs of one kind read
// about 0.55), so a bias shows as a mean square above another pair's.
struct HourlyZ {
    double mean = 0.0, mean_square = 0.0;
};
HourlyZ hourly_z(const ResultReader& a, const ResultReader& b, const std::string& what) {
    const std::string g = "/annual/detectors/desk/";
    const std::vector<double> ea = a.f64(g + "illuminance_lx"), sa = a.f64(g + "illuminance_sigma_lx");
    const std::vector<double> eb = b.f64(g + "illuminance_lx"), sb = b.f64(g + "illuminance_sigma_lx");
    const std::vector<double> sun = a.f64(g + "direct_sun_lx");
    EXPECT_EQ(ea.size(), eb.size());
    const std::size_t cells = 36;
    double n = 0.0, z1 = 0.0, z2 = 0.0;
    for (std::size_t h = 0; h * cells < ea.size(); ++h) {
        bool sunny = false;
        for (std::size_t c = 0; c < cells; ++c) sunny = sunny || sun[h * cells + c] > 0.0;
        if (!sunny) continue;
        for (std::size_t c = 0; c < cells; ++c) {
            const std::size_t i = h * cells + c;
            const double var = sa[i] * sa[i] + sb[i] * sb[i];
            if (!(var > 0.0)) continue;
            const double z = (eb[i] - ea[i]) / std::sqrt(var);
            z1 += z;
            z2 += z * z;
            n += 1.0;
        }
    }
    std::cout << "[annual direct] " << what << ": " << n << " sunny (hour, cell) pairs: mean z " << z1 / n
              << ", mean z^2 " << z2 / n << "\n";
    EXPECT_GT(n, 10000.0) << what;
    EXPECT_LT(z2 / n, 1.4) << what;
    EXPECT_LT(std::abs(z1 / n), 0.1) << what;
    return {z1 / n, z2 / n};
}

TEST(AnnualDirect, ShadowRaysAndPhotonsGiveTheSameYear) {
    test_support::ScratchDir dir("annual_direct");
    test_support::CommandOutcome o;
    const fs::path photons = test_support::run_scene_text(dir, "photons", room("photons", 11), &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const fs::path shadow = test_support::run_scene_text(dir, "shadow", room("shadow_rays", 12), &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const std::string own_suns = "sun_group_days = 1\n";
    const fs::path gather = test_support::run_scene_text(dir, "gather", room("shadow_rays", 13, "gather", own_suns),
                                                         &o);
    ASSERT_EQ(o.code, 0) << o.out;
    // Another gather: its noise and its rays' (the gather's rays follow the seed) are the
    // first one's size, which this tests.
    const fs::path gather2 = test_support::run_scene_text(dir, "gather2", room("shadow_rays", 14, "gather", own_suns),
                                                          &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const ResultReader p(photons), s(shadow), g(gather), g2(gather2);
    EXPECT_EQ(s.attr_str("/annual", "direct"), "shadow_rays");
    EXPECT_EQ(g.attr_str("/annual", "indirect"), "gather");
    const Year by_photons = year_of(p);
    expect_same_year(by_photons, year_of(s), "shadow rays against photons");
    expect_same_year(by_photons, year_of(g), "shadow rays and the gather against photons");
    expect_same_year(year_of(g), year_of(g2), "the gather against itself");
    const HourlyZ same = hourly_z(g, g2, "the gather against itself");
    // The suns of a week's clock hour in one light group (sun_group_days): the same year,
    // and every sunny hour's illuminance the same within the two runs' hourly errors.
    const fs::path week = test_support::run_scene_text(dir, "week",
                                                       room("shadow_rays", 15, "gather", "sun_group_days = 7\n"), &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const ResultReader w(week);
    expect_same_year(year_of(g), year_of(w), "the suns' groups by weeks against each its own");
    const HourlyZ weeks = hourly_z(g, w, "the suns' groups by weeks against each its own");
    EXPECT_LT(weeks.mean_square, 1.25 * same.mean_square);

    // Each hour's direct sun (LM-83's ASE) per cell: the photons' direct count against the
    // shadow rays'. Over the sunny hours, the z scores' mean and spread.
    const std::vector<double> sp_d = p.f64("/annual/detectors/desk/direct_sun_lx");
    const std::vector<double> sp_ds = p.f64("/annual/detectors/desk/direct_sun_sigma_lx");
    const std::vector<double> ss_d = s.f64("/annual/detectors/desk/direct_sun_lx");
    const std::vector<double> ss_ds = s.f64("/annual/detectors/desk/direct_sun_sigma_lx");
    double zsum = 0.0, z2 = 0.0, n = 0.0, direct_p = 0.0, direct_s = 0.0;
    for (std::size_t i = 0; i < sp_d.size(); ++i) {
        direct_p += sp_d[i];
        direct_s += ss_d[i];
        const double var = sp_ds[i] * sp_ds[i] + ss_ds[i] * ss_ds[i];
        if (!(var > 0.0)) continue;
        const double z = (ss_d[i] - sp_d[i]) / std::sqrt(var);
        zsum += z;
        z2 += z * z;
        n += 1.0;
    }
    std::cout << "[annual direct] direct sun of " << n << " (hour, cell) pairs: mean z " << zsum / n << ", mean z^2 "
              << z2 / n << "; the year's direct sun " << direct_s / direct_p << " (shadow / photons)\n";
    EXPECT_GT(n, 10000.0);
    EXPECT_LT(std::abs(direct_s / direct_p - 1.0), 0.02);
    EXPECT_LT(z2 / n, 1.5);
}

}  // namespace
}  // namespace luxtrace
