// Daylight factors and EN 17037's daylight-factor method (stats/daylight_metrics.hpp): the
// quantile's definition, the verdict rule, the parametric bootstrap's error and bias against
// many synthetic noisy grids, and (end to end) against the scatter of real runs over seeds
// and the exact cell values of an analytic scene (docs/DAYLIGHT.md "Daylight factor and
// EN 17037", calibration).
#include "luxtrace/stats/daylight_metrics.hpp"
#include "app/result_summary.hpp"
#include "luxtrace/core/math.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/simulation.hpp"
#include "luxtrace/scene/scene.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct MeanSd {
    double mean = 0.0, sd = 0.0;
};
MeanSd mean_sd(const std::vector<double>& x) {
    MeanSd m;
    for (double v : x) m.mean += v;
    m.mean /= x.size();
    for (double v : x) m.sd += (v - m.mean) * (v - m.mean);
    m.sd = std::sqrt(m.sd / (x.size() - 1));
    return m;
}

// "Exceeded over a share f of the cells": at least ceil(f K) cells reach it and fewer than
// ceil(f K) exceed it, for any K and any order of the cells.
TEST(ExceededOver, AtLeastTheShareReachesItAndFewerExceedIt) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 10.0);
    for (int k : {1, 2, 3, 7, 20, 99, 100, 101, 1000})
        for (double f : {0.5, 0.95}) {
            std::vector<double> x(k);
            for (double& v : x) v = u(rng);
            const double q = exceeded_over(x, f);
            const auto need = static_cast<long>(std::ceil(f * k - 1e-9));
            const long reach = std::count_if(x.begin(), x.end(), [&](double v) { return v >= q; });
            const long exceed = std::count_if(x.begin(), x.end(), [&](double v) { return v > q; });
            EXPECT_GE(reach, need) << k << " cells, share " << f;
            EXPECT_LT(exceed, need) << k << " cells, share " << f;
        }
    // 1..100: 50 cells reach 51 (51..100), 95 cells reach 6.
    std::vector<double> x(100);
    for (int i = 0; i < 100; ++i) x[i] = 100 - i;
    EXPECT_EQ(exceeded_over(x, 0.5), 51.0);
    EXPECT_EQ(exceeded_over(x, 0.95), 6.0);
}

// Exact cells (sigma 0): the quantile has no error and no bias, and the verdicts follow the
// plain comparison, equality passing (EN 17037: "at least").
TEST(DaylightAreaMetrics, ExactCellsDecideByComparison) {
    std::vector<double> df(100), sigma(100, 0.0);
    for (int i = 0; i < 100; ++i) df[i] = 0.05 * (i + 1);  // 0.05 .. 5 %
    const En17037Targets t{2.55, 0.3};
    const DaylightAreaMetrics m = daylight_area_metrics(df, sigma, 10, TaskArea{"", 0, 10, 0, 10}, &t);
    EXPECT_EQ(m.cells, 100u);
    EXPECT_DOUBLE_EQ(m.median.value, 0.05 * 51);
    EXPECT_DOUBLE_EQ(m.df_95.value, 0.05 * 6);
    EXPECT_EQ(m.median.sigma, 0.0);
    EXPECT_EQ(m.median.bias, 0.0);
    EXPECT_EQ(m.target_verdict.verdict, Verdict::pass);   // 2.55 >= 2.55
    EXPECT_EQ(m.minimum_verdict.verdict, Verdict::pass);  // 0.30 >= 0.3
    EXPECT_EQ(m.overall, Verdict::pass);
    const En17037Targets high{2.6, 0.3};
    const DaylightAreaMetrics f = daylight_area_metrics(df, sigma, 10, TaskArea{"", 0, 10, 0, 10}, &high);
    EXPECT_EQ(f.target_verdict.verdict, Verdict::fail);
    EXPECT_EQ(f.overall, Verdict::fail);
    // A task area: cells 0 <= i < 5 of rows 0 and 1 (df 0.05..0.25 and 0.55..0.75).
    const DaylightAreaMetrics a = daylight_area_metrics(df, sigma, 10, TaskArea{"a", 0, 5, 0, 2}, nullptr);
    EXPECT_EQ(a.cells, 10u);
    EXPECT_FALSE(a.has_targets);
    EXPECT_DOUBLE_EQ(a.median.value, 0.55);
    EXPECT_DOUBLE_EQ(a.df_95.value, 0.05);
    EXPECT_NEAR(a.mean_df, 0.4, 1e-12);
}

