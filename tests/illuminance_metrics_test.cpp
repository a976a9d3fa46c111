// Illuminance metrics (include/luxtrace/stats/illuminance_metrics.hpp): hand computations,
// the expected maximum of normal cells against tables and brute force, the bias of the
// minimum of noisy cells against brute force, the coverage of U0's error over synthetic
// draws, and an end-to-end run with analytic references (docs/VALIDATION.md case 6).
#include "luxtrace/stats/illuminance_metrics.hpp"
#include "luxtrace/core/math.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// E[max of n standard normals] (tables of order statistics, e.g. Harter 1961; n = 2, 3
// in closed form: 1/sqrt(pi), 3/(2 sqrt(pi))).
TEST(ExpectedMaximum, IdenticalNormalsMatchTheTables) {
    const std::pair<int, double> table[] = {{2, 0.5641896},
                                            {3, 0.8462844},
                                            {5, 1.1629644},
                                            {10, 1.5387527},
                                            {100, 2.5075937}};
    for (const auto& [n, e] : table) {
        EXPECT_NEAR(expected_extreme_bias(std::vector<double>(n, 1.0)), e, 2e-5) << n << " cells";
        EXPECT_NEAR(expected_extreme_bias(std::vector<double>(n, 2.5)), 2.5 * e, 5e-5) << n << " cells";
        EXPECT_NEAR(expected_maximum(std::vector<double>(n, 7.0), std::vector<double>(n, 1.0)), 7.0 + e, 2e-5);
    }
    EXPECT_EQ(expected_extreme_bias(std::vector<double>{3.0}), 0.0);  // one cell: E[sigma Z] = 0
    EXPECT_EQ(expected_extreme_bias(std::vector<double>{}), 0.0);
}

TEST(ExpectedMaximum, UnequalCellsAgreeWithBruteForce) {
    // Different means and sigmas, one cell without noise (a floor under the maximum).
    const std::vector<double> mean{0.0, 0.5, 1.0, 1.2, -2.0, 0.8, 1.1};
    const std::vector<double> sigma{1.0, 0.3, 2.0, 0.1, 5.0, 0.0, 0.7};
    std::mt19937_64 rng(17);
    std::normal_distribution<double> z;
    const int n = 200000;
    double s = 0.0, s2 = 0.0;
    for (int k = 0; k < n; ++k) {
        double m = -1e300;
        for (std::size_t c = 0; c < mean.size(); ++c) m = std::max(m, mean[c] + sigma[c] * z(rng));
        s += m;
        s2 += m * m;
    }
    const double bf = s / n, se = std::sqrt((s2 / n - bf * bf) / n);
    const double e = expected_maximum(mean, sigma);
    std::cout << "[metrics] E[max] integral " << e << ", brute force " << bf << " +- " << se << '\n';
    EXPECT_LT(std::abs(e - bf), 5.0 * se);
    // Unequal sigmas of equal means: the bias bound itself, against the same integral.
    const std::vector<double> s_only{1.0, 0.3, 2.0, 0.1, 5.0, 0.7};
    EXPECT_NEAR(expected_extreme_bias(s_only), expected_maximum(std::vector<double>(6, 0.0), s_only), 1e-6);
}

