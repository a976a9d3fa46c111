// Radiance models run as they are (issue 25; docs/RADIANCE.md "Running Radiance models"):
// `luxtrace run model.rad --sensors grid.pts` and [[radiance]] in a scene. Physics judged by
// each run's own error: a Lambertian `light` panel over sensors gives the exact illuminance
// of a uniform rectangle (Radiance's 179 lm/W), a narrow distant `source` gives L times its
// solid angle, and a model in millimetres with `scale` gives the same flux as in metres.
// Bad input exits 2 naming the file and line, with nothing written.
#include "cie171_cases.hpp"
#include "luxtrace/core/math.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "luxtrace/scene/scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;
using test_support::run_luxtrace;
using test_support::ScratchDir;

// Illuminance at a point a distance h below the corner of a parallel Lambertian rectangle
// a x b of luminance L (the configuration factor of a differential area to a parallel
// rectangle, times pi L).
double corner_illuminance(double L, double a, double b, double h) {
    const double x = a / h, y = b / h;
    const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return 0.5 * L * (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy));
}

// Below (px, py) at depth h from the panel [x0, x1] x [y0, y1]: the four rectangles that
// share the point's foot as a corner, with signs.
double panel_illuminance(double L, double x0, double x1, double y0, double y1, double px, double py, double h) {
    const auto part = [&](double dx, double dy) {
        const double s = (dx < 0 ? -1.0 : 1.0) * (dy < 0 ? -1.0 : 1.0);
        return std::abs(dx) > 0 && std::abs(dy) > 0 ? s * corner_illuminance(L, std::abs(dx), std::abs(dy), h) : 0.0;
    };
    return part(x1 - px, y1 - py) - part(x0 - px, y1 - py) - part(x1 - px, y0 - py) + part(x0 - px, y0 - py);
}

// The mean over a sensor's disc of radius r (polar midpoint rule: the illuminance varies
// on the scale of h, so 16 x 32 points are exact far below the runs' errors).
double disc_mean(double L, double x0, double x1, double y0, double y1, double px, double py, double h, double r) {
    const int nr = 16, nt = 32;
    double sum = 0.0, weight = 0.0;
    for (int i = 0; i < nr; ++i) {
        const double rho = r * (i + 0.5) / nr;
        for (int j = 0; j < nt; ++j) {
            const double t = 2.0 * kPi * (j + 0.5) / nt;
            sum += rho * panel_illuminance(L, x0, x1, y0, y1, px + rho * std::cos(t), py + rho * std::sin(t), h);
            weight += rho;
        }
    }
    return sum / weight;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// A 1 m x 0.6 m panel of radiance 10 W/sr/m^2 (1790 cd/m^2) facing down, 1 m above a
// black floor, and nine sensors on the floor.
constexpr double kPanelX0 = -0.5, kPanelX1 = 0.5, kPanelY0 = -0.3, kPanelY1 = 0.3, kHeight = 1.0;
const char* const kPanelRad = R"(# a ceiling panel over a black floor
void light panel_light 0 0 3 10 10 10
void plastic black_floor 0 0 5 0 0 0 0 0
panel_light polygon panel 0 0 12
  -0.5 -0.3 1   -0.5 0.3 1   0.5 0.3 1   0.5 -0.3 1
black_floor polygon floor 0 0 12
  -3 -3 0   3 -3 0   3 3 0   -3 3 0
)";

std::vector<Vec3> panel_sensors() {
    std::vector<Vec3> s;
    for (const double x : {-0.6, 0.0, 0.3})
        for (const double y : {-0.2, 0.0, 0.4}) s.emplace_back(x, y, 0.0);
    return s;
}

void write_pts(const fs::path& p, const std::vector<Vec3>& sensors) {
    std::ofstream f(p);
    for (const Vec3& s : sensors) f << s.x << ' ' << s.y << ' ' << s.z << " 0 0 1\n";
}

// `luxtrace run FILES --sensors PTS OPTIONS` into DIR/NAME.h5 (quiet, 2 threads); fails the
// test unless it exits 0. Returns the result's path.
fs::path run_model(const ScratchDir& dir, const std::string& name, const std::vector<fs::path>& files,
                   const fs::path& pts, const std::string& options) {
    std::string args = "run";
    for (const fs::path& f : files) args += " \"" + f.string() + "\"";
    const fs::path out = dir.path() / (name + ".h5");
    args += " --sensors \"" + pts.string() + "\" " + options + " --output \"" + out.string() + "\" --quiet --threads 2";
    const auto o = run_luxtrace(args);
    EXPECT_EQ(o.code, 0) << o.out;
    return out;
}

