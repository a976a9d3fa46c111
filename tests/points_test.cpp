// Points detectors (Radiance .pts sensor grids, issue 24 §4): the .pts reader on real
// Honeybee files and on bad lines; the plane-and-bin lookup against testing every sensor;
// the default radius; the loader's keys and refusals; and end to end, sensors under a
// uniform sky and under a point light read the analytic illuminance within their errors,
// agree with an illuminance grid whose cells share their centres, and the result file
// holds their positions and directions.
#include "luxtrace/detector/pts_file.hpp"
#include "luxtrace/detector/sensor_points.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "point_source.hpp"
#include "scene_test_support.hpp"
#include "z_pool.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The reader.

TEST(PtsReader, ReadsAHoneybeeGrid) {
    const SensorPointList s = read_pts(data("pts/class_room.pts").string());
    ASSERT_EQ(s.positions.size(), 72u);  // 6 x 12 sensors, 1 m apart
    expect_vec(s.positions.front(), Vec3(-2.5, 0.5, 0.800000011921));
    expect_vec(s.positions.back(), Vec3(2.5, 11.5, 0.800000011921));
    for (const Vec3& d : s.directions) expect_vec(d, Vec3(0, 0, 1));
    EXPECT_EQ(s.lines.front(), 1);
    EXPECT_EQ(s.lines.back(), 72);
}

TEST(PtsReader, SkipsCommentsAndBlanksAndNormalisesDirections) {
    // Honeybee's own test file: two '#' lines, runs of blanks, a leading '.', indentation.
    const SensorPointList s = read_pts(data("pts/test_points.pts").string());
    ASSERT_EQ(s.positions.size(), 3u);
    EXPECT_EQ(s.lines, (std::vector<int>{3, 4, 5}));
    expect_vec(s.positions[1], Vec3(0.2, 0.3, 0.4));
    expect_vec(s.directions[1], glm::normalize(Vec3(0.5, 0.6, 0.7)), 1e-15);
    expect_vec(s.directions[2], glm::normalize(Vec3(-50, -60, -70)), 1e-15);
    const SensorPointList t = parse_pts("\n  # indented comment\r\n\t1 2 3 0 0 2\r\n\n+1 -2e0 3 0 -1 0 \n", "t.pts");
    ASSERT_EQ(t.positions.size(), 2u);
    EXPECT_EQ(t.lines, (std::vector<int>{3, 5}));
    expect_vec(t.directions[0], Vec3(0, 0, 1));
    expect_vec(t.positions[1], Vec3(1, -2, 3));
}

TEST(PtsReader, BadInputNamesFileAndLine) {
    struct Case {
        std::string text, where, what;
    };
    const std::vector<Case> cases{
        {"0 0 0 0 0 1\n1 2 3 0 0\n", "g.pts:2:", "expected 6 numbers"},
        {"0 0 0 0 0 1 7\n", "g.pts:1:", "found 7"},
        {"# c\n1 2 x 0 0 1\n", "g.pts:2:", "field 3 (z) 'x' is not a number"},
        {"1 2 3 0 0 0\n", "g.pts:1:", "direction (dx dy dz) is zero"},
        {"1 2 3 nan 0 1\n", "g.pts:1:", "field 4 (dx) 'nan' is not finite"},
        {"1 inf 3 0 0 1\n", "g.pts:1:", "field 2 (y) 'inf' is not finite"},
        {"1e999 2 3 0 0 1\n", "g.pts:1:", "field 1 (x) '1e999' is not a number"},
        {"1 2 3 1e300 1e300 1e300\n", "g.pts:1:", "too large"},
        {"0 0 2e9 0 0 1\n", "g.pts:1:", "outside the +-1e9 m"},
        {"1,2,3,0,0,1\n", "g.pts:1:", "found 1"},
        {"", "g.pts:1:", "no sensor"},
        {"# only a comment\n\n", "g.pts:2:", "no sensor"},
    };
    for (const Case& c : cases) {
        try {
            (void)parse_pts(c.text, "g.pts");
            ADD_FAILURE() << "no InputError for: " << c.text;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(c.where, 0), 0u) << msg;
            EXPECT_NE(msg.find(c.what), std::string::npos) << "'" << c.what << "' not in: " << msg;
        }
    }
    EXPECT_THROW((void)read_pts("/nonexistent/luxtrace/grid.pts"), InputError);
}