// A 2 x 2 grid: row j = 0 holds 100, 200 lx, row 1 holds 300, 400 lx; sigma 1 lx each.
TEST(IlluminanceMetrics, HandComputedFigures) {
    const std::vector<double> v{100, 200, 300, 400}, s{1, 1, 1, 1};
    const IlluminanceMetrics m = illuminance_metrics(v, s, 2, TaskArea{"", 0, 2, 0, 2});
    EXPECT_EQ(m.cells, 4u);
    EXPECT_DOUBLE_EQ(m.avg_lx, 250.0);
    EXPECT_DOUBLE_EQ(m.avg_sigma_lx, 0.5);  // sqrt(4 x 1^2) / 4
    EXPECT_EQ(m.min_lx, 100.0);
    EXPECT_EQ(m.min_i, 0);
    EXPECT_EQ(m.min_j, 0);
    EXPECT_EQ(m.max_lx, 400.0);
    EXPECT_EQ(m.max_i, 1);
    EXPECT_EQ(m.max_j, 1);
    EXPECT_EQ(m.min_sigma_lx, 1.0);
    // No other cell within 3 x sqrt(2) lx of either extreme: no bias.
    EXPECT_EQ(m.min_competitors, 1u);
    EXPECT_EQ(m.max_competitors, 1u);
    EXPECT_EQ(m.min_bias_lx, 0.0);
    EXPECT_EQ(m.max_bias_lx, 0.0);
    EXPECT_DOUBLE_EQ(m.u0, 0.4);
    // (0.01^2 + 0.002^2 - 2 x 1 / (4 x 100 x 250)) = 8.4e-5
    EXPECT_NEAR(m.u0_sigma, 0.4 * std::sqrt(8.4e-5), 1e-12);
    EXPECT_DOUBLE_EQ(m.min_over_max, 0.25);
    EXPECT_NEAR(m.min_over_max_sigma, 0.25 * std::sqrt(1e-4 + 0.0025 * 0.0025), 1e-12);
    EXPECT_FALSE(m.unreliable);  // 1 lx is 1 % of Emin

    EXPECT_DOUBLE_EQ(illuminance_metrics(v, s, 2, TaskArea{"", 0, 2, 0, 2}, 0.7).avg_sigma_lx, 0.7);
    // The right column: 200 and 400 lx.
    const IlluminanceMetrics col = illuminance_metrics(v, s, 2, TaskArea{"right", 1, 2, 0, 2});
    EXPECT_EQ(col.area, "right");
    EXPECT_EQ(col.cells, 2u);
    EXPECT_DOUBLE_EQ(col.avg_lx, 300.0);
    EXPECT_DOUBLE_EQ(col.avg_sigma_lx, std::sqrt(2.0) / 2.0);
    EXPECT_EQ(col.min_lx, 200.0);
    EXPECT_EQ(col.min_i, 1);
    EXPECT_EQ(col.min_j, 0);
    EXPECT_DOUBLE_EQ(col.u0, 2.0 / 3.0);

    // Maintained: every illuminance times MF, ratios unchanged.
    const IlluminanceMetrics mt = maintained(m, 0.8);
    EXPECT_DOUBLE_EQ(mt.avg_lx, 200.0);
    EXPECT_DOUBLE_EQ(mt.avg_sigma_lx, 0.4);
    EXPECT_DOUBLE_EQ(mt.min_lx, 80.0);
    EXPECT_DOUBLE_EQ(mt.min_sigma_lx, 0.8);
    EXPECT_DOUBLE_EQ(mt.max_lx, 320.0);
    EXPECT_EQ(mt.u0, m.u0);
    EXPECT_EQ(mt.min_over_max, m.min_over_max);
}

TEST(IlluminanceMetrics, CompetingCellsAndTheWarning) {
    // Two cells 1 lx apart with sigmas 1 and 2 both compete for each extreme: the bias is
    // E[max(Z1, 2 Z2)] = sqrt(1 + 4) / sqrt(2 pi).
    const std::vector<double> v{100, 101}, s{1, 2};
    const IlluminanceMetrics m = illuminance_metrics(v, s, 2, TaskArea{"", 0, 2, 0, 1});
    EXPECT_EQ(m.min_competitors, 2u);
    EXPECT_NEAR(m.min_bias_lx, -std::sqrt(5.0 / (2.0 * kPi)), 1e-12);
    EXPECT_NEAR(m.max_bias_lx, std::sqrt(5.0 / (2.0 * kPi)), 1e-12);
    EXPECT_NEAR(m.u0_bias, m.min_bias_lx / 100.5, 1e-15);
    const double b = std::sqrt(5.0 / (2.0 * kPi));
    EXPECT_NEAR(m.min_over_max_bias, 100.0 / 101.0 - (100.0 + b) / (101.0 - b), 1e-12);
    EXPECT_FALSE(m.unreliable);  // sigma 1 % and bias 0.9 % of Emin: below 2 %
    // The warning: Emin's sigma above 2 %, its bias above 2 %, or a cell without photons.
    EXPECT_TRUE(illuminance_metrics(v, std::vector<double>{2.5, 2}, 2, TaskArea{"", 0, 2, 0, 1}).unreliable);
    // 10 equal cells of sigma 1.5 lx (1.5 %): the bias, 1.5 x 1.539 = 2.31 lx, alone passes 2 %.
    const IlluminanceMetrics ten = illuminance_metrics(std::vector<double>(10, 100.0), std::vector<double>(10, 1.5), 10,
                                                       TaskArea{"", 0, 10, 0, 1});
    EXPECT_NEAR(ten.min_bias_lx, -1.5 * 1.5387527, 1e-4);
    EXPECT_TRUE(ten.unreliable);
    EXPECT_TRUE(
        illuminance_metrics(std::vector<double>{0, 100}, std::vector<double>{kNaN, 1}, 2, TaskArea{"", 0, 2, 0, 1})
            .unreliable);
    // 100 identical cells of sigma 1 lx: bias 2.5 lx, 2.5 % of Emin, though each cell is at 1 %.
    const IlluminanceMetrics flat = illuminance_metrics(std::vector<double>(100, 100.0), std::vector<double>(100, 1.0),
                                                        10, TaskArea{"", 0, 10, 0, 10});
    EXPECT_NEAR(flat.min_bias_lx, -2.5075937, 1e-4);
    EXPECT_TRUE(flat.unreliable);
}