// The panel's (or the opening's) exact illuminance, averaged over each sensor's disc.
std::vector<double> panel_exact(const std::vector<Vec3>& sensors, double L, double radius) {
    std::vector<double> exact;
    for (const Vec3& s : sensors)
        exact.push_back(disc_mean(L, kPanelX0, kPanelX1, kPanelY0, kPanelY1, s.x, s.y, kHeight, radius));
    return exact;
}

// Each sensor within 4.5 of its own sigma, and the mean z^2 within chi-square bounds.
void expect_within_errors(const fs::path& result, const std::string& detector, const std::vector<double>& exact) {
    const ResultReader r(result);
    const std::vector<double> value = r.f64("/detectors/" + detector + "/value");
    const std::vector<double> sigma_rel = r.f64("/detectors/" + detector + "/sigma_rel");
    ASSERT_EQ(value.size(), exact.size());
    double z2 = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
        const double z = (value[k] - exact[k]) / (sigma_rel[k] * value[k]);
        EXPECT_LT(std::abs(z), 4.5) << "sensor " << k << ": " << value[k] << " lx, exact " << exact[k]
                                    << " lx, sigma_rel " << sigma_rel[k];
        z2 += z * z;
    }
    const double n = static_cast<double>(exact.size());
    EXPECT_LT(z2, test_support::chi2_quantile(n, test_support::kZ999)) << "sum of z^2 over " << n << " sensors";
}

TEST(RadianceRun, LightPanelGivesTheRectanglesIlluminanceAt179LumensPerWatt) {
    ScratchDir dir("radiance_panel");
    write(dir.path() / "panel.rad", kPanelRad);
    const std::vector<Vec3> sensors = panel_sensors();
    write_pts(dir.path() / "floor.pts", sensors);
    const fs::path out = run_model(dir, "panel", {dir.path() / "panel.rad"}, dir.path() / "floor.pts",
                                   "--sensor-radius 0.1 --photons 8M");
    // Radiance's luminance of radiance 10 in each channel: 179 x 10 (the weights sum to 1).
    const double L = kRadianceEfficacy_lm_per_W * 10.0;
    expect_within_errors(out, "floor", panel_exact(sensors, L, 0.1));
    const ResultReader r(out);
    EXPECT_NEAR(r.attr_f64("/", "total_flux_lm"), kPi * L * 0.6, 1e-9 * L);
}

TEST(RadianceRun, NarrowDistantSourceGivesLuminanceTimesSolidAngle) {
    ScratchDir dir("radiance_source");
    // A sun-like source 30 degrees from the zenith over a black ground; the sensors face up.
    const double angle_deg = 0.5, radiance = 1e5;
    write(dir.path() / "sun.rad", R"(void light solar 0 0 3 1e5 1e5 1e5
solar source sun 0 0 4 0.5 0 0.8660254037844387 0.5
void plastic ground 0 0 5 0 0 0 0 0
ground polygon g 0 0 12 -2 -2 0  2 -2 0  2 2 0  -2 2 0
)");
    write_pts(dir.path() / "grid.pts", {Vec3(-0.5, 0, 0.01), Vec3(0.5, 0, 0.01), Vec3(0, 0.5, 0.01)});
    const fs::path out = run_model(dir, "sun", {dir.path() / "sun.rad"}, dir.path() / "grid.pts",
                                   "--sensor-radius 0.2 --photons 2M");
    const double omega = 2.0 * kPi * (1.0 - std::cos(0.5 * angle_deg * kPi / 180.0));
    // On a horizontal sensor: E_n cos(30 degrees).
    const double exact = kRadianceEfficacy_lm_per_W * radiance * omega * std::cos(kPi / 6.0);
    expect_within_errors(out, "grid", std::vector<double>(3, exact));
}