// The one-sided 95 % rule and the photons that would decide: with the uncertainty shrunk
// by the reported factor (sigma ~ 1/sqrt(N)) the same value is decided, a little less is not.
TEST(Verdict, PassFailUndecidedAndThePhotonsToDecide) {
    EXPECT_EQ(judge({2.5, 0.1, 0.0}, 2.0).verdict, Verdict::pass);
    EXPECT_EQ(judge({1.5, 0.1, 0.0}, 2.0).verdict, Verdict::fail);
    // The bias-corrected value is judged, with the bias in the uncertainty: 2.3 observed,
    // biased +0.25, is 2.05 +- hypot(0.1, 0.25).
    EXPECT_EQ(judge({2.3, 0.0, 0.25}, 2.0).verdict, Verdict::undecided);
    EXPECT_EQ(judge({2.3, 0.0, 0.02}, 2.0).verdict, Verdict::pass);
    const CriterionVerdict u = judge({2.1, 0.1, 0.0}, 2.0);
    EXPECT_EQ(u.verdict, Verdict::undecided);
    EXPECT_NEAR(u.photons_factor, std::pow(kVerdictSigmas * 0.1 / 0.1, 2), 1e-9);
    EXPECT_EQ(judge({2.1, 0.1 / std::sqrt(u.photons_factor * 1.001), 0.0}, 2.0).verdict, Verdict::pass);
    EXPECT_EQ(judge({2.1, 0.1 / std::sqrt(u.photons_factor * 0.999), 0.0}, 2.0).verdict, Verdict::undecided);
    EXPECT_EQ(judge({1.9, 0.1 / std::sqrt(u.photons_factor * 1.001), 0.0}, 2.0).verdict, Verdict::fail);
    EXPECT_NEAR(judge({2.3, 0.1, 0.25}, 2.0).photons_factor, std::pow(kVerdictSigmas * std::hypot(0.1, 0.25) / 0.05, 2),
                1e-9);
    EXPECT_NE(decide_hint(u, {2.1, 0.1, 0.0}, 2.0).find("x the photons"), std::string::npos);
    // On the target: no number of photons decides.
    const CriterionVerdict tie = judge({2.0, 0.1, 0.0}, 2.0);
    EXPECT_EQ(tie.verdict, Verdict::undecided);
    EXPECT_TRUE(std::isinf(tie.photons_factor));
    EXPECT_NE(decide_hint(tie, {2.0, 0.1, 0.0}, 2.0).find("cannot decide"), std::string::npos);
    // Overall: a failed criterion fails; an undecided one leaves it undecided with its factor.
    std::vector<double> df{1.0, 2.0, 3.0, 4.0}, sigma{0.0, 0.5, 0.0, 0.0};
    const En17037Targets t{2.5, 0.5};
    const DaylightAreaMetrics m = daylight_area_metrics(df, sigma, 4, TaskArea{"", 0, 4, 0, 1}, &t);
    EXPECT_EQ(m.minimum_verdict.verdict, Verdict::pass);
    EXPECT_EQ(m.overall, m.target_verdict.verdict);
    if (m.overall == Verdict::undecided) {
        EXPECT_EQ(m.overall_photons_factor, m.target_verdict.photons_factor);
    }
}