// A synthetic detector: true cell values mu, per-cell relative error `rel`.
struct Field {
    int nx, ny;
    std::vector<double> mu;
    double rel;
    double true_min() const { return *std::min_element(mu.begin(), mu.end()); }
    double true_avg() const {
        double s = 0.0;
        for (double m : mu) s += m;
        return s / mu.size();
    }
    // One noisy measurement: values and their estimated sigmas (rel x the measured value).
    void draw(std::mt19937_64& rng, std::vector<double>& v, std::vector<double>& s) const {
        std::normal_distribution<double> z;
        v.resize(mu.size());
        s.resize(mu.size());
        for (std::size_t c = 0; c < mu.size(); ++c) {
            v[c] = mu[c] * (1.0 + rel * z(rng));
            s[c] = rel * v[c];
        }
    }
};

Field field(int nx, int ny, double rel, double (*f)(double x, double y)) {
    Field g{nx, ny, {}, rel};
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) g.mu.push_back(f((i + 0.5) / nx, (j + 0.5) / ny));
    return g;
}

// The reported bias of Emin against the bias the minimum really has, found by brute force
// over many noisy measurements of the same field.
TEST(IlluminanceMetrics, BiasOfTheMinimumAgainstBruteForce) {
    struct Case {
        const char* name;
        Field f;
        double lo, hi;  // allowed (reported mean bias) / (true mean bias)
    };
    const Case cases[] = {
        // All cells equal: the competing cells share one value, the bias is exact.
        {"flat", field(12, 10, 0.03, [](double, double) { return 100.0; }), 0.9, 1.1},
        // Gradients: the competitors differ, the estimate is conservative (larger).
        {"gradient 20 %", field(12, 10, 0.03, [](double x, double) { return 100.0 * (1.0 + 0.2 * x); }), 1.0, 1.5},
        {"bowl",
         field(12, 10, 0.03,
               [](double x, double y) {
                   return 100.0 * (1.0 + 0.5 * ((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)));
               }),
         1.0, 1.5},
    };
    std::mt19937_64 rng(23);
    for (const Case& c : cases) {
        const int n = 400;
        double sum_err = 0.0, sum_err2 = 0.0, sum_bias = 0.0;
        std::vector<double> v, s;
        for (int k = 0; k < n; ++k) {
            c.f.draw(rng, v, s);
            const IlluminanceMetrics m = illuminance_metrics(v, s, c.f.nx, TaskArea{"", 0, c.f.nx, 0, c.f.ny});
            const double err = m.min_lx - c.f.true_min();
            sum_err += err;
            sum_err2 += err * err;
            sum_bias += m.min_bias_lx;
        }
        const double true_bias = sum_err / n, se = std::sqrt((sum_err2 / n - true_bias * true_bias) / n);
        const double reported = sum_bias / n;
        std::cout << "[metrics] " << c.name << ": true bias of Emin " << true_bias << " +- " << se << " lx, reported "
                  << reported << " lx (ratio " << reported / true_bias << ")\n";
        ASSERT_LT(true_bias + 5.0 * se, 0.0) << "the case must have a bias to measure";
        EXPECT_GT(reported / true_bias, c.lo * (1.0 - 5.0 * se / -true_bias)) << c.name;
        EXPECT_LT(reported / true_bias, c.hi * (1.0 + 5.0 * se / -true_bias)) << c.name;
    }
    // One cell far below the others: no competitor, and no bias to find.
    Field clear = field(12, 10, 0.01, [](double x, double y) { return x + y < 0.1 ? 50.0 : 100.0; });
    std::vector<double> v, s;
    double sum_err = 0.0;
    for (int k = 0; k < 400; ++k) {
        clear.draw(rng, v, s);
        const IlluminanceMetrics m = illuminance_metrics(v, s, clear.nx, TaskArea{"", 0, clear.nx, 0, clear.ny});
        EXPECT_EQ(m.min_bias_lx, 0.0);
        sum_err += m.min_lx - 50.0;
    }
    EXPECT_LT(std::abs(sum_err / 400), 5.0 * 0.5 / std::sqrt(400.0));  // sigma 0.5 lx per draw
}