// A uniform sky seen through an opening is a Lambertian panel of the sky's luminance in the
// opening: the same exact illuminance as above, with the sky a 180-degree glow source and the
// opening an `illum` (a portal whose photons start at the opening).
TEST(RadianceRun, UniformSkyThroughAnIllumOpeningIsTheOpeningsConfigurationFactor) {
    ScratchDir dir("radiance_illum");
    write(dir.path() / "sky.rad", R"(void glow skyglow 0 0 4 2 2 2 0
skyglow source sky 0 0 4 0 0 1 180
)");
    // A black 4 m x 4 m x 1 m room; the roof is four pieces around the opening, which is
    // an illum facing down into the room (the light of a source leaves its front side).
    write(dir.path() / "room.rad", R"(void plastic black 0 0 5 0 0 0 0 0
void illum window 0 0 3 1 1 1
black polygon floor 0 0 12 -2 -2 0  2 -2 0  2 2 0  -2 2 0
black polygon w1 0 0 12 -2 -2 0  -2 -2 1  2 -2 1  2 -2 0
black polygon w2 0 0 12 -2 2 0  2 2 0  2 2 1  -2 2 1
black polygon w3 0 0 12 -2 -2 0  -2 2 0  -2 2 1  -2 -2 1
black polygon w4 0 0 12 2 -2 0  2 -2 1  2 2 1  2 2 0
black polygon r1 0 0 12 -2 -2 1  -2 2 1  -0.5 2 1  -0.5 -2 1
black polygon r2 0 0 12 0.5 -2 1  0.5 2 1  2 2 1  2 -2 1
black polygon r3 0 0 12 -0.5 0.3 1  -0.5 2 1  0.5 2 1  0.5 0.3 1
black polygon r4 0 0 12 -0.5 -2 1  -0.5 -0.3 1  0.5 -0.3 1  0.5 -2 1
window polygon opening 0 0 12 -0.5 -0.3 1  -0.5 0.3 1  0.5 0.3 1  0.5 -0.3 1
)");
    const std::vector<Vec3> sensors = panel_sensors();
    write_pts(dir.path() / "floor.pts", sensors);
    const fs::path out = run_model(dir, "room", {dir.path() / "sky.rad", dir.path() / "room.rad"},
                                   dir.path() / "floor.pts", "--sensor-radius 0.1 --photons 4M");
    const double L = kRadianceEfficacy_lm_per_W * 2.0;
    expect_within_errors(out, "floor", panel_exact(sensors, L, 0.1));
    // Every photon starts at the opening: the flux is the sky's through it, L pi A.
    EXPECT_NEAR(ResultReader(out).attr_f64("/", "total_flux_lm"), kPi * L * 0.6, 1e-6 * L);
}

// An ies2rad luminaire (Radiance's rect_fixture, tests/data/radiance) is a point light of
// the photometry its .dat holds, placed and turned as the file says: far below it the
// illuminance is I(direction) cos / d^2 (its 0.55 m x 0.12 m opening changes that by less
// than 0.1 % at 5 m).
TEST(RadianceRun, Ies2radLuminaireLightsAsItsPhotometryAtItsPlace) {
    ScratchDir dir("radiance_luminaire");
    const fs::path data = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance";
    write(dir.path() / "floor.rad", R"(void plastic black 0 0 5 0 0 0 0 0
black polygon floor 0 0 12 -30 -30 -2  30 -30 -2  30 30 -2  -30 30 -2
)");
    write(dir.path() / "scene.toml", "[[radiance]]\nfile = \"" + (data / "rect_fixture.rad").string() +
                                         "\"\n[[radiance]]\nfile = \"floor.rad\"\n"
                                         "[[detector]]\nname = \"floor\"\ntype = \"points\"\npoints = \"floor.pts\"\n"
                                         "radius_m = 0.25\n");
    const std::vector<Vec3> sensors = {Vec3(-4, 2.5, -1.99), Vec3(-1, 2.5, -1.99), Vec3(-4, 5.5, -1.99)};
    write_pts(dir.path() / "floor.pts", sensors);
    const Scene scene = load_scene(dir.path() / "scene.toml");
    ASSERT_EQ(scene.lights.lights().size(), 1u);
    ASSERT_TRUE(scene.lights.lights()[0].is<PointLight>());
    const PointLight& lum = *scene.lights.lights()[0].as<PointLight>();
    ASSERT_TRUE(lum.photometry);
    EXPECT_NEAR(lum.position.z, 2.999, 1e-3);  // the fixture's face, as its xform put it
    const fs::path out = dir.path() / "lum.h5";
    const auto o = run_luxtrace("run \"" + (dir.path() / "scene.toml").string() + "\" --photons 4M --output \"" +
                                out.string() + "\" --quiet --threads 2");
    ASSERT_EQ(o.code, 0) << o.out;
    std::vector<double> exact;
    for (const Vec3& p : sensors) {
        const Vec3 d = p - lum.position;
        const double r = glm::length(d);
        exact.push_back(lum.photometry->intensity_cd(lum.frame.to_local(d / r)) * (-d.z / r) / (r * r));
    }
    expect_within_errors(out, "floor", exact);
}

