// Tests of glazing (include/luxtrace/material/glazing.hpp, docs/DAYLIGHT.md "Glazing"):
// the closed form of a thin pane against a bounce-by-bounce sum of its internal
// reflections; the normal transmittance recovered from the derived transmissivity; the
// tracer's curve within 1e-5 of the closed form; CIE 171:2006 test case 5.5 (6 mm clear
// glass) within 0.5 % from 0 to 75 degrees; makers' tables; sampled event frequencies
// against R and T (chi-square); the loader's bad input; and whole runs, a parallel beam
// through a glazed pane onto an illuminance detector at several incidence angles.
#include "luxtrace/material/glazing.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"

#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = kPi / 180.0;

double sq(double x) { return x * x; }

// One polarisation followed bounce by bounce: r from the sine and tangent forms of the
// Fresnel equations (not the cosine form glazing.cpp uses), each pass through the glass
// attenuated by tau0^(1 / cos theta_t), the beam split at every interface until what is
// left inside is below 1e-17.
PaneOptics summed_bounces(double theta_i, double n, double tau0, bool s_polarised) {
    double r;
    double cos_t;
    if (theta_i == 0.0) {
        r = sq((n - 1.0) / (n + 1.0));
        cos_t = 1.0;
    } else {
        const double theta_t = std::asin(std::sin(theta_i) / n);
        r = s_polarised ? sq(std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t))
                        : sq(std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t));
        cos_t = std::cos(theta_t);
    }
    const double pass = std::pow(tau0, 1.0 / cos_t);
    PaneOptics out{r, 0.0};
    double inside = 1.0 - r;  // heading for the far face
    for (int bounce = 0; inside > 1e-17 && bounce < 100000; ++bounce) {
        inside *= pass;
        out.transmittance += inside * (1.0 - r);  // leaves through the far face
        inside *= r;                              // back towards the near face
        inside *= pass;
        out.reflectance += inside * (1.0 - r);  // leaves through the near face
        inside *= r;
    }
    return out;
}

TEST(PaneOptics, ClosedFormEqualsTheSumOfInternalReflections) {
    for (double n : {1.0, 1.33, 1.52, 2.0, 3.0})
        for (double tau0 : {0.3, 0.8, 0.95, 1.0})
            for (double deg = 0.0; deg < 89.95; deg += 0.5) {
                const PaneOptics s = summed_bounces(deg * kDeg, n, tau0, true);
                const PaneOptics p = summed_bounces(deg * kDeg, n, tau0, false);
                const PaneOptics got = pane_optics(std::cos(deg * kDeg), n, tau0);
                EXPECT_NEAR(got.reflectance, 0.5 * (s.reflectance + p.reflectance), 1e-12)
                    << "n " << n << " tau0 " << tau0 << " at " << deg << " deg";
                EXPECT_NEAR(got.transmittance, 0.5 * (s.transmittance + p.transmittance), 1e-12)
                    << "n " << n << " tau0 " << tau0 << " at " << deg << " deg";
            }
    // Grazing incidence reflects everything, even without absorption.
    const PaneOptics g = pane_optics(0.0, 1.52, 1.0);
    EXPECT_EQ(g.reflectance, 1.0);
    EXPECT_EQ(g.transmittance, 0.0);
}

TEST(PaneOptics, TransmissivityGivesBackTheNormalTransmittance) {
    for (double n : {1.0, 1.01, 1.52, 2.5})
        for (double t : {0.01, 0.3, 0.6, 0.8, 0.88, 0.9})
            if (t <= max_pane_transmittance(n)) {
                const double tau0 = pane_transmissivity(t, n);
                EXPECT_GT(tau0, 0.0);
                EXPECT_LE(tau0, 1.0);
                EXPECT_NEAR(pane_optics(1.0, n, tau0).transmittance, t, 1e-14) << "n " << n << " T " << t;
            }
    // No absorption at the largest transmittance; no interfaces at n = 1.
    EXPECT_NEAR(pane_transmissivity(max_pane_transmittance(1.52), 1.52), 1.0, 1e-14);
    EXPECT_NEAR(pane_transmissivity(0.7, 1.0), 0.7, 1e-15);
    // The same root in the form of Radiance's trans.cal (which cancels as r0 -> 0).
    for (double t : {0.5, 0.88}) {
        const double r0 = sq(0.52 / 2.52);
        EXPECT_NEAR(pane_transmissivity(t, 1.52),
                    (std::sqrt(sq(sq(1 - r0)) + 4 * sq(r0 * t)) - sq(1 - r0)) / (2 * sq(r0) * t), 1e-12);
    }
}