// U0 +- U0_sigma covers the true U0 at the normal rates when Emin and Emax are clear, and
// the bias-corrected U0 covers it when they are not.
TEST(IlluminanceMetrics, ErrorOfU0CoversTheTrueU0) {
    // 5 x 5 cells growing by 10 % from cell to cell, 1 % noise: every extreme is clear.
    Field f{5, 5, {}, 0.01};
    for (int c = 0; c < 25; ++c) f.mu.push_back(100.0 * std::pow(1.1, c));
    const double u0_true = f.true_min() / f.true_avg(), ratio_true = f.mu.front() / f.mu.back();
    std::mt19937_64 rng(29);
    const int n = 4000;
    double z2_u0 = 0.0, z2_ratio = 0.0;
    int in1_u0 = 0, in2_u0 = 0, in1_ratio = 0;
    std::vector<double> v, s;
    for (int k = 0; k < n; ++k) {
        f.draw(rng, v, s);
        const IlluminanceMetrics m = illuminance_metrics(v, s, 5, TaskArea{"", 0, 5, 0, 5});
        const double z_u0 = (m.u0 - u0_true) / m.u0_sigma;
        const double z_ratio = (m.min_over_max - ratio_true) / m.min_over_max_sigma;
        z2_u0 += z_u0 * z_u0;
        z2_ratio += z_ratio * z_ratio;
        in1_u0 += std::abs(z_u0) < 1.0;
        in2_u0 += std::abs(z_u0) < 2.0;
        in1_ratio += std::abs(z_ratio) < 1.0;
    }
    const double tol_z2 = 5.0 * std::sqrt(2.0 / n);
    auto rate_tol = [&](double p) { return 5.0 * std::sqrt(p * (1.0 - p) / n); };
    std::cout << "[metrics] U0: mean z^2 " << z2_u0 / n << ", within 1 sigma " << double(in1_u0) / n << ", 2 sigma "
              << double(in2_u0) / n << "; Emin/Emax: mean z^2 " << z2_ratio / n << ", within 1 sigma "
              << double(in1_ratio) / n << '\n';
    EXPECT_NEAR(z2_u0 / n, 1.0, tol_z2);
    EXPECT_NEAR(z2_ratio / n, 1.0, tol_z2);
    EXPECT_NEAR(double(in1_u0) / n, 0.6827, rate_tol(0.6827));
    EXPECT_NEAR(double(in2_u0) / n, 0.9545, rate_tol(0.9545));
    EXPECT_NEAR(double(in1_ratio) / n, 0.6827, rate_tol(0.6827));

    // 100 equal cells: the plain U0 is biased low by about 2.5 sigma; U0 - U0_bias is not,
    // and U0_sigma (the minimum cell's sigma, larger than the minimum's own spread) covers.
    Field flat{10, 10, std::vector<double>(100, 100.0), 0.01};
    int plain_in2 = 0, corrected_in2 = 0;
    double mean_corrected = 0.0;
    for (int k = 0; k < 1000; ++k) {
        flat.draw(rng, v, s);
        const IlluminanceMetrics m = illuminance_metrics(v, s, 10, TaskArea{"", 0, 10, 0, 10});
        plain_in2 += std::abs(m.u0 - 1.0) < 2.0 * m.u0_sigma;
        corrected_in2 += std::abs(m.u0 - m.u0_bias - 1.0) < 2.0 * m.u0_sigma;
        mean_corrected += (m.u0 - m.u0_bias) / 1000;
    }
    std::cout << "[metrics] flat: plain U0 within 2 sigma " << plain_in2 / 1000.0 << ", corrected "
              << corrected_in2 / 1000.0 << ", mean corrected U0 " << mean_corrected << '\n';
    EXPECT_LT(plain_in2, 500);
    EXPECT_GE(corrected_in2, 950);
    EXPECT_NEAR(mean_corrected, 1.0, 0.1 * 0.025);  // within a tenth of the bias (2.5 %)
}