// CIE 171:2006 §5.9 written as Radiance files (tests/data/radiance/cie171: the black room,
// its 1 m x 1 m roof opening and `!gensky -c -B 55.865922`, 10 000 lx) with the opening an
// illum, as a Radiance user would mark it: every report point's sky component within the
// run's error of the exact one (daylight_reference), averaged over its sensor disc.
TEST(RadianceRun, Cie171RoofOpeningFromRadianceFilesGivesTheExactSkyComponents) {
    ScratchDir dir("radiance_cie171");
    const fs::path data = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "cie171";
    write(dir.path() / "opening.rad", R"(void illum roof_portal 0 0 3 1 1 1
roof_portal polygon opening 0 0 12 1.5 1.5 3  1.5 2.5 3  2.5 2.5 3  2.5 1.5 3
)");
    const double radius = 0.1;
    const fs::path out =
        run_model(dir, "roof", {data / "overcast_10000lx.sky", data / "room_roof_1x1.rad", dir.path() / "opening.rad"},
                  data / "points.pts", "--sensor-radius " + std::to_string(radius) + " --photons 8M");
    const auto cases = cie171::report_cases();
    const auto c = std::find_if(cases.begin(), cases.end(), [](const cie171::Case& k) { return k.id == "5.9 1x1"; });
    ASSERT_NE(c, cases.end());
    std::vector<double> exact;
    for (const cie171::Point& p : c->points) {
        // The disc mean by the 4-point rule exact for cubics (points at r / sqrt(2)).
        const Frame f = Frame::around(p.normal);
        double sum = 0.0;
        for (int k = 0; k < 4; ++k) {
            const double a = 0.5 * kPi * k, s = radius / std::sqrt(2.0);
            cie171::Point q = p;
            q.position += s * (std::cos(a) * f.t + std::sin(a) * f.b);
            sum += cie171::exact_sc_percent(*c, q, 16) / 100.0 * cie171::kDiffuseHorizontalLx;
        }
        exact.push_back(0.25 * sum);
    }
    expect_within_errors(out, "points", exact);
}