// DF = 100 E / E_h,ext, its sigma scaled the same; a cell without photons keeps NaN and is
// counted.
TEST(DaylightEstimate, ScalesTheMapAndCountsEmptyCells) {
    Detector d;
    d.nx = 2, d.ny = 2;
    d.task_areas.push_back(TaskArea{"left", 0, 1, 0, 2});
    const std::vector<double> e{100.0, 200.0, 0.0, 400.0}, s{1.0, 2.0, kNaN, 4.0};
    const DaylightEstimate est = estimate_daylight(d, e, s, 10000.0);
    EXPECT_EQ(est.reference_lx, 10000.0);
    EXPECT_DOUBLE_EQ(est.df[1], 2.0);
    EXPECT_DOUBLE_EQ(est.df_sigma[3], 0.04);
    EXPECT_TRUE(std::isnan(est.df_sigma[2]));
    ASSERT_EQ(est.areas.size(), 2u);
    EXPECT_EQ(est.areas[0].cells_without_photons, 1u);
    EXPECT_EQ(est.areas[1].area, "left");
    EXPECT_EQ(est.areas[1].cells, 2u);
    EXPECT_FALSE(est.areas[0].has_targets);
}

// The bootstrap is deterministic: the same cells give the same figures bit for bit.
TEST(NoisyQuantile, Deterministic) {
    std::vector<double> v(300), s(300);
    for (int i = 0; i < 300; ++i) v[i] = std::sin(0.1 * i) + 2.0, s[i] = 0.05 + 0.001 * i;
    const QuantileEstimate a = noisy_quantile(v, s, 0.95), b = noisy_quantile(v, s, 0.95);
    EXPECT_EQ(a.sigma, b.sigma);
    EXPECT_EQ(a.bias, b.bias);
}

// Many independent noisy grids of known true cells t_c, each cell observed with a relative
// error of 15 % (a short run), its sigma estimated from its own observed value as a run's
// is. The reported sigma must match the quantiles' scatter over the grids; the
// bias-corrected quantiles must centre on the true ones to within the reported bias (the
// correction is good to its own size, which the verdict's uncertainty therefore holds);
// and with the target set at the true value the verdict must decide wrongly, either way,
// in no more than 5 % of the grids (95 % one-sided), up to the draws' own scatter.
struct Calibration {
    double true_q, raw_mean, raw_sd, corrected_mean, corrected_sd, reported_sigma, reported_bias;
    // With the target at the true value, the share of draws the verdict wrongly decides.
    double false_pass, false_fail;
};
Calibration calibrate(const std::vector<double>& truth, double fraction, int draws, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> z(0.0, 1.0);
    const double true_q = exceeded_over(truth, fraction);
    double false_pass = 0.0, false_fail = 0.0;
    std::vector<double> raw, corrected, reported, bias;
    for (int r = 0; r < draws; ++r) {
        std::vector<double> x(truth.size()), s(truth.size());
        for (std::size_t c = 0; c < x.size(); ++c) x[c] = truth[c] * (1.0 + 0.15 * z(rng));
        for (std::size_t c = 0; c < x.size(); ++c) s[c] = 0.15 * std::max(x[c], 0.0);
        const QuantileEstimate q = noisy_quantile(x, s, fraction);
        const Verdict v = judge(q, true_q).verdict;
        false_pass += v == Verdict::pass ? 1.0 / draws : 0.0;
        false_fail += v == Verdict::fail ? 1.0 / draws : 0.0;
        bias.push_back(q.bias);
        raw.push_back(q.value);
        corrected.push_back(q.corrected());
        reported.push_back(q.sigma);
    }
    const MeanSd r = mean_sd(raw), c = mean_sd(corrected), s = mean_sd(reported), b = mean_sd(bias);
    return {true_q, r.mean, r.sd, c.mean, c.sd, s.mean, b.mean, false_pass, false_fail};
}