// ---------------------------------------------------------------------------------
// End to end: a point source over a floor (docs/VALIDATION.md case 6).

#ifdef LUXTRACE_BINARY
struct Reference {
    double avg, min, max;
};

// Cell averages of E = I h / (x^2 + y^2 + h^2)^1.5 by an 8 x 8 midpoint rule over the cells
// [i0, i1) x [j0, j1) of the 4 m x 4 m, 10 x 10 grid centred under the source.
Reference point_source_reference(int i0, int i1, int j0, int j1) {
    const double I = 1000.0 / (4.0 * kPi), h = 2.0, d = 0.4;
    Reference r{0.0, 1e300, -1e300};
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
            double s = 0.0;
            for (int b = 0; b < 8; ++b)
                for (int a = 0; a < 8; ++a) {
                    const double x = -2.0 + (i + (a + 0.5) / 8) * d, y = -2.0 + (j + (b + 0.5) / 8) * d;
                    s += I * h / std::pow(x * x + y * y + h * h, 1.5);
                }
            s /= 64.0;
            r.avg += s;
            r.min = std::min(r.min, s);
            r.max = std::max(r.max, s);
        }
    r.avg /= (i1 - i0) * (j1 - j0);
    return r;
}

TEST(IlluminanceMetricsEndToEnd, PointSourceOverAFloor) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_metrics_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path out = dir / "pf.h5";
    const fs::path scene = fs::path(LUXTRACE_TEST_DATA_DIR) / "validation" / "point_floor_metrics.toml";
    const auto run = test_support::run_luxtrace("run " + scene.string() + " --output " + out.string() +
                                                " --threads 2 --quiet");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    auto check = [&](const std::string& g, const Reference& ref, const char* what) {
        auto a = [&](const char* name) { return r.attr_f64(g, name); };
        const double z_avg = (a("E_avg_lx") - ref.avg) / a("E_avg_sigma_lx");
        // Emin and Emax minus their reported bias, against the true extreme cell.
        const double z_min = (a("E_min_lx") - a("E_min_bias_lx") - ref.min) / a("E_min_sigma_lx");
        const double z_max = (a("E_max_lx") - a("E_max_bias_lx") - ref.max) / a("E_max_sigma_lx");
        const double z_u0 = (a("U0") - a("U0_bias") - ref.min / ref.avg) / a("U0_sigma");
        const double z_ratio = (a("E_min_over_max") - a("E_min_over_max_bias") - ref.min / ref.max) /
                               a("E_min_over_max_sigma");
        std::cout << "[metrics] " << what << ": Eavg " << a("E_avg_lx") << " (ref " << ref.avg << ", z " << z_avg
                  << "), Emin " << a("E_min_lx") << " bias " << a("E_min_bias_lx") << " (ref " << ref.min << ", z "
                  << z_min << "), Emax " << a("E_max_lx") << " bias " << a("E_max_bias_lx") << " (ref " << ref.max
                  << ", z " << z_max << "), U0 " << a("U0") << " +- " << a("U0_sigma") << " (ref " << ref.min / ref.avg
                  << ", z " << z_u0 << "), Emin/Emax z " << z_ratio << '\n';
        EXPECT_LT(std::abs(z_avg), 5.0) << what;
        EXPECT_LT(std::abs(z_min), 5.0) << what;
        EXPECT_LT(std::abs(z_max), 5.0) << what;
        EXPECT_LT(std::abs(z_u0), 5.0) << what;
        EXPECT_LT(std::abs(z_ratio), 5.0) << what;
        // Maintained = initial x the scene's maintenance factor 0.8.
        EXPECT_NEAR(a("E_avg_maintained_lx"), 0.8 * a("E_avg_lx"), 1e-12 * a("E_avg_lx"));
        EXPECT_NEAR(a("E_min_maintained_lx"), 0.8 * a("E_min_lx"), 1e-12 * a("E_min_lx"));
        EXPECT_NEAR(a("E_max_maintained_sigma_lx"), 0.8 * a("E_max_sigma_lx"), 1e-12 * a("E_max_sigma_lx"));
        EXPECT_EQ(r.attr_u64(g, "U0_unreliable"), 0u) << what;
    };
    // Whole grid: the four corner cells share the minimum and the four centre cells the maximum.
    const std::string g = "/detectors/floor_E";
    check(g, point_source_reference(0, 10, 0, 10), "whole grid");
    EXPECT_EQ(r.attr_u64(g, "E_min_competitors"), 4u);
    EXPECT_EQ(r.attr_u64(g, "E_max_competitors"), 4u);
    EXPECT_EQ(r.attr_u64(g, "metrics_cells"), 100u);
    // The whole grid's Eavg is the detector's mean, with its exact error (eq. 8, one cell).
    EXPECT_DOUBLE_EQ(r.attr_f64(g, "E_avg_lx"), r.attr_f64(g, "mean_value"));
    EXPECT_DOUBLE_EQ(r.attr_f64(g, "E_avg_sigma_lx"), r.attr_f64(g, "mean_value") * r.attr_f64(g, "mean_sigma_rel"));
    // Task area "side", cells 6 <= i < 10, 2 <= j < 5: minimum at (9, 2), maximum at (6, 4).
    const std::string ga = g + "/task_areas/side";
    check(ga, point_source_reference(6, 10, 2, 5), "task area");
    EXPECT_EQ(r.f64_attr_array(ga, "cell_range"), (std::vector<double>{6, 10, 2, 5}));
    EXPECT_EQ(r.f64_attr_array(ga, "E_min_cell"), (std::vector<double>{9, 2}));
    EXPECT_EQ(r.f64_attr_array(ga, "E_max_cell"), (std::vector<double>{6, 4}));
    EXPECT_EQ(r.attr_u64(ga, "metrics_cells"), 12u);

    // luxtrace info prints them back from the file.
    const auto info = test_support::run_luxtrace("info " + out.string());
    EXPECT_EQ(info.code, 0);
    for (const char* s :
         {"U0 = Emin/Eavg", "Emin/Emax", "task area 'side' cells [6:10,2:5], 12 cells", "maintained Eavg"})
        EXPECT_NE(info.out.find(s), std::string::npos) << s << " not in:\n" << info.out;
    fs::remove_all(dir);
}

