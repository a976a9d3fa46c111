// A result's light groups laid out again as the run's tallies (io/light_group_tallies.hpp),
// as `luxtrace info --scene` estimates them: the run's own estimate of a light scene on them
// gives, to the bit, what the run stored, at weights all 1 the plain run's detectors and
// map, at a [[light_scene]]'s weights that scene's. Random and sobol runs, cylinders, a
// luminance detector and daylight factors.
#include "luxtrace/io/light_group_tallies.hpp"

#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/scene/scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

// Equal to the bit, or both NaN (a cell or a detector no photon reached).
bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }
bool same(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!same(a[i], b[i])) return false;
    return true;
}

// The estimate at `weights` against what the run wrote under `group` ("" for the plain run,
// "/light_scenes/NAME" for a light scene).
void expect_stored(const ResultFile& file, const LightGroupTallies& t, const std::vector<double>& weights,
                   const std::string& group) {
    const ResultReader& r = file.raw();
    const ResultEstimates e =
        estimate_light_scene(t.scene(), LightScene{"test", weights}, t.layout, t.data, t.e0, t.photons).estimates;
    const std::string where = file.path().filename().string() + (group.empty() ? " (plain)" : " " + group);
    if (t.group_maps) {
        const std::string g = group + "/global";
        EXPECT_TRUE(same(e.global.mean_arithmetic_lx, r.attr_f64(g, "mean_arithmetic_lx"))) << where;
        EXPECT_TRUE(same(e.global.sigma_lx, r.attr_f64(g, "sigma_lx"))) << where;
        EXPECT_TRUE(same(e.global.moment_sigma_lx, r.attr_f64(g, "moment_sigma_lx"))) << where;
        if (r.has_attr(g, "replicate_sigma_lx")) {
            EXPECT_TRUE(same(e.global.replicate_sigma_lx, r.attr_f64(g, "replicate_sigma_lx"))) << where;
        }
        EXPECT_EQ(e.global.lit_sides, r.attr_u64(g, "lit_sides")) << where;
    }
    ASSERT_EQ(e.detectors.size(), t.detectors.size());
    for (std::size_t di = 0; di < t.detectors.size(); ++di) {
        const std::string d = group + "/detectors/" + t.detectors[di].name;
        EXPECT_TRUE(same(e.detectors[di].mean_value, r.attr_f64(d, "mean_value"))) << where << d;
        EXPECT_TRUE(same(e.detectors[di].mean_sigma_rel, r.attr_f64(d, "mean_sigma_rel"))) << where << d;
        EXPECT_TRUE(same(e.detectors[di].value, r.f64(d + "/value"))) << where << d;
        EXPECT_TRUE(same(e.detectors[di].sigma_rel, r.f64(d + "/sigma_rel"))) << where << d;
        EXPECT_EQ(e.daylight[di].has_value(), r.has(d + "/daylight_factor")) << where << d;
        if (!e.daylight[di] || !r.has(d + "/daylight_factor")) continue;
        EXPECT_TRUE(same(e.daylight[di]->reference_lx, r.attr_f64(d, "daylight_reference_lx"))) << where << d;
        EXPECT_TRUE(same(e.daylight[di]->df, r.f64(d + "/daylight_factor"))) << where << d;
    }
}

void expect_the_runs_estimates(const fs::path& result) {
    const ResultFile file(result);
    const LightGroupTallies t = read_light_group_tallies(file);
    ASSERT_GE(t.groups.size(), 2u) << result;
    expect_stored(file, t, std::vector<double>(t.groups.size(), 1.0), "");
    ASSERT_TRUE(file.raw().has("/light_scenes")) << result;
    for (const std::string& name : file.raw().children("/light_scenes")) {
        const std::string g = "/light_scenes/" + name;
        expect_stored(file, t, file.raw().f64_attr_array(g, "weights"), g);
    }
}

fs::path run(const test_support::ScratchDir& dir, const fs::path& scene, const std::string& photons) {
    const fs::path out = dir.path() / (scene.stem().string() + ".h5");
    const auto o = test_support::run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                              "\" --quiet --threads 2 --photons " + photons);
    EXPECT_EQ(o.code, 0) << o.out;
    return out;
}

const fs::path kData = LUXTRACE_TEST_DATA_DIR;

// Two point lights in groups a and b, a light scene "dim" (random photons).
TEST(LightGroupTallies, GiveTheRunsEstimatesOfTwoGroups) {
    test_support::ScratchDir dir("group_tallies_two");
    expect_the_runs_estimates(run(dir, kData / "run" / "two_groups.toml", "20k"));
}

// sobol with replicates, and cylinders (tests/data/reference).
TEST(LightGroupTallies, GiveTheRunsEstimatesOfASobolRun) {
    test_support::ScratchDir dir("group_tallies_sobol");
    expect_the_runs_estimates(run(dir, kData / "reference" / "more_keys.toml", "20k"));
}

// The daylight example: two skies as groups, daylight factors relative to each scene's
// E_h,ext.
TEST(LightGroupTallies, GiveTheRunsDaylightFactors) {
    test_support::ScratchDir dir("group_tallies_daylight");
    expect_the_runs_estimates(run(dir, fs::path(LUXTRACE_EXAMPLES_DIR) / "daylight" / "side_lit_office.toml", "20k"));
}

// A luminance detector's value per count comes from its stored axes and cone: the run's to
// the bit. Without group maps there is no map to estimate, only the detectors.
TEST(LightGroupTallies, GiveTheRunsLuminanceWithoutGroupMaps) {
    test_support::ScratchDir dir("group_tallies_luminance");
    const std::string scene = R"([[material]]
name = "wall"
reflectance = 0.5

[[shape]]
type = "box"
center = [2, 1.5, 1.25]
size = [4, 3, 2.5]
inward = true
material = "wall"

[[light]]
type = "point"
position = [1, 1.5, 2]
flux_lm = 800
group = "a"

[[light]]
type = "point"
position = [3, 1.5, 2]
flux_lm = 1200
group = "b"

[[light_scene]]
name = "dim"
dimming = { a = 0.1, b = 1.0 }

[[detector]]
name = "floor"
type = "luminance"
center = [2, 1.5, 0]
normal = [0, 0, 1]
up = [0, 1, 0]
size = [3, 2.5]
cells = [3, 3]
view_direction = [0.3, 0.2, 1]
half_angle_deg = 25

[run]
photons = 20000
group_maps = false
)";
    test_support::CommandOutcome o;
    const fs::path out = test_support::run_scene_text(dir, "luminance", scene, &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const ResultFile file(out);
    const LightGroupTallies t = read_light_group_tallies(file);
    EXPECT_FALSE(t.group_maps);
    EXPECT_EQ(t.layout.triangles(), 0u);
    ASSERT_EQ(t.detectors.size(), 1u);
    EXPECT_GT(file.raw().attr_u64("/detectors/floor", "photons_received"), 0u);
    expect_the_runs_estimates(out);
}

// A run with one light group keeps no groups: nothing to lay out.
TEST(LightGroupTallies, AreEmptyForOneGroup) {
    test_support::ScratchDir dir("group_tallies_one");
    test_support::CommandOutcome o;
    const fs::path out = test_support::run_scene_text(dir, "one",
                                                      std::string(test_support::kBlackSpeck) +
                                                          "\n[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\n" +
                                                          "flux_lm = 100\n\n[run]\nphotons = 1000\n",
                                                      &o);
    ASSERT_EQ(o.code, 0) << o.out;
    EXPECT_TRUE(read_light_group_tallies(ResultFile(out)).groups.empty());
}

}  // namespace
}  // namespace luxtrace