// ---------------------------------------------------------------------------------
// The lookup.

// Every sensor tested on its own: the disc of radius r in its own plane, crossed from the front.
std::vector<int> brute_force(const SensorPoints& s, const Vec3& o, const Vec3& d, double t_max) {
    std::vector<int> out;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const Vec3 &p = s.positions()[k], &n = s.directions()[k];
        const double denom = glm::dot(d, n);
        if (denom >= 0.0) continue;
        const double t = glm::dot(p - o, n) / denom;
        if (!(t > 0.0 && t <= t_max)) continue;
        const Vec3 x = o + t * d;
        if (glm::dot(x - p, x - p) <= s.radius_m() * s.radius_m()) out.push_back(static_cast<int>(k));
    }
    return out;
}

TEST(SensorPoints, PlaneLookupFindsExactlyTheDiscsTestingEverySensorFinds) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec3> pos, dir;
    // A 40 x 40 grid 0.25 m apart on a work plane, a tilted 10 x 10 grid, and 200 sensors
    // each in a plane of its own; discs of 0.3 m overlap their neighbours.
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
            pos.emplace_back(-5.0 + 0.25 * i, -5.0 + 0.25 * j, 0.8);
            dir.emplace_back(0, 0, 1);
        }
    const Vec3 tilt = glm::normalize(Vec3(1, 0, 1)), a = Vec3(0, 1, 0), b = glm::cross(tilt, a);
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) {
            pos.push_back(Vec3(0, 0, 2) + 0.4 * i * a + 0.4 * j * b);
            dir.push_back(tilt);
        }
    for (int k = 0; k < 200; ++k) {
        pos.emplace_back(3 * u(rng), 3 * u(rng), 1 + u(rng));
        dir.push_back(glm::normalize(Vec3(u(rng), u(rng), u(rng))));
    }
    const SensorPoints s(pos, dir, 0.3);
    EXPECT_EQ(s.planes(), 202u);  // through the hierarchy over the planes
    std::size_t found = 0;
    std::vector<int> got;
    for (int ray = 0; ray < 20000; ++ray) {
        const Vec3 o(6 * u(rng), 6 * u(rng), 1.5 + 2 * u(rng));
        const Vec3 d = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
        const double t_max = ray % 2 ? 1e30 : 3.0 * (1.0 + u(rng));
        got.clear();
        s.crossings(o, d, t_max, Vec3(0.0), 0.0, got);
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, brute_force(s, o, d, t_max)) << "ray " << ray;
        found += got.size();
    }
    EXPECT_GT(found, 5000u);  // the rays do cross discs
}

