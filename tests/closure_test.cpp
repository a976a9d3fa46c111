// Closed rooms are closed (docs/RELIABILITY.md): no photon leaves a closed room through
// the edges and corners where its faces meet, and the same room placed 10 km from the
// origin, with a 2 mm thin shelf in it, gives the same answer within its sigmas and
// loses no photon either. Runs the real binary; photon fates come from the result file.
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/material/ward_lobe.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using luxtrace::ResultReader;

namespace {

class Closure : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("luxtrace_closure_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    // Runs `scene` and checks that every photon ended absorbed inside.
    fs::path run_closed(const fs::path& scene, const std::string& name, const std::string& photons, int seed) {
        const fs::path out = dir / (name + ".h5");
        const auto o = luxtrace::test_support::run_luxtrace("run " + scene.string() +
                                                            " --quiet --threads 2 --photons " + photons + " --seed " +
                                                            std::to_string(seed) + " --output " + out.string());
        EXPECT_EQ(o.code, 0) << o.out;
        const ResultReader r(out);
        const std::uint64_t n = r.attr_u64("/", "photons");
        EXPECT_EQ(r.attr_u64("/global", "photons_escaped"), 0u) << name << ": photons left a closed room";
        EXPECT_EQ(r.attr_u64("/global", "photons_truncated"), 0u) << name;
        EXPECT_EQ(r.attr_u64("/global", "photons_absorbed"), n) << name;
        return out;
    }
    fs::path dir;
};

const fs::path kBench = fs::path(LUXTRACE_EXAMPLES_DIR).parent_path() / "bench" / "scenes";

// A grey room with a 2 mm shelf under the light, everything shifted by (dx, dy, 0).
std::string room_with_shelf(double dx, double dy) {
    char buf[2048];
    std::snprintf(buf, sizeof buf, R"(
[[material]]
name = "grey"
reflectance = 0.5
[[material]]
name = "white"
reflectance = 0.8
[[shape]]
type = "box"
center = [%.3f, %.3f, 1.5]
size = [4, 4, 3]
inward = true
subdivisions = 10
material = "grey"
[[shape]]
type = "box"
center = [%.3f, %.3f, 2.0]
size = [1.0, 0.8, 0.002]
subdivisions = 4
material = "white"
[[light]]
type = "point"
position = [%.3f, %.3f, 2.6]
flux_lm = 1000
[[detector]]
name = "desk"
center = [%.3f, %.3f, 0.75]
size = [3, 3]
cells = [12, 12]
)",
                  2 + dx, 2 + dy, 2.2 + dx, 2.1 + dy, 2.3 + dx, 1.9 + dy, 2 + dx, 2 + dy);
    return buf;
}

}  // namespace

TEST_F(Closure, BoxRoomLosesNoPhoton) {
    // 19,200 triangles: 1,200 edges between faces of the box where a photon could slip out.
    run_closed(kBench / "box_room.toml", "box", "3M", 1);
}

TEST_F(Closure, MillionTriangleRoomLosesNoPhoton) { run_closed(kBench / "million.toml", "million", "1M", 1); }

TEST_F(Closure, TheSameRoomTenKilometresAwayGivesTheSameAnswer) {
    const fs::path near = dir / "near.toml", far = dir / "far.toml";
    std::ofstream(near) << room_with_shelf(0, 0);
    std::ofstream(far) << room_with_shelf(10000, -10000);
    // Independent seeds: the comparison is statistical, judged by each file's own sigmas.
    const ResultReader a(run_closed(near, "near", "2M", 3)), b(run_closed(far, "far", "2M", 4));
    const auto va = a.f64("/detectors/desk/value"), vb = b.f64("/detectors/desk/value");
    const auto sa = a.f64("/detectors/desk/sigma_rel"), sb = b.f64("/detectors/desk/sigma_rel");
    ASSERT_EQ(va.size(), 144u);
    ASSERT_EQ(vb.size(), va.size());
    // The shelf's shadow is on the desk: skipping the 2 mm shelf far away would show.
    double chi2 = 0.0;
    for (std::size_t c = 0; c < va.size(); ++c) {
        const double s2 = std::pow(sa[c] * va[c], 2) + std::pow(sb[c] * vb[c], 2);
        ASSERT_GT(s2, 0.0) << "cell " << c;
        const double z = (va[c] - vb[c]) / std::sqrt(s2);
        EXPECT_LT(std::abs(z), 5.0) << "cell " << c << ": " << va[c] << " vs " << vb[c] << " lx";
        chi2 += z * z;
    }
    const double dof = static_cast<double>(va.size());
    EXPECT_LT(chi2, luxtrace::test_support::chi2_quantile(dof, luxtrace::test_support::kZ999)) << "chi2 " << chi2;
    // The geometry itself is stored where it was placed.
    const auto verts = b.f64("/mesh/vertices");
    double max_x = 0.0;
    for (std::size_t i = 0; i < verts.size(); i += 3) max_x = std::max(max_x, verts[i]);
    EXPECT_NEAR(max_x, 10004.0, 1e-9);
}

TEST_F(Closure, GlossyWallsLoseNoPhotonAndReflectWithinTheirAlbedo) {
    // Glossy walls (docs/MATERIALS.md#glossy-reflection) send photons out near grazing,
    // where the edges are: none may leave. Each arrival reflects with probability
    // rho_d + rho_s a(cos_i), so the share of arrivals that reflect, (A - N) / A in a closed
    // room where all N photons end absorbed, lies between that over the angles' extremes.
    const fs::path scene = dir / "glossy.toml";
    std::ofstream(scene) << R"(
[[material]]
name = "satin"
type = "general"
diffuse_reflectance = 0.3
specular_reflectance = 0.6
roughness = 0.3
[[shape]]
type = "box"
center = [2, 1.5, 1.5]
size = [4, 3, 3]
inward = true
subdivisions = 6
material = "satin"
[[light]]
type = "point"
position = [1.3, 1.1, 2.2]
flux_lm = 1000
)";
    const ResultReader r(run_closed(scene, "glossy", "400k", 5));
    const double n = static_cast<double>(r.attr_u64("/", "photons"));
    double arrivals = 0.0;
    for (const char* d : {"/global/count_odd", "/global/count_even"})
        for (std::uint64_t c : r.u64(d)) arrivals += static_cast<double>(c);
    const double reflected = (arrivals - n) / arrivals;
    const luxtrace::WardLobe lobe(0.3);
    double lo = 1.0, hi = 0.0;
    for (int k = 0; k <= 1000; ++k) {
        const double p = 0.3 + 0.6 * lobe.albedo(k / 1000.0);
        lo = std::min(lo, p);
        hi = std::max(hi, p);
    }
    EXPECT_GT(reflected, lo) << "reflected share of arrivals";
    EXPECT_LT(reflected, hi) << "reflected share of arrivals";
}