TEST(GlazingCurve, PaneCurveWithin1e5OfTheClosedForm) {
    // The hardest panes absorb little: their internal reflections turn sharply near grazing.
    for (double n : {1.2, 1.52, 2.2, 3.0})
        for (double fraction : {0.05, 0.5, 0.9, 0.97, 0.99, 0.999, 1.0}) {
            const double t = fraction * max_pane_transmittance(n);
            const GlazingCurve curve = pane_curve(t, n);
            const double tau0 = pane_transmissivity(t, n);
            double worst = 0.0;
            for (int i = 0; i <= 100000; ++i) {
                const double c = i / 100000.0;
                const PaneOptics want = pane_optics(c, n, tau0), got = curve.at(c);
                worst = std::max({worst, std::abs(got.reflectance - want.reflectance),
                                  std::abs(got.transmittance - want.transmittance)});
            }
            EXPECT_LT(worst, 1e-5) << "n " << n << " T " << t;
            std::cout << "[glazing] n " << n << " T " << t << ": curve vs closed form, worst " << worst << "\n";
        }
}

// CIE 171:2006, test case 5.5: the directional transmittance of 6 mm clear glass as the
// report gives it, a fifth-order polynomial in cos(theta) (from Tregenza and Sharples'
// daylight algorithms); the report's own table was not available, so the reference values
// are this formula's. At normal incidence it gives 0.87881, the glass's T_n.
double cie171_clear_glass(double cos_t) {
    const double c = cos_t;
    return -0.028378 + c * (3.156075 + c * (-3.058376 + c * (-1.428919 + c * (4.014235 + c * -1.775827))));
}

TEST(GlazingCurve, Cie171TestCase55WithinHalfAPercent) {
    const double t_normal = cie171_clear_glass(1.0);
    const GlazingCurve pane = pane_curve(t_normal, 1.52);
    for (int deg = 0; deg <= 75; deg += 5) {
        const double c = std::cos(deg * kDeg);
        const double want = cie171_clear_glass(c), got = pane.at(c).transmittance;
        EXPECT_NEAR(got / want, 1.0, 0.005) << deg << " deg: luxtrace " << got << ", CIE 171 " << want;
        std::printf("[glazing] CIE 171 5.5 %2d deg: published %.5f luxtrace %.5f difference %+.3f %%\n", deg, want, got,
                    100.0 * (got / want - 1.0));
    }
}

TEST(GlazingCurve, TableIsLinearInCosineAndHeldBeyondItsEnds) {
    const GlazingTable t{{10, 40, 60, 80}, {0.80, 0.78, 0.70, 0.40}, {0.08, 0.09, 0.12, 0.30}};
    const GlazingCurve c = table_curve(t);
    for (std::size_t i = 0; i < 4; ++i) {
        const PaneOptics o = c.at(std::cos(t.angles_deg[i] * kDeg));
        EXPECT_NEAR(o.transmittance, t.transmittance[i], 1e-15);
        EXPECT_NEAR(o.reflectance, t.reflectance[i], 1e-15);
    }
    // Halfway in cos(theta) between 40 and 60 degrees.
    const double mid = 0.5 * (std::cos(40 * kDeg) + std::cos(60 * kDeg));
    EXPECT_NEAR(c.at(mid).transmittance, 0.74, 1e-14);
    EXPECT_NEAR(c.at(mid).reflectance, 0.105, 1e-14);
    EXPECT_NEAR(c.at(1.0).transmittance, 0.80, 1e-15);   // 0 deg: the 10-degree entry
    EXPECT_NEAR(c.at(0.0).reflectance, 0.30, 1e-15);     // 90 deg: the 80-degree entry
    EXPECT_NEAR(c.at(-0.5).transmittance, 0.40, 1e-15);  // clamped
}