TEST(SensorPoints, DefaultRadiusIsHalfTheSmallestSpacingWithinAPlane) {
    const SensorPointList grid = read_pts(data("pts/class_room.pts").string());
    EXPECT_NEAR(SensorPoints::half_smallest_spacing_m(grid.positions, grid.directions), 0.5, 1e-12);
    const SensorPoints s(grid.positions, grid.directions, 0.5);
    EXPECT_EQ(s.planes(), 1u);
    // Sensors 0.1 m apart but facing different ways, or 0.2 m apart along their normal,
    // share no plane: only the 0.6 m pair counts.
    const std::vector<Vec3> pos{{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0.2}, {0.6, 0, 0}};
    const std::vector<Vec3> dir{{0, 0, 1}, {1, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    EXPECT_NEAR(SensorPoints::half_smallest_spacing_m(pos, dir), 0.3, 1e-12);
    // One sensor: no spacing. Two at one point of a plane: zero, naming them.
    EXPECT_EQ(SensorPoints::half_smallest_spacing_m({{0, 0, 0}}, {{0, 0, 1}}), 0.0);
    int first = -1, second = -1;
    EXPECT_EQ(SensorPoints::half_smallest_spacing_m({{0, 0, 0}, {5, 0, 0}, {5, 0, 0}},
                                                    {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, &first, &second),
              0.0);
    EXPECT_EQ(first, 1);
    EXPECT_EQ(second, 2);
}

// ---------------------------------------------------------------------------------
// The loader.

TEST_F(Loader, PointsDetectorTakesItsCellsFromThePtsFile) {
    std::ifstream in(data("pts/class_room.pts"));
    std::ostringstream text;
    text << in.rdbuf();
    write("grid.pts", text.str());
    const Scene s = load(kMat + kFloor + kLamp +
                         "[[detector]]\nname = \"g\"\ntype = \"points\"\npoints = \"grid.pts\"\n");
    ASSERT_EQ(s.detectors.size(), 1u);
    const Detector& d = s.detectors[0];
    EXPECT_EQ(d.type, DetectorType::points);
    EXPECT_EQ(d.nx, 72);
    EXPECT_EQ(d.ny, 1);
    EXPECT_EQ(d.radius_m, 0.5);  // half the 1 m spacing
    EXPECT_NEAR(d.value_per_lm(), 1.0 / (kPi * 0.25), 1e-12);
    EXPECT_EQ(d.sensors.size(), 72u);
    const Scene r = load(kMat + kFloor + kLamp +
                         "[[detector]]\nname = \"g\"\ntype = \"points\"\npoints = \"grid.pts\"\nradius_m = 0.2\n");
    EXPECT_EQ(r.detectors[0].radius_m, 0.2);
    write("one.pts", "0 0 1 0 0 1\n");
    const Scene o = load(kMat + kFloor + kLamp +
                         "[[detector]]\nname = \"g\"\ntype = \"points\"\npoints = \"one.pts\"\n");
    EXPECT_EQ(o.detectors[0].radius_m, 0.1);  // no two sensors share a plane
}

TEST_F(Loader, BadPointsDetectorsAreRefused) {
    const std::string head = kMat + kFloor + kLamp + "[[detector]]\nname = \"g\"\ntype = \"points\"\n";
    write("bad.pts", "0 0 1 0 0 1\n0 0 1 0 0\n");
    expect_bad(head + "points = \"bad.pts\"\n", "points =", {"bad.pts:2:", "expected 6 numbers"});
    expect_bad(head + "points = \"missing.pts\"\n", "points =", {"missing.pts", "cannot open"});
    write("empty.pts", "");
    expect_bad(head + "points = \"empty.pts\"\n", "points =", {"empty.pts:1:", "no sensor"});
    write("twice.pts", "0 0 1 0 0 1\n1 0 1 0 0 1\n# the same again\n1 0 1 0 0 1\n");
    expect_bad(head + "points = \"twice.pts\"\n", "points =", {"lines 2 and 4", "give 'radius_m'"});
    EXPECT_NO_THROW((void)load(head + "points = \"twice.pts\"\nradius_m = 0.3\n"));
    write("ok.pts", "0 0 1 0 0 1\n");
    expect_bad(head + "points = \"ok.pts\"\nradius_m = -1\n", "radius_m", {"must be positive"});
    expect_bad(head + "points = \"ok.pts\"\ncenter = [0, 0, 0]\n", "center", {"'center' does not apply"});
    expect_bad(head, "", {"needs 'points'"});
}

// ---------------------------------------------------------------------------------
// End to end: the luxtrace binary.

struct Reading {
    double value = 0.0, sigma = 0.0;
};

// Cell c of a one-band detector: its value and absolute error.
std::vector<Reading> cells_of(const ResultReader& r, const std::string& name) {
    const std::vector<double> v = r.f64("/detectors/" + name + "/value"),
                              s = r.f64("/detectors/" + name + "/sigma_rel");
    std::vector<Reading> out;
    for (std::size_t c = 0; c < v.size(); ++c) out.push_back({v[c], v[c] * s[c]});
    return out;
}

fs::path run_scene(const ScratchDir& dir, const std::string& text, std::uint64_t photons) {
    const fs::path scene = dir.path() / "s.toml", out = dir.path() / "s.h5";
    std::ofstream(scene) << text;
    const auto o = run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() + "\" --photons " +
                                std::to_string(photons) + " --quiet --threads 2");
    EXPECT_EQ(o.code, 0) << o.out;
    return out;
}

// Under a uniform sky every upward sensor reads the unobstructed horizontal illuminance
// and a vertical one what the sky's quadrature gives (half of it for a uniform sky); the
// vertical sensors share no plane, so this also runs the one-plane-per-sensor path.
TEST(PointsRun, SensorsUnderAUniformSkyReadItsIlluminance) {
    ScratchDir dir("points_sky");
    std::ofstream pts(dir.path() / "grid.pts");
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) pts << i - 2 << ' ' << j - 2 << " 0.8 0 0 1\n";
    pts << "# facing the four points of the compass\n4 0 1 1 0 0\n-4 0 1 -1 0 0\n0 4 1 0 1 0\n0 -4 1 0 -1 0\n";
    pts.close();
    const std::string text = std::string(kBlackSpeck) +
                             "\n[[light]]\ntype = \"sky\"\nsky = \"uniform\"\ndiffuse_horizontal_lx = 12000\n"
                             "\n[[detector]]\nname = \"sensors\"\ntype = \"points\"\npoints = \"grid.pts\"\n"
                             "\n[run]\nseed = 5\n";
    const ResultReader r(run_scene(dir, text, 2'000'000));
    const std::vector<Reading> c = cells_of(r, "sensors");
    ASSERT_EQ(c.size(), 29u);
    const SkyModel sky = SkyModel::uniform();
    const double lz = 12000.0 / sky.horizontal_illuminance_per_zenith_luminance_sr();
    ZPool pool("points");
    for (std::size_t k = 0; k < 25; ++k)
        pool.add("upward sensor " + std::to_string(k), c[k].value, c[k].sigma, 12000.0);
    for (std::size_t k = 25; k < 29; ++k)
        pool.add("vertical sensor " + std::to_string(k), c[k].value, c[k].sigma,
                 lz * sky.vertical_illuminance_per_zenith_luminance_sr(0.0));
    pool.check("uniform sky");
    EXPECT_EQ(r.attr_f64("/detectors/sensors", "radius_m"), 0.5);  // half the 1 m spacing
}

// A 5 x 5 sensor grid 0.5 m apart (default discs r = 0.25 m) under a point light, and an
// illuminance grid whose 0.5 m cells have the sensors' centres: each sensor reads its
// disc's analytic mean; each sensor minus its cell reads the difference of the disc's and
// the square's means (their errors combined as independent, which overstates them: the
// two count many of the same photons). The result holds the sensors as read.
TEST(PointsRun, SensorsUnderAPointLightMatchTheAnalyticValueAndTheCoincidentGrid) {
    ScratchDir dir("points_lamp");
    std::ofstream pts(dir.path() / "grid.pts");
    for (int j = 0; j < 5; ++j)  // rows along y, as the illuminance grid's cells (i + 5 j)
        for (int i = 0; i < 5; ++i) pts << 0.5 * (i - 2) << ' ' << 0.5 * (j - 2) << " 0 0 0 1\n";
    pts.close();
    constexpr double kFlux = 1000.0, kHeight = 1.5;
    const std::string text = std::string(kBlackSpeck) + "\n[[light]]\ntype = \"point\"\nposition = [0, 0, 1.5]\n" +
                             "flux_lm = 1000\n\n[[detector]]\nname = \"sensors\"\ntype = \"points\"\n" +
                             "points = \"grid.pts\"\n\n[[detector]]\nname = \"cells\"\ncenter = [0, 0, 0]\n" +
                             "size = [2.5, 2.5]\ncells = [5, 5]\n\n[run]\nseed = 9\n";
    const ResultReader r(run_scene(dir, text, 4'000'000));
    const std::vector<Reading> s = cells_of(r, "sensors"), g = cells_of(r, "cells");
    ASSERT_EQ(s.size(), 25u);
    ASSERT_EQ(g.size(), 25u);
    const double intensity = kFlux / (4.0 * kPi);
    ZPool alone("points"), paired("points");
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const std::size_t k = static_cast<std::size_t>(i + 5 * j);
            const double x = 0.5 * (i - 2), y = 0.5 * (j - 2);
            const double disc = disc_average(intensity, kHeight, x, y, 0.25);
            const double square = square_average(intensity, kHeight, x, y, 0.5);
            alone.add("sensor " + std::to_string(k), s[k].value, s[k].sigma, disc);
            paired.add("sensor - cell " + std::to_string(k), s[k].value - g[k].value,
                       std::hypot(s[k].sigma, g[k].sigma), disc - square);
        }
    alone.check("point light, sensors against the disc means");
    // Independent errors overstate the difference's: its mean z^2 lies below 1; each
    // |z| within 5 still holds.
    std::vector<std::size_t> shape;
    const std::vector<double> positions = r.f64("/detectors/sensors/positions", &shape);
    ASSERT_EQ(shape, (std::vector<std::size_t>{25, 3}));
    EXPECT_EQ(positions[3 * 7 + 0], 0.5 * (2 - 2));
    EXPECT_EQ(positions[3 * 7 + 1], 0.5 * (1 - 2));
    const std::vector<double> directions = r.f64("/detectors/sensors/directions", &shape);
    ASSERT_EQ(shape, (std::vector<std::size_t>{25, 3}));
    EXPECT_EQ(directions[3 * 7 + 2], 1.0);
    EXPECT_EQ(r.attr_str("/detectors/sensors", "type"), "points");
    EXPECT_EQ(r.attr_str("/detectors/sensors", "points_file"), "grid.pts");
    EXPECT_NEAR(r.attr_f64("/detectors/sensors", "disc_area_m2"), kPi * 0.0625, 1e-15);
}