// Honeybee's sample model folder run as Honeybee wrote it (the files in oconv's order, the
// grid as written): one table line per sensor in the .pts order at the .pts positions, and
// no sensor brighter than the unobstructed sky's 10 000 lx by more than its error.
TEST(RadianceRun, HoneybeeModelRunsAsWritten) {
    ScratchDir dir("radiance_honeybee");
    const fs::path hb = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "honeybee";
    std::vector<fs::path> files{hb / "sky_10000lx.sky"};
    for (const char* f : {"scene/envelope.mat", "scene/shades.mat", "scene/envelope.rad", "scene/shades.rad",
                          "aperture/aperture.mat", "aperture/aperture.rad"})
        files.push_back(hb / "model" / f);
    run_model(dir, "office", files, hb / "model/grid/office.pts", "--photons 2M");
    std::ifstream table(dir.path() / "office.office.txt"), pts(hb / "model/grid/office.pts");
    std::string line;
    std::vector<std::vector<double>> rows;
    while (std::getline(table, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream in(line);
        std::vector<double> v(5);
        for (double& x : v) in >> x;
        rows.push_back(v);
    }
    std::size_t k = 0;
    while (std::getline(pts, line)) {
        std::istringstream in(line);
        double x, y, z;
        if (!(in >> x >> y >> z)) continue;
        ASSERT_LT(k, rows.size());
        EXPECT_EQ(rows[k][0], x);
        EXPECT_EQ(rows[k][1], y);
        EXPECT_EQ(rows[k][2], z);
        EXPECT_GE(rows[k][3], 0.0);
        if (rows[k][3] > 0.0) EXPECT_LT(rows[k][3] - 4.0 * rows[k][4], 10000.0) << "sensor " << k;
        ++k;
    }
    EXPECT_EQ(k, 54u);
    EXPECT_EQ(rows.size(), k);
}

// `!gensky 3 21 12 -a 40 -o 105 -m 105 +s` becomes its sky (CIE clear, type 12) and its sun
// (radiance_sky.hpp gives their keys): on sensors facing up over a black ground, nothing in
// the way, the run gives the two lights' unobstructed horizontal illuminance (the ground
// glow lies below the horizon, behind the sensors).
TEST(RadianceRun, GenskyLineBecomesItsSkyAndSun) {
    ScratchDir dir("radiance_gensky");
    write(dir.path() / "site.rad", R"(!gensky 3 21 12 -a 40 -o 105 -m 105 +s
skyfunc glow sky_mat 0 0 4 1 1 1 0
sky_mat source sky 0 0 4 0 0 1 180
void plastic black 0 0 5 0 0 0 0 0
black polygon ground 0 0 12 -5 -5 0  5 -5 0  5 5 0  -5 5 0
)");
    write_pts(dir.path() / "roof.pts", {Vec3(-2, 0, 0.01), Vec3(2, 0, 0.01), Vec3(0, 2, 0.01)});
    RadianceRun run;
    run.models = {dir.path() / "site.rad"};
    run.sensors = dir.path() / "roof.pts";
    const Scene scene = load_radiance_scene(run);
    double horizontal = 0.0;
    int skies = 0, suns = 0;
    for (const Light& l : scene.lights.lights()) {
        horizontal += l.unobstructed_horizontal_lx;
        skies += l.is<SkyLight>() && l.unobstructed_horizontal_lx > 0.0;
        suns += l.is<SunLight>();
    }
    EXPECT_EQ(skies, 1);
    EXPECT_EQ(suns, 1);
    const fs::path out = run_model(dir, "site", {dir.path() / "site.rad"}, dir.path() / "roof.pts",
                                   "--sensor-radius 0.5 --photons 2M");
    expect_within_errors(out, "roof", std::vector<double>(3, horizontal));
}

// `--target` with sensors is a target on the sensors: a run given far more photons than it
// needs stops when their pooled error reaches the goal, and reports it met.
TEST(RadianceRun, TargetWithSensorsStopsOnTheSensorsError) {
    ScratchDir dir("radiance_target");
    const fs::path ward = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "ward1990";
    const fs::path out = run_model(dir, "room", {ward / "room.rad"}, ward / "ceiling.pts",
                                   "--photons 100G --target 0.03");
    const ResultReader r(out);
    EXPECT_EQ(r.attr_str("/", "stop_reason").rfind("target detector:ceiling", 0), 0u) << r.attr_str("/", "stop_reason");
    const std::vector<double> sigma_rel = r.f64("/detectors/ceiling/sigma_rel");
    double q = 0.0;
    for (const double s : sigma_rel) q += s * s;
    EXPECT_LE(std::sqrt(q / static_cast<double>(sigma_rel.size())), 0.03);
}

// A `trans` sheet (Radiance's diffuse and specular transmission) under a uniform sky, nothing
// else: lit by pi L on top, it passes T = Td + Ts of it downward, diffusely (a Lambertian
// underside of luminance Td L) and straight (the sky seen through it, Ts L), so a sensor
// below sees pi L from the open sky around the sheet and T L through the sheet's solid
// angle: E = pi L - (1 - T) E_sheet, E_sheet the sheet's configuration factor times pi L.
TEST(RadianceRun, TransSheetPassesItsDiffuseAndSpecularTransmission) {
    ScratchDir dir("radiance_trans");
    // c 0.8, no specular reflection, transmissivity 0.5 of which 0.3 specular:
    // Rd = 0.4, Td = 0.8 x 0.5 x 0.7 = 0.28, Ts = 0.8 x 0.5 x 0.3 = 0.12.
    write(dir.path() / "sheet.rad", R"(void glow skyglow 0 0 4 1 1 1 0
skyglow source sky 0 0 4 0 0 1 180
void trans diffuser 0 0 7 0.8 0.8 0.8 0 0 0.5 0.3
diffuser polygon sheet 0 0 12 -0.5 -0.3 1  -0.5 0.3 1  0.5 0.3 1  0.5 -0.3 1
)");
    const std::vector<Vec3> sensors = panel_sensors();
    write_pts(dir.path() / "below.pts", sensors);
    const fs::path out = run_model(dir, "sheet", {dir.path() / "sheet.rad"}, dir.path() / "below.pts",
                                   "--sensor-radius 0.1 --photons 8M");
    const double L = kRadianceEfficacy_lm_per_W, T = 0.28 + 0.12;
    std::vector<double> exact = panel_exact(sensors, L, 0.1);
    for (double& e : exact) e = kPi * L - (1.0 - T) * e;
    expect_within_errors(out, "below", exact);
}

TEST(RadianceRun, ScaleMakesMetresOfAModelInMillimetres) {
    ScratchDir dir("radiance_scale");
    write(dir.path() / "panel_mm.rad", R"(void light panel_light 0 0 3 10 10 10
panel_light polygon panel 0 0 12 -500 -300 1000  -500 300 1000  500 300 1000  500 -300 1000
)");
    write(dir.path() / "scene.toml", R"([[radiance]]
file = "panel_mm.rad"
scale = 0.001
)");
    const Scene s = load_scene(dir.path() / "scene.toml");
    ASSERT_EQ(s.lights.lights().size(), 1u);
    EXPECT_NEAR(s.lights.total_flux_lm(), kPi * 1790.0 * 0.6, 1e-6);
    EXPECT_NEAR(s.bounds_max.z, 1.0, 1e-6);
    RadianceRun run;
    run.models = {dir.path() / "panel_mm.rad"};
    run.scale = 0.001;
    EXPECT_NEAR(load_radiance_scene(run).lights.total_flux_lm(), s.lights.total_flux_lm(), 1e-9);
}

TEST(RadianceRun, CheckPrintsWhatEachModifierBecomes) {
    const auto o = run_luxtrace("check \"" + std::string(LUXTRACE_TEST_DATA_DIR) + "/radiance/cornell.rad\"");
    ASSERT_EQ(o.code, 0) << o.out;
    EXPECT_NE(o.out.find("cornell.rad:31: plastic mat.red_wall -> diffuse reflectance"), std::string::npos) << o.out;
    EXPECT_NE(o.out.find("dielectric mat.sphere -> glass, index 1.5; absorption per metre"), std::string::npos)
        << o.out;
    EXPECT_NE(o.out.find("radiance light 'mat.light'"), std::string::npos) << o.out;
}

TEST(RadianceRun, BadInputExitsTwoNamingTheFileAndWritesNothing) {
    ScratchDir dir("radiance_bad");
    write(dir.path() / "box.rad", "void plastic white 0 0 5 .5 .5 .5 0 0\n!genbox white box 1 1 1\n");
    write(dir.path() / "panel.rad", kPanelRad);
    write(dir.path() / "grid.pts", "0 0 0 0 0 1\n0 0 0.5 0 0\n");
    const std::string out = (dir.path() / "out.h5").string();
    const auto cmd = run_luxtrace("run \"" + (dir.path() / "box.rad").string() + "\" --output \"" + out + "\"");
    EXPECT_EQ(cmd.code, 2) << cmd.out;
    EXPECT_NE(cmd.out.find("box.rad:2:"), std::string::npos) << cmd.out;
    const auto pts = run_luxtrace("run \"" + (dir.path() / "panel.rad").string() + "\" --sensors \"" +
                                  (dir.path() / "grid.pts").string() + "\" --output \"" + out + "\"");
    EXPECT_EQ(pts.code, 2) << pts.out;
    EXPECT_NE(pts.out.find("grid.pts:2"), std::string::npos) << pts.out;
    const auto mixed = run_luxtrace("run \"" + (dir.path() / "panel.rad").string() + "\" \"" +
                                    (dir.path() / "grid.pts").string() + "\" --output \"" + out + "\"");
    EXPECT_EQ(mixed.code, 2) << mixed.out;
    const auto no_light = run_luxtrace("check \"" + std::string(LUXTRACE_TEST_DATA_DIR) + "/radiance/corner.rad\"");
    EXPECT_EQ(no_light.code, 2) << no_light.out;
    EXPECT_NE(no_light.out.find("no light"), std::string::npos) << no_light.out;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 3);
}

}  // namespace
}  // namespace luxtrace