TEST(GlazingCurve, TableErrorsNameTheKey) {
    auto key = [](const GlazingTable& t) { return check_glazing_table(t).key; };
    EXPECT_EQ(key({{0, 90}, {0.8, 0}, {0.1, 1}}), "");
    EXPECT_EQ(key({{0}, {0.8}, {0.1}}), "angles_deg");                              // one angle
    EXPECT_EQ(key({{0, 40, 30}, {0.8, 0.7, 0.6}, {0.1, 0.1, 0.1}}), "angles_deg");  // not increasing
    EXPECT_EQ(key({{0, 40, 40}, {0.8, 0.7, 0.6}, {0.1, 0.1, 0.1}}), "angles_deg");  // not strictly
    EXPECT_EQ(key({{-5, 40}, {0.8, 0.7}, {0.1, 0.1}}), "angles_deg");
    EXPECT_EQ(key({{0, 95}, {0.8, 0.7}, {0.1, 0.1}}), "angles_deg");
    EXPECT_EQ(key({{0, 40}, {0.8}, {0.1, 0.1}}), "transmittance_at");  // lengths
    EXPECT_EQ(key({{0, 40}, {0.8, 0.7}, {0.1}}), "reflectance_at");
    EXPECT_EQ(key({{0, 40}, {1.2, 0.7}, {0.0, 0.1}}), "transmittance_at");  // outside [0, 1]
    EXPECT_EQ(key({{0, 40}, {0.8, 0.7}, {0.1, -0.1}}), "reflectance_at");
    EXPECT_EQ(key({{0, 40}, {0.8, 0.7}, {0.1, 0.4}}), "transmittance_at");  // T + R > 1
    EXPECT_THROW(table_curve({{0, 40, 30}, {0.8, 0.7, 0.6}, {0.1, 0.1, 0.1}}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------
// Sampling: the tracer's events against R and T.

Material glazing_material(double t, double n) {
    Material m;
    m.name = "pane";
    m.type = MaterialType::glazing;
    m.ior = n;
    m.transmittance = {t};
    m.glazing = std::make_shared<std::vector<GlazingCurve>>(1, pane_curve(t, n));
    return m;
}

TEST(GlazingScatter, EventFrequenciesMatchRAndT) {
    const Material m = glazing_material(0.75, 1.52);
    const ScatterModel model = scatter_model(m, 0);
    const Vec3 ng = glm::normalize(Vec3(0.2, -0.3, 1.0));
    const Vec3 t = glm::normalize(glm::cross(ng, Vec3(1, 0, 0)));
    constexpr int kN = 200000;
    // Pearson's chi-square over {reflected, transmitted, absorbed}: 2 degrees of freedom,
    // exceeded with probability exp(-x / 2); 23.0 is p = 1e-5 for each of the 10 cases.
    constexpr double kChi2Max = 23.0;
    std::uint64_t seed = 7;
    for (double deg : {0.0, 30.0, 60.0, 75.0, 85.0})
        for (bool front : {true, false}) {
            const Vec3 n_in = front ? ng : -ng;
            const Vec3 dir = -std::cos(deg * kDeg) * n_in + std::sin(deg * kDeg) * t;
            const PaneOptics want = m.glazing->front().at(std::cos(deg * kDeg));
            std::array<double, 3> count{};
            PhiloxSampler s(seed++);
            for (int k = 0; k < kN; ++k) {
                s.start_photon(static_cast<std::uint64_t>(k));
                const double u = s.next(), u1 = s.next(), u2 = s.next();
                const Scattered r = scatter(model, dir, ng, u, u1, u2);
                if (r.event == ScatterEvent::specular_reflection) {
                    ++count[0];
                    EXPECT_EQ(r.side, 1);
                    EXPECT_NEAR(glm::length(r.direction - (dir - 2.0 * glm::dot(dir, n_in) * n_in)), 0.0, 1e-14);
                } else if (r.event == ScatterEvent::specular_transmission) {
                    ++count[1];
                    EXPECT_EQ(r.side, -1);
                    EXPECT_EQ(r.direction, dir);  // a thin pane: straight through
                } else {
                    ASSERT_EQ(r.event, ScatterEvent::absorbed);
                    ++count[2];
                }
            }
            const std::array<double, 3> p{want.reflectance, want.transmittance,
                                          1.0 - want.reflectance - want.transmittance};
            double chi2 = 0.0;
            for (int i = 0; i < 3; ++i) chi2 += sq(count[i] - kN * p[i]) / (kN * p[i]);
            EXPECT_LT(chi2, kChi2Max) << deg << " deg, " << (front ? "front" : "back") << ": R " << count[0] / kN
                                      << " (want " << p[0] << "), T " << count[1] / kN << " (want " << p[1] << ")";
        }
    // Both sides alike, and albedo is R + T at normal incidence.
    EXPECT_NEAR(albedo(m, 0), 0.75 + pane_optics(1.0, 1.52, pane_transmissivity(0.75, 1.52)).reflectance, 1e-12);
}

// ---------------------------------------------------------------------------------
// The scene file: [[material]] type = "glazing".

using test_support::Loader;

const std::string kPaneRest = "[[shape]]\ntype = \"rectangle\"\nsize = [1, 1]\nmaterial = \"pane\"\n" +
                              test_support::kLamp;

TEST_F(Loader, GlazingByTransmittanceAndByTable) {
    const Scene s = load("[scene]\nbands = [\"R\", \"G\", \"B\"]\n"
                         "[[material]]\nname = \"pane\"\ntype = \"glazing\"\ntransmittance = [0.8, 0.85, 0.7]\n"
                         "refractive_index = 1.5\n"
                         "[[material]]\nname = \"maker\"\ntype = \"glazing\"\nangles_deg = [0, 45, 90]\n"
                         "transmittance_at = [0.8, 0.7, 0]\nreflectance_at = [0.08, 0.1, 1]\n" +
                         kPaneRest);
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& a = s.materials[0];
    EXPECT_EQ(a.type, MaterialType::glazing);
    EXPECT_EQ(a.ior, 1.5);
    ASSERT_TRUE(a.glazing);
    ASSERT_EQ(a.glazing->size(), 3u);
    EXPECT_NEAR((*a.glazing)[1].at(1.0).transmittance, 0.85, 1e-12);
    const Material& b = s.materials[1];
    ASSERT_TRUE(b.glazing);
    EXPECT_NEAR((*b.glazing)[2].at(std::cos(45 * kDeg)).transmittance, 0.7, 1e-15);
    // The default index is 1.52.
    const Scene d = load("[[material]]\nname = \"pane\"\ntype = \"glazing\"\ntransmittance = 0.8\n" + kPaneRest);
    EXPECT_EQ(d.materials[0].ior, 1.52);
}

TEST_F(Loader, GlazingBadInput) {
    const std::string head = "[[material]]\nname = \"pane\"\ntype = \"glazing\"\n";
    expect_bad(head + kPaneRest, "", {"needs 'transmittance'"});
    expect_bad(head + "transmittance = 0\n" + kPaneRest, "transmittance = 0", {"'transmittance'", "(0, 1)"});
    expect_bad(head + "transmittance = 1\n" + kPaneRest, "transmittance = 1", {"'transmittance'", "(0, 1)"});
    expect_bad(head + "transmittance = 1.2\n" + kPaneRest, "transmittance = 1.2", {"'transmittance'"});
    expect_bad(head + "transmittance = 0.93\n" + kPaneRest, "transmittance = 0.93",
               {"'transmittance'", "more than a pane"});
    expect_bad(head + "transmittance = 0.8\nrefractive_index = 1.1\n" + kPaneRest, "refractive_index",
               {"'refractive_index'", "[1.2, 3]"});
    expect_bad(head + "transmittance = 0.8\nrefractive_index = 5\n" + kPaneRest, "refractive_index",
               {"'refractive_index'"});
    // A pane given by a table, its three columns as TOML arrays.
    auto pane = [&](const std::string& angles, const std::string& t, const std::string& r) {
        return head + "angles_deg = " + angles + "\ntransmittance_at = " + t + "\nreflectance_at = " + r + "\n" +
               kPaneRest;
    };
    const std::string table = "angles_deg = [0, 40, 60]\ntransmittance_at = [0.8, 0.75, 0.6]\n"
                              "reflectance_at = [0.08, 0.09, 0.15]\n";
    expect_bad(head + "transmittance = 0.8\n" + table + kPaneRest, "transmittance = 0.8",
               {"'transmittance'", "not both"});
    const std::string t = "[0.8, 0.75, 0.6]", r = "[0.08, 0.09, 0.15]";
    expect_bad(pane("[0, 60, 40]", t, r), "angles_deg", {"'angles_deg'", "increase"});
    expect_bad(pane("[0, 40, 100]", t, r), "angles_deg", {"'angles_deg'", "[0, 90]"});
    expect_bad(pane("[0, 40, 60]", "[0.8, 0.75, 1.6]", r), "transmittance_at", {"'transmittance_at'", "[0, 1]"});
    expect_bad(pane("[0, 40, 60]", t, "[0.08, 0.3, 0.15]"), "transmittance_at", {"'transmittance_at'", "> 1"});
    expect_bad(pane("[0, 40, 60]", "[0.8, 0.75]", r), "transmittance_at",
               {"'transmittance_at'", "2 values for 3 angles"});
    expect_bad(head + "angles_deg = [0, 40, 60]\ntransmittance_at = [0.8, 0.75, 0.6]\n" + kPaneRest, "",
               {"reflectance_at"});
    expect_bad(head + table + "refractive_index = 1.5\n" + kPaneRest, "refractive_index", {"'refractive_index'"});
}

// ---------------------------------------------------------------------------------
// Whole runs: a parallel beam of E_n = 1000 lx at incidence theta through a 6 m x 6 m
// pane at z = 1 (T_n = 0.8, n = 1.52) onto a horizontal illuminance detector 0.5 m below,
// wholly in the pane's shadow. What the pane reflects goes up and escapes; nothing else is
// in the scene, so the detector reads E_n cos(theta) T(theta).
TEST(GlazingRun, BeamThroughAPaneReadsECosThetaT) {
    constexpr double kEn = 1000.0, kTn = 0.8, kIor = 1.52;
    const double tau0 = pane_transmissivity(kTn, kIor);
    test_support::ScratchDir dir("glazing_run");
    std::uint64_t seed = 101;
    for (double deg : {0.0, 45.0, 70.0}) {
        const double th = deg * kDeg;
        const fs::path scene = dir.path() / "pane.toml", out = dir.path() / "pane.h5";
        std::ofstream(scene) << "[[material]]\nname = \"pane\"\ntype = \"glazing\"\ntransmittance = " << kTn
                             << "\nrefractive_index = " << kIor
                             << "\n[[shape]]\ntype = \"rectangle\"\ncenter = [0, 0, 1]\nsize = [6, 6]\n"
                                "material = \"pane\"\n[[light]]\ntype = \"directional\"\ndirection = ["
                             << std::sin(th) << ", 0, " << -std::cos(th) << "]\nilluminance_lx = " << kEn
                             << "\n[[detector]]\nname = \"below\"\ntype = \"illuminance\"\ncenter = [0, 0, 0.5]\n"
                                "normal = [0, 0, 1]\nup = [0, 1, 0]\nsize = [1, 1]\ncells = [2, 2]\n";
        const auto r = test_support::run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                                  "\" --quiet --threads 2 --photons 3000000 --seed " +
                                                  std::to_string(seed++));
        ASSERT_EQ(r.code, 0) << r.out;
        const ResultReader res(out);
        const double value = res.attr_f64("/detectors/below", "mean_value");
        const double sigma = res.attr_f64("/detectors/below", "mean_sigma_rel") * value;
        const double want = kEn * std::cos(th) * pane_optics(std::cos(th), kIor, tau0).transmittance;
        EXPECT_LT(std::abs(value - want), 4.0 * sigma) << deg << " deg: " << value << " lx, want " << want;
        std::cout << "[glazing] beam at " << deg << " deg: " << value << " lx +- " << sigma << ", E cos T = " << want
                  << " (z " << (value - want) / sigma << ")\n";
    }
}

}  // namespace
}  // namespace luxtrace