// The statistics built on cells work on sensors unchanged: two lamps in two light groups,
// a light scene of one of them, and a run target on two sensors. The whole run reads the
// sum of both lamps' disc means, the light scene the one lamp's, each within its errors;
// the run stops at the target, whose sensors' combined error is then within it.
TEST(PointsRun, LightGroupsScenesAndTargetsWorkOnSensors) {
    ScratchDir dir("points_groups");
    std::ofstream pts(dir.path() / "grid.pts");
    for (int i = 0; i < 6; ++i) pts << 0.5 * i - 1.25 << " 0 0 0 0 1\n";
    pts.close();
    const std::string text = std::string(kBlackSpeck) +
                             "\n[[light]]\ntype = \"point\"\nposition = [-1, 0, 1.5]\nflux_lm = 1000\ngroup = \"a\"\n"
                             "\n[[light]]\ntype = \"point\"\nposition = [1, 0, 1.5]\nflux_lm = 500\ngroup = \"b\"\n"
                             "\n[[light_scene]]\nname = \"only_a\"\ndimming = { a = 1 }\n"
                             "\n[[detector]]\nname = \"sensors\"\ntype = \"points\"\npoints = \"grid.pts\"\n"
                             "\n[run]\nseed = 12\nreport_every_photons = 100000\n"
                             "\n[[run.target]]\non = \"detector:sensors[2:4,0:1]\"\nrelative_error = 0.01\n";
    const ResultReader r(run_scene(dir, text, 50'000'000));
    EXPECT_NE(r.attr_str("/", "stop_reason").find("target"), std::string::npos) << r.attr_str("/", "stop_reason");
    const std::vector<Reading> all = cells_of(r, "sensors");
    const std::vector<double> v = r.f64("/light_scenes/only_a/detectors/sensors/value"),
                              rel = r.f64("/light_scenes/only_a/detectors/sensors/sigma_rel");
    ASSERT_EQ(all.size(), 6u);
    ASSERT_EQ(v.size(), 6u);
    const double ia = 1000.0 / (4.0 * kPi), ib = 500.0 / (4.0 * kPi);
    ZPool pool("points");
    double target_n = 0.0, target_var = 0.0;
    for (std::size_t k = 0; k < 6; ++k) {
        const double x = 0.5 * static_cast<double>(k) - 1.25;
        const double a = disc_average(ia, 1.5, x + 1.0, 0.0, 0.25), b = disc_average(ib, 1.5, x - 1.0, 0.0, 0.25);
        pool.add("both lamps, sensor " + std::to_string(k), all[k].value, all[k].sigma, a + b);
        pool.add("light scene only_a, sensor " + std::to_string(k), v[k], v[k] * rel[k], a);
        if (k == 2 || k == 3) {
            target_n += all[k].value;
            target_var += all[k].sigma * all[k].sigma;  // a bound: the run's own error is exact
        }
    }
    pool.check("two light groups and a light scene");
    EXPECT_LT(std::sqrt(target_var) / target_n, 0.01 * std::sqrt(2.0));
}

}  // namespace
}  // namespace luxtrace