// A side-lit room's DF falls with depth, 8 exp(-depth / 1.2 m) %, over 12 x 30 cells.
TEST(NoisyQuantile, CalibratedOnSyntheticGrids) {
    const int nx = 12, ny = 30, draws = 200;
    // Smooth: each cell at its own depth (distinct, evenly spread values).
    std::vector<double> smooth(nx * ny), rows(nx * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            smooth[j * nx + i] = 8.0 * std::exp(-0.1 * (j + (i + 0.5) / nx) / 1.2);
            // Rows: the cells of a row share a depth, +-10 % across the room.
            rows[j * nx + i] = 8.0 * std::exp(-0.1 * (j + 0.5) / 1.2) * (1.0 + 0.1 * std::cos(0.8 * i));
        }
    for (const auto& [name, truth] : {std::pair{"smooth", &smooth}, std::pair{"rows", &rows}})
        for (double f : {0.5, 0.95}) {
            const Calibration c = calibrate(*truth, f, draws, 2026);
            std::cout << "[daylight] " << name << ", share " << f << ": true " << c.true_q << ", raw mean "
                      << c.raw_mean << " (bias " << c.raw_mean - c.true_q << ", reported " << c.reported_bias
                      << "), corrected mean " << c.corrected_mean << ", scatter " << c.raw_sd << ", reported sigma "
                      << c.reported_sigma << ", corrected sd " << c.corrected_sd << ", wrong verdicts " << c.false_pass
                      << " pass / " << c.false_fail << " fail\n";
            // The sd of 200 draws is itself known to 5 %; the bootstrap's own to 3.5 %.
            EXPECT_NEAR(c.reported_sigma / c.raw_sd, 1.0, 0.15) << name << ' ' << f;
            const double se = 3.0 * c.corrected_sd / std::sqrt(draws);
            EXPECT_LT(std::abs(c.corrected_mean - c.true_q), se + std::abs(c.reported_bias)) << name << ' ' << f;
            // 5 % of 200 draws is 10 +- 3.1: 10 % is 3 of their sigmas above.
            EXPECT_LE(c.false_pass, 0.10) << name << ' ' << f;
            EXPECT_LE(c.false_fail, 0.10) << name << ' ' << f;
        }
    // The 95 % value's bias is real (noise widens the distribution downward) and corrected.
    const Calibration c = calibrate(smooth, 0.95, draws, 7);
    EXPECT_LT(c.raw_mean, c.true_q - 5.0 * c.raw_sd / std::sqrt(draws));
    EXPECT_LT(std::abs(c.corrected_mean - c.true_q), std::abs(c.raw_mean - c.true_q));
}

// E_h,ext of a run is the sum over its lights, of a light scene the weighted sum over its
// groups.
TEST(DaylightReference, SumsTheLightsWeightedByTheirGroups) {
    Scene scene;
    std::vector<Light> lights(3);
    lights[0].unobstructed_horizontal_lx = 8000.0, lights[0].group = 0;  // sky
    lights[1].unobstructed_horizontal_lx = 2000.0, lights[1].group = 0;  // sun
    lights[2].group = 1;                                                 // electric: 0
    for (Light& l : lights) l.flux_lm = 1.0;
    scene.lights = LightSet(lights);
    scene.light_groups = {"daylight", "lamps"};
    EXPECT_DOUBLE_EQ(daylight_reference_lx(estimate_scene(scene), {}), 10000.0);
    const std::vector<double> half{0.5, 1.0}, off{0.0, 1.0};
    EXPECT_DOUBLE_EQ(daylight_reference_lx(estimate_scene(scene), half), 5000.0);
    EXPECT_EQ(daylight_reference_lx(estimate_scene(scene), off), 0.0);
}

