// UGR at observer positions (CIE 117:1995; docs/GLARE.md). Guth's position index against
// its table; the [[observer]] keys and their errors; two panels in a grey room whose L,
// omega, p and UGR are computed here by hand from the scene's numbers; and the indirect
// vertical illuminance at an eye inside an integrating sphere, whose value is known.
#include "luxtrace/core/error.hpp"
#include "luxtrace/glare/ugr.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/scene/scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifndef LUXTRACE_TEST_DATA_DIR
#error "define LUXTRACE_TEST_DATA_DIR (the tests/data folder)"
#endif

namespace luxtrace {
namespace {

namespace fs = std::filesystem;
using test_support::run_luxtrace;

constexpr double kDeg = kPi / 180.0;

// ---- Guth's position index ----------------------------------------------------------

TEST(GuthPositionIndex, IsOneOnTheLineOfSight) {
    for (double alpha = 0.0; alpha <= 90.0; alpha += 15.0) EXPECT_DOUBLE_EQ(guth_position_index(alpha, 0.0), 1.0);
}

// The column T/R = 0 (sources straight above the line of sight) of Guth's table, CIE
// 117:1995 Table 4.1, H/R = 0.0, 0.1, ..., 1.7, as the handbooks reproduce it. The
// analytic form is CIE's fit to the table: it stays within 3.5 % of every entry.
TEST(GuthPositionIndex, FitsTheTableAboveTheLineOfSight) {
    const double table[] = {1.00, 1.26, 1.53, 1.90, 2.35,  2.86,  3.50,  4.20,  5.00,
                            6.00, 7.00, 8.10, 9.25, 10.35, 11.70, 13.15, 14.70, 16.20};
    for (int k = 0; k < 18; ++k) {
        const double h_over_r = 0.1 * k;
        const double beta = std::atan(h_over_r) / kDeg;
        EXPECT_NEAR(guth_position_index(0.0, beta) / table[k], 1.0, 0.035) << "H/R = " << h_over_r;
    }
}

// Over the table's field (H/R <= 1.9, T/R <= 3), p grows as a source moves away from the
// line of sight in any plane; and a source straight above the line of sight glares less
// (larger p) than one level with the eye at the same angle: p(0, b) > p(90, b).
TEST(GuthPositionIndex, GrowsAwayFromTheLineOfSight) {
    for (double alpha = 0.0; alpha <= 90.0; alpha += 10.0) {
        // The edge of the table in the plane alpha: H = s cos(alpha), T = s sin(alpha).
        const double c = std::cos(alpha * kDeg), s = std::sin(alpha * kDeg);
        const double s_max = std::min(c > 1e-12 ? 1.9 / c : 1e9, s > 1e-12 ? 3.0 / s : 1e9);
        const double beta_max = std::atan(s_max) / kDeg;
        double last = guth_position_index(alpha, 0.0);
        for (double beta = 1.0; beta <= beta_max; beta += 1.0) {
            const double p = guth_position_index(alpha, beta);
            EXPECT_GT(p, last) << "alpha " << alpha << " beta " << beta;
            last = p;
        }
        EXPECT_LT(last, 20.0) << "alpha " << alpha;  // the table's entries stay below 20
    }
    for (double beta = 10.0; beta <= 60.0; beta += 10.0)
        EXPECT_GT(guth_position_index(0.0, beta), guth_position_index(90.0, beta)) << beta;
}

TEST(Ugr, FormulaAndError) {
    GlareSource a, b;
    a.luminance_cd_m2 = 2000.0;
    a.solid_angle_sr = 0.01;
    a.position_index = 2.0;
    b.luminance_cd_m2 = 1000.0;
    b.solid_angle_sr = 0.004;
    b.position_index = 4.0;
    // sum = 4e6 * 0.01 / 4 + 1e6 * 0.004 / 16 = 10000 + 250; Lb = 31.4159.. / pi = 10 cd/m^2.
    const UgrEstimate u = estimate_ugr({a, b}, 10.0 * kPi, 0.02);
    EXPECT_NEAR(u.background_luminance_cd_m2, 10.0, 1e-12);
    EXPECT_NEAR(u.glare_sum, 10250.0, 1e-9);
    EXPECT_NEAR(u.ugr, 8.0 * std::log10(0.25 * 10250.0 / 10.0), 1e-12);
    EXPECT_NEAR(u.ugr_sigma, 8.0 / std::log(10.0) * 0.02, 1e-12);
    EXPECT_TRUE(std::isnan(estimate_ugr({}, 10.0, 0.02).ugr));  // no luminaire in view
    EXPECT_TRUE(std::isnan(estimate_ugr({a}, 0.0, 0.0).ugr));   // no background light
}

// ---- [[observer]] in the scene file -------------------------------------------------

class ObserverKeys : public ::testing::Test {
protected:
    test_support::ScratchDir scratch_{std::string("glare_test_") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name()};
    const fs::path& dir_ = scratch_.path();