// With sobol a task area's Eavg error is the spread of its replicate sums (7 dof here).
TEST(IlluminanceMetricsEndToEnd, SobolTaskAreaAverage) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_metrics_sobol_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path out = dir / "pf.h5";
    const fs::path scene = fs::path(LUXTRACE_TEST_DATA_DIR) / "validation" / "point_floor_metrics.toml";
    const auto run = test_support::run_luxtrace("run " + scene.string() + " --output " + out.string() +
                                                " --threads 2 --quiet --sampler sobol --photons 2M");
    ASSERT_EQ(run.code, 0) << run.out;
    const ResultReader r(out);
    const std::string ga = "/detectors/floor_E/task_areas/side";
    const Reference ref = point_source_reference(6, 10, 2, 5);
    const double sigma = r.attr_f64(ga, "E_avg_sigma_lx");
    const double z = (r.attr_f64(ga, "E_avg_lx") - ref.avg) / sigma;
    std::cout << "[metrics] sobol task area: Eavg " << r.attr_f64(ga, "E_avg_lx") << " +- " << sigma << " (ref "
              << ref.avg << ", z " << z << ")\n";
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(z), 5.0);
    fs::remove_all(dir);
}

TEST(IlluminanceMetricsEndToEnd, BadTaskAreaExitsWithTwoAndWritesNothing) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_metrics_bad_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path scene = dir / "bad.toml";
    std::ofstream(scene) << "[[material]]\nname = \"m\"\nreflectance = 0.5\n"
                            "[[shape]]\ntype = \"rectangle\"\nsize = [2, 2]\nmaterial = \"m\"\n"
                            "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 100\n"
                            "[[detector]]\nname = \"desk\"\ncenter = [0, 0, 0.5]\nsize = [1, 1]\ncells = [4, 3]\n"
                            "[[detector.task_area]]\nname = \"t\"\ncells = [0, 4, 0, 4]\n";
    const auto run = test_support::run_luxtrace("run " + scene.string() + " --output " + (dir / "out.h5").string());
    EXPECT_EQ(run.code, 2) << run.out;
    EXPECT_NE(run.out.find(scene.string() + ":19: [[detector]] #1 'desk' task_area #1 't': key 'cells'"),
              std::string::npos)
        << run.out;
    EXPECT_FALSE(fs::exists(dir / "out.h5"));
    fs::remove_all(dir);
}
#endif

}  // namespace
}  // namespace luxtrace