#ifdef LUXTRACE_BINARY
// Real runs standing in for a sky: an isotropic point source over a black floor (the DF
// map of a sky would be as spread). The reference illuminance is any fixed number here
// (DF / E is exact); the statistics are those of a daylight run. Over several seeds of a
// short run the reported sigma of the median and the 95 % value matches their scatter, and
// the bias-corrected values agree with the exact cell averages.
TEST(DaylightMetricsEndToEnd, SigmaMatchesSeedScatterAndCorrectedQuantilesTheTruth) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_daylight_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path scene = dir / "floor.toml";
    const int n = 20;
    {
        std::ofstream s(scene);
        s << "[[material]]\nname = \"floor\"\ntype = \"black\"\n"
             "[[shape]]\ntype = \"rectangle\"\nsize = [6, 6]\nmaterial = \"floor\"\n"
             "[[light]]\ntype = \"point\"\nposition = [0, 0, 2]\nflux_lm = 1000\n"
             "[[detector]]\nname = \"floor\"\ncenter = [0, 0, 0]\nsize = [4, 4]\ncells = ["
          << n << ", " << n << "]\n";
    }
    // Exact cell averages of E = I h / r^3, 8 x 8 midpoint rule per cell.
    const double I = 1000.0 / (4.0 * kPi), h = 2.0, d = 4.0 / n, reference_lx = 100.0;
    std::vector<double> truth(n * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double sum = 0.0;
            for (int b = 0; b < 8; ++b)
                for (int a = 0; a < 8; ++a) {
                    const double x = -2.0 + (i + (a + 0.5) / 8) * d, y = -2.0 + (j + (b + 0.5) / 8) * d;
                    sum += I * h / std::pow(x * x + y * y + h * h, 1.5);
                }
            truth[j * n + i] = 100.0 * sum / 64.0 / reference_lx;
        }
    Detector det;
    det.nx = det.ny = n;
    const int seeds = 16;
    std::vector<double> median, df95, median_sigma, df95_sigma, median_corr, df95_corr;
    for (int seed = 1; seed <= seeds; ++seed) {
        const fs::path out = dir / (std::to_string(seed) + ".h5");  // no literal prefix: GCC 12 -Wrestrict
        const auto run = test_support::run_luxtrace("run " + scene.string() + " --output " + out.string() +
                                                    " --photons 200k --seed " + std::to_string(seed) +
                                                    " --threads 2 --quiet");
        ASSERT_EQ(run.code, 0) << run.out;
        const DetectorData data = ResultFile(out).detector("floor");
        ASSERT_EQ(data.bands, 1u);
        std::vector<double> s(data.value.size());
        for (std::size_t c = 0; c < s.size(); ++c) s[c] = data.value[c] * data.sigma_rel[c];
        const DaylightEstimate e = estimate_daylight(det, data.value, s, reference_lx);
        const DaylightAreaMetrics& m = e.areas.front();
        median.push_back(m.median.value), df95.push_back(m.df_95.value);
        median_sigma.push_back(m.median.sigma), df95_sigma.push_back(m.df_95.sigma);
        median_corr.push_back(m.median.corrected()), df95_corr.push_back(m.df_95.corrected());
    }
    auto check = [&](const char* what, const std::vector<double>& v, const std::vector<double>& sig,
                     const std::vector<double>& corr, double fraction) {
        const double true_q = exceeded_over(truth, fraction);
        const MeanSd raw = mean_sd(v), s = mean_sd(sig), c = mean_sd(corr);
        std::cout << "[daylight] " << what << ": true " << true_q << " %, raw " << raw.mean << " (scatter " << raw.sd
                  << " over " << seeds << " seeds), reported sigma " << s.mean << ", corrected " << c.mean << '\n';
        // The sd of 16 seeds over the true sigma lies in 0.55 to 1.48 at 99 % (chi, 15 dof).
        EXPECT_GT(s.mean / raw.sd, 1.0 / 1.48 - 0.03) << what;
        EXPECT_LT(s.mean / raw.sd, 1.0 / 0.55 + 0.03) << what;
        // Within 3 standard errors of the seeds' mean plus the correction's own size.
        EXPECT_LT(std::abs(c.mean - true_q), 3.0 * s.mean / std::sqrt(seeds) + std::abs(raw.mean - c.mean)) << what;
    };
    check("median", median, median_sigma, median_corr, 0.5);
    check("95 %", df95, df95_sigma, df95_corr, 0.95);
    fs::remove_all(dir);
}