    void SetUp() override {
        fs::copy_file(fs::path(LUXTRACE_TEST_DATA_DIR) / "glare" / "panel_600.ies", dir_ / "panel_600.ies");
    }
    // A grey room with one panel at (3, 2, 2.9) and whatever `extra` adds.
    fs::path write(const std::string& extra) const {
        const fs::path f = dir_ / "scene.toml";
        std::ofstream(f) << "[[material]]\nname = \"g\"\ntype = \"diffuse\"\nreflectance = 0.5\n"
                            "[[shape]]\ntype = \"box\"\ncenter = [3, 2, 1.5]\nsize = [6, 4, 3]\ninward = true\n"
                            "material = \"g\"\n"
                            "[[light]]\ntype = \"point\"\nphotometry = \"panel_600.ies\"\nposition = [3, 2, 2.9]\n"
                         << extra;
        return f;
    }
    // Loading must fail naming the file, the key and the fragment.
    void expect_bad(const std::string& extra, const std::string& key, const std::string& fragment) const {
        const fs::path f = write(extra);
        try {
            (void)load_scene(f);
            ADD_FAILURE() << "no InputError for:\n" << extra;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(f.string()), std::string::npos) << msg;
            EXPECT_NE(msg.find(key), std::string::npos) << msg;
            EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
        }
    }
};

TEST_F(ObserverKeys, DefaultsAndTheEyeDetector) {
    const Scene s = load_scene(write("[[detector]]\nname = \"desk\"\ncenter = [3, 2, 0.8]\nsize = [1, 1]\n"
                                     "[[observer]]\nposition = [0.5, 2, 1.2]\nview_direction = [2, 0, 0]\n"
                                     "[[observer]]\nname = \"door\"\nposition = [5.5, 0.5, 1.6]\n"
                                     "view_direction = [-1, 1, 0]\neye_detector_size = 0.1\n"));
    ASSERT_EQ(s.observers.size(), 2u);
    ASSERT_EQ(s.detectors.size(), 3u);  // the user's, then one per observer
    const Observer& a = s.observers[0];
    EXPECT_EQ(a.name, "observer_1");
    EXPECT_DOUBLE_EQ(a.eye_detector_size_m, 0.2);
    EXPECT_NEAR(glm::length(a.view_direction - Vec3(1, 0, 0)), 0.0, 1e-15);
    EXPECT_EQ(a.eye_detector, 1u);
    const Detector& eye = s.detectors[1];
    EXPECT_EQ(eye.name, "observer:observer_1");
    EXPECT_TRUE(eye.indirect_only);
    EXPECT_EQ(eye.observer, 0);
    EXPECT_EQ(eye.type, DetectorType::illuminance);
    EXPECT_NEAR(glm::length(eye.normal - Vec3(1, 0, 0)), 0.0, 1e-15);  // vertical, facing the line of sight
    EXPECT_NEAR(eye.size_u * eye.size_v, 0.04, 1e-15);
    EXPECT_EQ(eye.cells(), 1);
    ASSERT_EQ(a.sources.size(), 1u);  // the panel ahead, 1.7 m above the eye
    EXPECT_FALSE(s.detectors[0].indirect_only);
    EXPECT_EQ(s.detectors[0].observer, -1);
    const Observer& b = s.observers[1];
    EXPECT_EQ(b.name, "door");
    EXPECT_EQ(s.detectors[2].name, "observer:door");
    EXPECT_DOUBLE_EQ(b.eye_detector_size_m, 0.1);
    EXPECT_EQ(b.sources.size(), 1u);
}

TEST_F(ObserverKeys, BadInputIsRefused) {
    const std::string pos = "position = [0.5, 2, 1.2]\n", view = "view_direction = [1, 0, 0]\n";
    expect_bad("[[observer]]\n" + view, "[[observer]] #1", "needs 'position'");
    expect_bad("[[observer]]\n" + pos, "[[observer]] #1", "needs 'view_direction'");
    expect_bad("[[observer]]\n" + pos + "view_direction = [0, 0, 0]\n", "view_direction", "non-zero");
    expect_bad("[[observer]]\n" + pos + "view_direction = [0.1, 0, -1]\n", "view_direction", "vertical");
    expect_bad("[[observer]]\n" + pos + view + "eye_detector_size = 0\n", "eye_detector_size", "(0, 1]");
    expect_bad("[[observer]]\n" + pos + view + "eye_detector_size = 1.5\n", "eye_detector_size", "(0, 1]");
    expect_bad("[[observer]]\n" + pos + view + "name = \"a b\"\n", "name", "may not contain");
    expect_bad("[[observer]]\n" + pos + view + "name = \"\"\n", "name", "empty");
    expect_bad("[[observer]]\n" + pos + view + "name = \"x\"\n[[observer]]\n" + pos + view + "name = \"x\"\n", "name",
               "defined twice");
    expect_bad("[[observer]]\n" + pos + view + "eye = 3\n", "eye", "unknown key");
    expect_bad("[[observer]]\nposition = [0.5, 2]\n" + view, "position", "");
    expect_bad("[[observer]]\nname = \"x\"\n" + pos + view +
                   "[run]\n[[run.target]]\non = \"observer:y\"\n"
                   "relative_error = 0.02\n",
               "on", "no [[observer]] is named 'y'");
    // A target on an observer's E_ind is accepted.
    const Scene s = load_scene(write("[[observer]]\nname = \"x\"\n" + pos + view +
                                     "[run]\n[[run.target]]\non = \"observer:x\"\nrelative_error = 0.02\n"));
    ASSERT_EQ(s.run.targets.size(), 1u);
    EXPECT_EQ(s.run.targets[0].detector, "observer:x");
}

// Lights without a luminous area cannot enter the UGR sum: the scene says which.
TEST_F(ObserverKeys, LightsWithoutLuminousAreaAreNamed) {
    const Scene s = load_scene(write("[[light]]\ntype = \"point\"\nposition = [4, 2, 2.5]\nflux_lm = 500\n"
                                     "[[light]]\ntype = \"spot\"\nposition = [4, 1, 2.5]\ndirection = [0, 0, -1]\n"
                                     "half_angle_deg = 20\nflux_lm = 500\n"
                                     "[[light]]\ntype = \"point\"\nposition = [0.2, 2, 2.5]\nflux_lm = 500\n"
                                     "[[observer]]\nposition = [0.5, 2, 1.2]\nview_direction = [1, 0, 0]\n"));
    ASSERT_EQ(s.observers.size(), 1u);
    EXPECT_EQ(s.observers[0].sources.size(), 1u);  // the panel only
    std::string all;
    for (const std::string& w : s.warnings) all += w + "\n";
    EXPECT_NE(all.find("light 2 (point) is left out of UGR: it has no luminous area"), std::string::npos) << all;
    EXPECT_NE(all.find("light 3 (spot) is left out of UGR"), std::string::npos) << all;
    EXPECT_EQ(all.find("light 4"), std::string::npos) << all;  // behind the eye: it could not count
}

// UGR does not test what the eye sees; `luxtrace check` says when a surface hides a
// luminaire it counts, and only then.
TEST_F(ObserverKeys, CheckNamesHiddenLuminaires) {
    const std::string observer = "[[observer]]\nposition = [0.5, 2, 1.2]\nview_direction = [1, 0, 0]\n";
    const auto open = run_luxtrace("check " + write(observer).string());
    ASSERT_EQ(open.code, 0) << open.out;
    EXPECT_EQ(open.out.find("hidden"), std::string::npos) << open.out;
    const std::string partition = "[[shape]]\ntype = \"rectangle\"\ncenter = [2, 2, 1.5]\nnormal = [-1, 0, 0]\n"
                                  "size = [4, 3]\nup = [0, 0, 1]\nmaterial = \"g\"\n";
    const auto hidden = run_luxtrace("check " + write(observer + partition).string());
    ASSERT_EQ(hidden.code, 0) << hidden.out;
    EXPECT_NE(hidden.out.find("observer 'observer_1': light 1 (point) is hidden from the eye by a surface"),
              std::string::npos)
        << hidden.out;
}

// ---- whole runs ---------------------------------------------------------------------

fs::path scene(const std::string& name) { return fs::path(LUXTRACE_TEST_DATA_DIR) / "glare" / (name + ".toml"); }

class GlareRun : public ::testing::Test {
protected:
    test_support::ScratchDir scratch_{std::string("glare_run_") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name()};
    const fs::path& dir_ = scratch_.path();
};

// One panel's terms seen from the eye, from first principles: a flat Lambertian 0.6 m
// square facing down with I = 360 cd cos(gamma) has luminance 360 / 0.36 = 1000 cd/m^2
// toward every direction below it and projected area 0.36 cos(gamma).
struct HandTerms {
    double L, omega, p, alpha_deg, beta_deg;
};
HandTerms hand_terms(const Vec3& eye, const Vec3& panel) {
    const Vec3 v = panel - eye;  // the observer looks along +x, up is +z, right is -y
    const double R = v.x, H = v.z, T = -v.y, r2 = glm::dot(v, v);
    const double cos_gamma = H / std::sqrt(r2);  // the panel faces straight down
    HandTerms t{};
    t.L = 360.0 * cos_gamma / (0.36 * cos_gamma);
    t.omega = 0.36 * cos_gamma / r2;
    t.beta_deg = std::atan(std::sqrt(H * H + T * T) / R) / kDeg;
    t.alpha_deg = std::atan(std::abs(T) / H) / kDeg;
    const double a = t.alpha_deg, b = t.beta_deg;  // CIE 117's form of Guth's index
    t.p = std::exp((35.2 - 0.31889 * a - 1.22 * std::exp(-2.0 * a / 9.0)) * 1e-3 * b +
                   (21.0 + 0.26667 * a - 0.002963 * a * a) * 1e-5 * b * b);
    return t;
}

TEST_F(GlareRun, TwoPanelsByHand) {
    const fs::path out = dir_ / "office.h5";
    const auto run = run_luxtrace("run " + scene("office").string() + " --output " + out.string() +
                                  " --quiet --threads 2 --photons 2M --seed 13");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    ASSERT_TRUE(r.has("/observers/desk"));
    EXPECT_TRUE(r.children("/detectors").empty());  // the eye detector is not a user's detector
    const std::string g = "/observers/desk";
    const Vec3 eye(0.5, 2, 1.2);
    const HandTerms t[2] = {hand_terms(eye, Vec3(3, 1, 2.9)), hand_terms(eye, Vec3(5, 3, 2.9))};
    ASSERT_EQ(r.attr_u64(g, "luminaires_in_view"), 2u);
    EXPECT_FALSE(r.has_attr(g, "ugr_maintained"));  // maintenance factor 1
    const std::vector<double> L = r.f64(g + "/luminance_cd_m2"), omega = r.f64(g + "/solid_angle_sr"),
                              p = r.f64(g + "/position_index"), alpha = r.f64(g + "/alpha_deg"),
                              beta = r.f64(g + "/beta_deg");
    ASSERT_EQ(L.size(), 2u);
    double sum = 0.0;
    for (int k = 0; k < 2; ++k) {
        // The file's table holds cos(gamma) at whole degrees: interpolated between them the
        // intensity is off by at most (1 degree)^2 / 8 = 4e-5 relative.
        EXPECT_NEAR(L[k] / t[k].L, 1.0, 1e-4) << k;
        EXPECT_NEAR(omega[k] / t[k].omega, 1.0, 1e-12) << k;
        EXPECT_NEAR(alpha[k], t[k].alpha_deg, 1e-9) << k;
        EXPECT_NEAR(beta[k], t[k].beta_deg, 1e-9) << k;
        EXPECT_NEAR(p[k] / t[k].p, 1.0, 1e-12) << k;
        sum += t[k].L * t[k].L * t[k].omega / (t[k].p * t[k].p);
    }
    // UGR from the hand terms and the run's E_ind; its error from E_ind's.
    const double e_ind = r.attr_f64(g, "indirect_vertical_illuminance_lx");
    const double rel = r.attr_f64(g, "indirect_vertical_illuminance_sigma_rel");
    ASSERT_GT(e_ind, 0.0);
    EXPECT_NEAR(r.attr_f64(g, "background_luminance_cd_m2"), e_ind / kPi, 1e-12 * e_ind);
    const double ugr = 8.0 * std::log10(0.25 / (e_ind / kPi) * sum);
    EXPECT_NEAR(r.attr_f64(g, "ugr"), ugr, 1e-3);
    EXPECT_NEAR(r.attr_f64(g, "ugr_sigma"), 8.0 / std::log(10.0) * rel, 1e-12);
    // E_ind is eq. (8) on the eye detector's n and q: recompute it from the stored tallies.
    const double n = static_cast<double>(r.u64(g + "/eye_count").at(0));
    const double q = static_cast<double>(r.u64(g + "/eye_sumsq").at(0));
    const double photons = static_cast<double>(r.attr_u64("/", "photons"));
    EXPECT_NEAR(e_ind, r.attr_f64("/", "flux_per_photon_lm") * n / 0.04, 1e-9 * e_ind);
    EXPECT_NEAR(rel, std::sqrt(q / (n * n) - 1.0 / photons), 1e-12);
    EXPECT_LT(rel, 0.06);
    // The summary and `luxtrace info` report it.
    const auto info = run_luxtrace("info " + out.string());
    ASSERT_EQ(info.code, 0) << info.out;
    EXPECT_NE(info.out.find("observer desk"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("UGR "), std::string::npos) << info.out;
}

// Light scenes (issue 22): each panel its own group. At one weight w for every group, the
// luminances and E_ind all scale by w, so UGR moves by exactly 8 log10(w); with the far
// panel off, UGR is the near panel's term over the scene's own E_ind.
TEST_F(GlareRun, LightScenesDimTheLuminairesTheyView) {
    const std::string ies = (fs::path(LUXTRACE_TEST_DATA_DIR) / "glare" / "panel_600.ies").string();
    const std::string text = "[[material]]\nname = \"grey\"\nreflectance = 0.5\n"
                             "[[shape]]\ntype = \"box\"\ncenter = [3, 2, 1.5]\nsize = [6, 4, 3]\ninward = true\n"
                             "subdivisions = 6\nmaterial = \"grey\"\n"
                             "[[light]]\ntype = \"point\"\nphotometry = \"" +
                             ies +
                             "\"\nposition = [3, 1, 2.9]\ngroup = \"near\"\n"
                             "[[light]]\ntype = \"point\"\nphotometry = \"" +
                             ies +
                             "\"\nposition = [5, 3, 2.9]\ngroup = \"far\"\n"
                             "[[light_scene]]\nname = \"half\"\ndimming = { near = 0.5, far = 0.5 }\n"
                             "[[light_scene]]\nname = \"near_only\"\ndimming = { near = 1 }\n"
                             "[[observer]]\nname = \"desk\"\nposition = [0.5, 2, 1.2]\nview_direction = [1, 0, 0]\n";
    const fs::path file = dir_ / "groups.toml", out = dir_ / "groups.h5";
    std::ofstream(file) << text;
    const auto run = run_luxtrace("run " + file.string() + " --output " + out.string() +
                                  " --quiet --threads 2 --photons 1M --seed 17");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    const std::string plain = "/observers/desk", half = "/light_scenes/half/observers/desk",
                      near = "/light_scenes/near_only/observers/desk";
    // The plain eye counts are every group's together: E_ind is eq. (8)'s value on them.
    const double e_plain = r.attr_f64(plain, "indirect_vertical_illuminance_lx");
    EXPECT_NEAR(e_plain,
                r.attr_f64("/", "flux_per_photon_lm") * static_cast<double>(r.u64(plain + "/eye_count").at(0)) / 0.04,
                1e-9 * e_plain);
    EXPECT_NEAR(r.attr_f64(half, "ugr"), r.attr_f64(plain, "ugr") + 8.0 * std::log10(0.5), 1e-9);
    EXPECT_NEAR(r.attr_f64(half, "ugr_sigma"), r.attr_f64(plain, "ugr_sigma"), 1e-12);
    const HandTerms t = hand_terms(Vec3(0.5, 2, 1.2), Vec3(3, 1, 2.9));
    const double e_ind = r.attr_f64(near, "indirect_vertical_illuminance_lx");
    ASSERT_GT(e_ind, 0.0);
    EXPECT_LT(e_ind, r.attr_f64(plain, "indirect_vertical_illuminance_lx"));
    EXPECT_NEAR(r.attr_f64(near, "ugr"), 8.0 * std::log10(0.25 / (e_ind / kPi) * t.L * t.L * t.omega / (t.p * t.p)),
                1e-3);
}

// `on = "observer:NAME"` stops the run when E_ind's relative error (hence UGR's, 3.47
// times it) reaches the goal.
TEST_F(GlareRun, ObserverTargetStopsTheRun) {
    std::ifstream in(scene("office"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text += "report_every_photons = 250000\n[[run.target]]\non = \"observer:desk\"\nrelative_error = 0.06\n";
    text.replace(text.find("[scene]\n"), 8, "[scene]\nmaintenance_factor = 0.8\n");  // and a maintained UGR
    fs::copy_file(scene("office").parent_path() / "panel_600.ies", dir_ / "panel_600.ies");
    std::ofstream(dir_ / "office.toml") << text;
    const fs::path out = dir_ / "office.h5";
    const auto run = run_luxtrace("run " + (dir_ / "office.toml").string() + " --output " + out.string() +
                                  " --quiet --threads 2 --photons 20M --seed 13");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    const std::string reason = r.attr_str("/", "stop_reason");
    EXPECT_NE(reason.find("observer:desk"), std::string::npos) << reason;
    EXPECT_LT(r.attr_u64("/", "photons"), 20'000'000u);
    const double rel = r.attr_f64("/observers/desk", "indirect_vertical_illuminance_sigma_rel");
    EXPECT_LE(rel, 0.06);
    EXPECT_GT(rel, 0.03);  // it stopped at the first reduction that met the goal, not much later
    EXPECT_NEAR(r.attr_f64("/observers/desk", "ugr_sigma"), 8.0 / std::log(10.0) * rel, 1e-12);
    // L^2 / Lb scales as the maintenance factor.
    EXPECT_NEAR(r.attr_f64("/observers/desk", "ugr_maintained"),
                r.attr_f64("/observers/desk", "ugr") + 8.0 * std::log10(0.8), 1e-12);
}

// An observer only watches: the same run without it has bit-identical surface tallies
// (photon k's random numbers do not depend on the detectors).
TEST_F(GlareRun, AnObserverChangesNothingElse) {
    std::ifstream in(scene("office"));
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t from = text.find("[[observer]]"), to = text.find("[run]");
    ASSERT_TRUE(from != std::string::npos && to != std::string::npos && from < to);
    fs::copy_file(scene("office").parent_path() / "panel_600.ies", dir_ / "panel_600.ies");
    std::ofstream(dir_ / "plain.toml") << text.substr(0, from) + text.substr(to);
    for (const std::string& s : {scene("office").string(), (dir_ / "plain.toml").string()}) {
        const fs::path out = dir_ / (fs::path(s).stem().string() + ".h5");
        const auto run = run_luxtrace("run " + s + " --output " + out.string() +
                                      " --quiet --threads 2 --photons 300000 --seed 4");
        ASSERT_EQ(run.code, 0) << run.out;
    }
    const ResultReader with(dir_ / "office.h5"), without(dir_ / "plain.h5");
    EXPECT_TRUE(with.has("/observers/desk"));
    EXPECT_FALSE(without.has("/observers"));
    for (const char* d : {"/global/count_odd", "/global/count_even", "/global/direct_odd", "/global/direct_even"})
        EXPECT_EQ(with.u64(d), without.u64(d)) << d;
}

// Under --sampler sobol E_ind's error is the replicate spread (R - 1 degrees of freedom),
// and UGR's follows it.
TEST_F(GlareRun, SobolErrorsComeFromTheReplicates) {
    const fs::path out = dir_ / "sobol.h5";
    const auto run = run_luxtrace("run " + scene("office").string() + " --output " + out.string() +
                                  " --quiet --threads 2 --photons 512K --sampler sobol --replicates 8 --seed 2");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    const std::string g = "/observers/desk";
    EXPECT_EQ(r.attr_str(g, "error_estimator"), "replicate_spread");
    EXPECT_EQ(r.attr_u64(g, "error_dof"), 7u);
    const double rel = r.attr_f64(g, "indirect_vertical_illuminance_sigma_rel");
    EXPECT_TRUE(rel > 0.0 && rel < 0.5) << rel;
    EXPECT_NEAR(r.attr_f64(g, "ugr_sigma"), 8.0 / std::log(10.0) * rel, 1e-12);
}

// In an integrating sphere lit uniformly the walls share one luminance, rho F / ((1 - rho)
// pi S), so any plane inside receives E_ind = rho F / ((1 - rho) S) from them; the direct
// light at the eye, F cos / (4 pi d^2), 3.4 times as much here, must not be counted (the
// source lies in front of the eye).
TEST_F(GlareRun, IndirectIlluminanceInAnIntegratingSphere) {
    const fs::path out = dir_ / "sphere.h5";
    const auto run = run_luxtrace("run " + scene("sphere_room").string() + " --output " + out.string() +
                                  " --quiet --threads 2 --photons 2M --seed 7");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    const std::string g = "/observers/off_centre";
    double s = 0.0;
    for (double a : r.f64("/mesh/area")) s += a;
    EXPECT_NEAR(s / (4.0 * kPi * 4.0), 1.0, 0.01);  // the triangulated sphere of radius 2 m
    const double rho = 0.5, flux = 10000.0;
    const double ref = rho * flux / ((1.0 - rho) * s);
    const double e = r.attr_f64(g, "indirect_vertical_illuminance_lx");
    const double sigma = r.attr_f64(g, "indirect_vertical_illuminance_sigma_rel") * e;
    EXPECT_LT(std::abs(e - ref) / sigma, 4.0) << "E_ind " << e << " lx, reference " << ref << " lx, sigma " << sigma;
    EXPECT_LT(sigma / e, 0.02);
    EXPECT_EQ(r.attr_u64(g, "luminaires_in_view"), 0u);
    EXPECT_TRUE(std::isnan(r.attr_f64(g, "ugr")));
}

}  // namespace
}  // namespace luxtrace
