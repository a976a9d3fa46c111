// Annual daylight with the direct light by shadow rays ([annual] direct = "shadow_rays",
// issue 37) against the all-photon run of the same room, end to end: a side-lit room
// behind glazing, with an obstruction outside that shades the low sun and sky and a
// glossy floor that sends sunlight on by reflection. Both ways estimate the same light,
// so per work-plane cell the year's exposure (plain detector plus the shadow rays' direct
// exposure, against the plain detector) agrees within the two runs' errors, and so does
// each hour's direct sun. Different seeds: the runs' noise is independent.
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

const std::string kWeather = std::string(LUXTRACE_TEST_DATA_DIR) + "/weather/chicago.epw";

std::string room(const std::string& direct, int seed) {
    auto rect = [](const std::string& center, const std::string& normal, const std::string& size,
                   const std::string& material) {
        return "[[shape]]\ntype = \"rectangle\"\ncenter = " + center + "\nnormal = " + normal + "\nsize = " + size +
               "\nmaterial = \"" + material + "\"\n";
    };
    return "[site]\nlatitude_deg = 41.98\nlongitude_deg = -87.92\nutc_offset_h = -6\nnorth = [0, 1, 0]\n"
           "[annual]\nweather = \"" +
           kWeather + "\"\ndirect = \"" + direct +
           "\"\n"
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

TEST(AnnualDirect, ShadowRaysAndPhotonsGiveTheSameYear) {
    test_support::ScratchDir dir("annual_direct");
    test_support::CommandOutcome o;
    const fs::path photons = test_support::run_scene_text(dir, "photons", room("photons", 11), &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const fs::path shadow = test_support::run_scene_text(dir, "shadow", room("shadow_rays", 12), &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const ResultReader p(photons), s(shadow);
    EXPECT_EQ(s.attr_str("/annual", "direct"), "shadow_rays");

    // The year's exposure per cell.
    const std::vector<double> vp = p.f64("/detectors/desk/value"), rp = p.f64("/detectors/desk/sigma_rel");
    const std::vector<double> vs = s.f64("/detectors/desk/value"), rs = s.f64("/detectors/desk/sigma_rel");
    const std::string g = "/annual/detectors/desk/";
    const std::vector<double> d_sky = s.f64(g + "shadow_direct_sky_lx_h"), d_sun = s.f64(g + "shadow_direct_sun_lx_h");
    const std::vector<double> s_sky = s.f64(g + "shadow_direct_sky_sigma_lx_h"),
                              s_sun = s.f64(g + "shadow_direct_sun_sigma_lx_h");
    std::vector<double> d(d_sky.size()), ds(d_sky.size());
    for (std::size_t c = 0; c < d.size(); ++c) {
        d[c] = d_sky[c] + d_sun[c];
        ds[c] = std::hypot(s_sky[c], s_sun[c]);
    }
    ASSERT_EQ(d.size(), vp.size());
    double chi2 = 0.0, sum_z = 0.0, total_p = 0.0, total_s = 0.0, var_p = 0.0, var_s = 0.0;
    for (std::size_t c = 0; c < vp.size(); ++c) {
        const double es = vs[c] + d[c];
        const double sp = rp[c] * vp[c], ss2 = rs[c] * vs[c] * rs[c] * vs[c] + ds[c] * ds[c];
        const double z = (es - vp[c]) / std::sqrt(sp * sp + ss2);
        chi2 += z * z;
        sum_z += z;
        total_p += vp[c];
        total_s += es;
        var_p += sp * sp / vp[c] / vp[c];
        var_s += ss2 / es / es;
    }
    const double cells = static_cast<double>(vp.size());
    std::cout << "[annual direct] year's exposure, " << vp.size() << " cells: chi2/dof " << chi2 / cells << ", mean z "
              << sum_z / cells << ", totals " << total_s / total_p << " (shadow / photons); mean "
              << "relative error photons " << std::sqrt(var_p / cells) << ", shadow rays " << std::sqrt(var_s / cells)
              << "\n";
    // chi2 of 36 cells: 99.9 % within [0.40, 2.0] times the dof.
    EXPECT_GT(chi2 / cells, 0.40);
    EXPECT_LT(chi2 / cells, 2.0);
    EXPECT_LT(std::abs(sum_z / std::sqrt(cells)), 3.5);

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