// Under a real sky (the traditional overcast sky, type 16) an unobstructed horizontal grid
// above a black floor reads DF = 100 % in every cell: E_h,ext is the sky's own horizontal
// illuminance. The run, the result and `luxtrace info` agree.
TEST(DaylightMetricsEndToEnd, UnobstructedGridUnderTheOvercastSkyReadsOneHundredPercent) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_daylight_sky_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path scene = dir / "sky.toml", out = dir / "sky.h5";
    std::ofstream(scene) << "[[material]]\nname = \"floor\"\ntype = \"black\"\n"
                            "[[shape]]\ntype = \"rectangle\"\nsize = [4, 4]\nmaterial = \"floor\"\n"
                            "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = 8000\n"
                            "[[detector]]\nname = \"open\"\ncenter = [0, 0, 0.5]\nsize = [2, 2]\ncells = [4, 4]\n"
                            "en17037 = { target_df = 90, minimum_df = 80 }\n";
    const auto run = test_support::run_luxtrace("run " + scene.string() + " --output " + out.string() +
                                                " --photons 400k --threads 2 --quiet");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultFile result(out);
    const DetectorData d = result.detector("open");
    EXPECT_EQ(d.daylight_reference_lx, 8000.0);
    const ResultReader& r = result.raw();
    const double mean = r.attr_f64("/detectors/open", "DF_mean_pct");
    const double sigma = r.attr_f64("/detectors/open", "DF_mean_sigma_pct");
    std::cout << "[daylight] open grid under CIE 16: DF mean " << mean << " +- " << sigma << " %\n";
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(mean - 100.0), 4.0 * sigma);
    for (std::size_t c = 0; c < d.daylight_factor_pct.size(); ++c)
        EXPECT_LT(std::abs(d.daylight_factor_pct[c] - 100.0), 5.0 * d.daylight_factor_sigma_pct[c]) << c;
    EXPECT_EQ(r.attr_str("/detectors/open", "en17037_verdict"), "pass");
    const auto info = test_support::run_luxtrace("info " + out.string());
    EXPECT_EQ(info.code, 0);
    for (const char* s : {"E_h,ext 8000.0 lx", "DF mean", "verdict pass"})
        EXPECT_NE(info.out.find(s), std::string::npos) << s << " not in:\n" << info.out;
    fs::remove_all(dir);
}

// A daylight_factor detector through the whole run: the scene's light stands in for the
// sky with its E_h,ext set by hand (the sky light's loader sets it), a lamp in a second
// group is electric. The result holds DF = 100 E / E_h,ext per cell, the figures with
// verdicts on the grid and its task area, each light scene's DF against its own weighted
// E_h,ext (none where the daylight is off), and `info` prints them.
TEST(DaylightMetricsEndToEnd, ResultAndSummaryOfADaylightFactorDetector) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_daylight_run_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path file = dir / "scene.toml";
    std::ofstream(file) << "[[material]]\nname = \"floor\"\ntype = \"black\"\n"
                           "[[shape]]\ntype = \"rectangle\"\nsize = [6, 6]\nmaterial = \"floor\"\n"
                           "[[light]]\ntype = \"point\"\nposition = [0, 0, 2]\nflux_lm = 1000\ngroup = \"sky\"\n"
                           "[[light]]\ntype = \"point\"\nposition = [1, 0, 2]\nflux_lm = 200\ngroup = \"lamp\"\n"
                           "[[light_scene]]\nname = \"daylight\"\ndimming = { sky = 1 }\n"
                           "[[light_scene]]\nname = \"half\"\ndimming = { sky = 0.5, lamp = 1 }\n"
                           "[[light_scene]]\nname = \"night\"\ndimming = { lamp = 1 }\n"
                           "[[detector]]\nname = \"floor\"\ncenter = [0, 0, 0]\nsize = [4, 4]\ncells = [8, 8]\n"
                           "[[detector.task_area]]\nname = \"desk\"\ncells = [0, 4, 0, 4]\n"
                           "[run]\nphotons = 200000\n";
    Scene scene = load_scene(file);
    std::vector<Light> lights = scene.lights.lights();
    lights[0].unobstructed_horizontal_lx = 200.0;
    scene.lights = LightSet(lights);
    scene.detectors[0].daylight_factor = true;
    scene.detectors[0].en17037 = En17037Targets{1.0, 90.0};  // the 95 % value cannot reach 90 %
    scene.run.output = (dir / "r.h5").string();
    RunOptions opt;
    opt.threads = 2;
    opt.quiet = true;
    std::ostringstream log;
    static const Communicator comm(nullptr, nullptr);
    ASSERT_EQ(run_simulation(scene, comm, opt, log).exit_code, 0) << log.str();

    const ResultFile result(scene.run.output);
    const ResultReader& r = result.raw();
    const DetectorData d = result.detector("floor");
    ASSERT_EQ(d.daylight_factor_pct.size(), 64u);
    EXPECT_EQ(d.daylight_reference_lx, 200.0);
    for (std::size_t c = 0; c < 64; ++c) {
        EXPECT_NEAR(d.daylight_factor_pct[c], 100.0 * d.value[c] / 200.0, 1e-12 * d.daylight_factor_pct[c]) << c;
        EXPECT_NEAR(d.daylight_factor_sigma_pct[c], d.daylight_factor_pct[c] * d.sigma_rel[c],
                    1e-9 * d.daylight_factor_pct[c])
            << c;
    }
    const std::string g = "/detectors/floor";
    EXPECT_EQ(r.attr_str(g, "en17037_minimum_verdict"), "fail");
    EXPECT_EQ(r.attr_str(g, "en17037_verdict"), "fail");
    EXPECT_EQ(r.attr_f64(g, "en17037_target_df_pct"), 1.0);
    EXPECT_GT(r.attr_f64(g, "DF_median_pct"), r.attr_f64(g, "DF_95_pct"));
    EXPECT_GT(r.attr_f64(g, "DF_median_sigma_pct"), 0.0);
    EXPECT_NEAR(r.attr_f64(g, "DF_mean_pct"), 100.0 * r.attr_f64(g, "E_avg_lx") / 200.0, 1e-9);
    const std::string ga = g + "/task_areas/desk";
    EXPECT_EQ(r.attr_str(ga, "en17037_minimum_verdict"), "fail");
    EXPECT_NEAR(r.attr_f64(ga, "DF_mean_pct"), 100.0 * r.attr_f64(ga, "E_avg_lx") / 200.0, 1e-9);
    // Light scenes: DF against their own E_h,ext; the same light at half weight over half
    // the reference reads the same DF plus the lamp's share.
    EXPECT_EQ(r.attr_f64("/light_scenes/daylight/detectors/floor", "daylight_reference_lx"), 200.0);
    EXPECT_EQ(r.attr_f64("/light_scenes/half/detectors/floor", "daylight_reference_lx"), 100.0);
    EXPECT_GT(r.attr_f64("/light_scenes/half/detectors/floor", "DF_mean_pct"),
              r.attr_f64("/light_scenes/daylight/detectors/floor", "DF_mean_pct"));
    EXPECT_FALSE(r.has("/light_scenes/night/detectors/floor/daylight_factor"));
    EXPECT_FALSE(r.has_attr("/light_scenes/night/detectors/floor", "DF_median_pct"));
    EXPECT_TRUE(r.has_attr("/light_scenes/daylight/detectors/floor/task_areas/desk", "en17037_verdict"));

    std::ostringstream info;
    print_result_summary(result, info);
    for (const char* s : {"E_h,ext 200.0 lx", "DF mean", "median", "exceeded over 95 %", "EN 17037 D_T over 50 % 1 %",
                          "D_TM over 95 % 90 %: fail", "verdict fail"})
        EXPECT_NE(info.str().find(s), std::string::npos) << s << " not in:\n" << info.str();
    fs::remove_all(dir);
}
#endif

}  // namespace
}  // namespace luxtrace
