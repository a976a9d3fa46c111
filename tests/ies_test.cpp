// Tests of the IES LM-63 reader (values, symmetry, flux), of PhotometryDistribution sampling
// (chi-square against intensity_cd) and of the errors for bad files.
#include "luxtrace/light/ies.hpp"
#include "luxtrace/light/photometry_distribution.hpp"

#include "luxtrace/core/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#ifndef LUXTRACE_TEST_DATA_DIR
#error "define LUXTRACE_TEST_DATA_DIR (the tests/data folder)"
#endif
#ifndef LUXTRACE_EXAMPLES_DIR
#error "define LUXTRACE_EXAMPLES_DIR (the examples folder)"
#endif

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;

std::filesystem::path data(const std::string& name) {
    return std::filesystem::path(LUXTRACE_TEST_DATA_DIR) / "ies" / name;
}
std::filesystem::path office() { return std::filesystem::path(LUXTRACE_EXAMPLES_DIR) / "office" / "fixture.ies"; }

double I(const Photometry& p, double g_deg, double c_deg) { return p.intensity_cd(g_deg * kDeg, c_deg * kDeg); }

TEST(IesLoad, RotationalWithCommasAndMultipliers) {
    const Photometry p = load_ies(data("rotational.ies"));
    EXPECT_EQ(p.vertical_deg, (std::vector<double>{0, 30, 60, 90}));
    EXPECT_EQ(p.horizontal_deg, (std::vector<double>{0}));
    ASSERT_EQ(p.candela_cd.size(), 1u);
    // Raw 100 90 50 0 times multiplier 2.0 times ballast factor 0.9.
    const std::vector<double> want{180, 162, 90, 0};
    ASSERT_EQ(p.candela_cd[0].size(), want.size());
    for (std::size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(p.candela_cd[0][i], want[i], 1e-9);
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Rotational);
    EXPECT_EQ(p.num_lamps, 1);
    EXPECT_DOUBLE_EQ(p.lamp_flux_lm, 1000.0 * p.num_lamps);
    EXPECT_DOUBLE_EQ(p.input_watts, 15.0);
    ASSERT_FALSE(p.keywords.empty());
    EXPECT_EQ(p.keywords[0].first, "TEST");

    EXPECT_NEAR(I(p, 30, 0), 162.0, 1e-9);
    EXPECT_NEAR(I(p, 45, 0), 126.0, 1e-9);  // halfway between 162 and 90
    for (double c : {0.0, 37.0, 90.0, 200.0, 359.0}) EXPECT_NEAR(I(p, 45, c), 126.0, 1e-9);
    EXPECT_EQ(I(p, 90.5, 0), 0.0);  // above the last vertical angle
    EXPECT_EQ(I(p, 150, 10), 0.0);
}

TEST(IesLoad, QuadrantUnfolds) {
    const Photometry p = load_ies(data("quadrant.ies"));
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Quadrant);
    EXPECT_EQ(p.horizontal_deg, (std::vector<double>{0, 45, 90}));
    ASSERT_EQ(p.candela_cd.size(), 3u);
    EXPECT_EQ(p.candela_cd[1], (std::vector<double>{1000, 700, 300, 0}));
    EXPECT_NEAR(I(p, 30, 45), 700.0, 1e-9);
    EXPECT_NEAR(I(p, 30, 22.5), 750.0, 1e-9);
    EXPECT_NEAR(I(p, 45, 22.5), 550.0, 1e-9);   // bilinear: mean of 600 and 500
    EXPECT_NEAR(I(p, 30, 112.5), 650.0, 1e-9);  // folds to 67.5
    EXPECT_NEAR(I(p, 30, 270), 600.0, 1e-9);    // folds to 90
    for (double g : {5.0, 33.0, 71.0})
        for (double c : {3.0, 20.0, 44.0, 61.0, 89.0}) {
            const double cr = c * kDeg, gr = g * kDeg, ref = p.intensity_cd(gr, cr);
            EXPECT_NEAR(p.intensity_cd(gr, kPi - cr), ref, 1e-9) << g << " " << c;
            EXPECT_NEAR(p.intensity_cd(gr, kPi + cr), ref, 1e-9) << g << " " << c;
            EXPECT_NEAR(p.intensity_cd(gr, 2 * kPi - cr), ref, 1e-9) << g << " " << c;
        }
    EXPECT_NE(I(p, 30, 10), I(p, 30, 80));  // not rotationally symmetric
}

TEST(IesLoad, BilateralUnfolds) {
    const Photometry p = load_ies(data("bilateral.ies"));
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Bilateral);
    EXPECT_EQ(p.vertical_deg.back(), 180.0);
    EXPECT_NEAR(I(p, 45, 180), 300.0, 1e-9);
    EXPECT_NEAR(I(p, 45, 270), 450.0, 1e-9);  // folds to 90
    EXPECT_NEAR(I(p, 180, 90), 50.0, 1e-9);
    EXPECT_NEAR(I(p, 157.5, 0), 150.0, 1e-9);
    for (double c : {10.0, 80.0, 135.0, 179.0}) {
        EXPECT_NEAR(I(p, 60, c), I(p, 60, 360 - c), 1e-9) << c;
        EXPECT_NE(I(p, 60, c), I(p, 60, 180 - c)) << c;  // no 90-270 mirror
    }
}

TEST(IesLoad, Bilateral90Unfolds) {
    const Photometry p = load_ies(data("bilateral90.ies"));
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Bilateral90);
    EXPECT_NEAR(I(p, 45, 0), 250.0, 1e-9);  // plane 0 is plane 180
    for (double c : {0.0, 30.0, 80.0}) EXPECT_NEAR(I(p, 30, c), I(p, 30, 180 - c), 1e-9) << c;
    EXPECT_NEAR(I(p, 30, 300), I(p, 30, 240), 1e-9);
}

TEST(IesLoad, FullCircleAsymmetric) {
    const Photometry p = load_ies(data("full.ies"));
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Full);
    ASSERT_EQ(p.vertical_deg.size(), 13u);
    ASSERT_EQ(p.horizontal_deg.size(), 9u);
    EXPECT_EQ(p.horizontal_deg.back(), 360.0);
    EXPECT_NEAR(I(p, 45, 270), p.candela_cd[6][3], 1e-9);
    EXPECT_NEAR(I(p, 180, 90), p.candela_cd[2][12], 1e-9);
    EXPECT_NEAR(I(p, 45, 359.9999), I(p, 45, 0), 1e-2);  // continuous across C = 0
    EXPECT_NEAR(I(p, 45, -90), I(p, 45, 270), 1e-9);     // c is wrapped
    EXPECT_GT(std::abs(I(p, 45, 90) - I(p, 45, 270)), 50.0);
}

TEST(IesLoad, OfficeFixture) {
    const Photometry p = load_ies(office());
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Quadrant);
    EXPECT_EQ(p.vertical_deg.size(), 19u);
    EXPECT_EQ(p.num_lamps, 2);
    EXPECT_NEAR(p.flux_lm(), 3000.0, 30.0);
    EXPECT_EQ(I(p, 90, 0), 0.0);
    EXPECT_EQ(I(p, 120, 0), 0.0);
    bool luminaire = false;
    for (const auto& [k, v] : p.keywords)
        if (k == "LUMINAIRE") luminaire = v.find("opal") != std::string::npos;  // [MORE] joined
    EXPECT_TRUE(luminaire);
}

TEST(IesFlux, CosineGivesPiI0) {
    const Photometry p = load_ies(data("cosine.ies"));
    EXPECT_NEAR(p.flux_lm(), kPi * 1000.0, 0.005 * kPi * 1000.0);
    EXPECT_NEAR(I(p, 60, 0), 500.0, 0.01);
}

TEST(IesFlux, ConstantOverSphereGives4PiI0) {
    const Photometry p = load_ies(data("uniform_sphere.ies"));
    EXPECT_NEAR(p.flux_lm(), 4 * kPi * 250.0, 1e-9 * 4 * kPi * 250.0);
    EXPECT_NEAR(I(p, 135, 77), 250.0, 1e-9);
}

TEST(IesFlux, DistributionMatchesPhotometry) {
    for (const auto& f : {office(), data("full.ies"), data("quadrant.ies"), data("cosine.ies")}) {
        const Photometry p = load_ies(f);
        const PhotometryDistribution d(p);
        EXPECT_NEAR(d.flux_lm() / p.flux_lm(), 1.0, 1e-3) << f;
    }
}

// ---- chi-square test of PhotometryDistribution::sample ------------------------------------

constexpr int kBinsG = 9, kBinsC = 8;

using luxtrace::test_support::chi2_quantile;

// Expected probability of each (gamma, c) bin: midpoint rule on a sub-grid that is not
// aligned with PhotometryDistribution's grid, with exact solid angles of the sub-cells.
std::vector<double> bin_probabilities(const Photometry& p) {
    constexpr int kSub = 50;
    const double dg = kPi / (kBinsG * kSub), dc = 2 * kPi / (kBinsC * kSub);
    std::vector<double> prob(kBinsG * kBinsC, 0.0);
    double total = 0.0;
    for (int i = 0; i < kBinsG * kSub; ++i) {
        const double solid = (std::cos(i * dg) - std::cos((i + 1) * dg)) * dc;
        for (int j = 0; j < kBinsC * kSub; ++j) {
            const double w = p.intensity_cd((i + 0.5) * dg, (j + 0.5) * dc) * solid;
            prob[(i / kSub) * kBinsC + j / kSub] += w;
            total += w;
        }
    }
    EXPECT_NEAR(total / p.flux_lm(), 1.0, 1e-3);
    for (double& q : prob) q /= total;
    return prob;
}

struct ChiSquare {
    double stat = 0.0;
    int dof = 0;
    long stray = 0;  // samples in bins of zero expected count
};

ChiSquare chi_square(const PhotometryDistribution& d, const std::vector<double>& prob, long n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<long> observed(prob.size(), 0);
    for (long k = 0; k < n; ++k) {
        const double u1 = u(rng), u2 = u(rng);
        const Vec3 w = d.sample(u1, u2);
        EXPECT_NEAR(glm::length(w), 1.0, 1e-12);
        const double g = std::acos(std::clamp(w.z, -1.0, 1.0));
        double c = std::atan2(w.y, w.x);
        if (c < 0) c += 2 * kPi;
        const int bg = std::min(kBinsG - 1, static_cast<int>(g / kPi * kBinsG));
        const int bc = std::min(kBinsC - 1, static_cast<int>(c / (2 * kPi) * kBinsC));
        ++observed[bg * kBinsC + bc];
    }
    // Bins expecting fewer than 5 samples are pooled so the chi-square law holds.
    ChiSquare r;
    double pool_exp = 0.0;
    long pool_obs = 0;
    int bins = 0;
    for (std::size_t b = 0; b < prob.size(); ++b) {
        const double e = prob[b] * n;
        if (e == 0.0) {
            r.stray += observed[b];
        } else if (e < 5.0) {
            pool_exp += e;
            pool_obs += observed[b];
        } else {
            r.stat += (observed[b] - e) * (observed[b] - e) / e;
            ++bins;
        }
    }
    if (pool_exp > 0.0) {
        r.stat += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
        ++bins;
    }
    r.dof = bins - 1;
    return r;
}

constexpr long kSamples = 200000;
using luxtrace::test_support::kZ999;

void expect_passes(const std::filesystem::path& f, std::uint64_t seed) {
    const Photometry p = load_ies(f);
    const PhotometryDistribution d(p);
    const ChiSquare r = chi_square(d, bin_probabilities(p), kSamples, seed);
    const double limit = chi2_quantile(r.dof, kZ999);
    std::printf("  chi-square %s: %.2f with %d dof (0.999 quantile %.2f)\n", f.filename().string().c_str(), r.stat,
                r.dof, limit);
    EXPECT_EQ(r.stray, 0);
    EXPECT_GT(r.dof, 20);
    EXPECT_LT(r.stat, limit) << f;
}

TEST(IesSample, ChiSquareOfficeFixture) { expect_passes(office(), 0x1E5u); }
TEST(IesSample, ChiSquareAsymmetricFull) { expect_passes(data("full.ies"), 42u); }

// The same statistic must notice small errors: the office fixture's vertical angles
// stretched by 2% (about a 1 degree shift at the peak), and the full file mirrored in c
// (I(g, c) -> I(g, 360 - c), i.e. local +y taken as C = 270 instead of C = 90).
TEST(IesSample, ChiSquareRejectsWrongDistributions) {
    const Photometry p = load_ies(office());
    Photometry stretched = p;
    for (double& v : stretched.vertical_deg) v *= 1.02;
    const ChiSquare r1 = chi_square(PhotometryDistribution(p), bin_probabilities(stretched), kSamples, 7u);
    std::printf("  chi-square stretched: %.2f with %d dof\n", r1.stat, r1.dof);
    EXPECT_GT(r1.stat, chi2_quantile(r1.dof, kZ999));

    const Photometry f = load_ies(data("full.ies"));
    Photometry mirrored = f;
    std::reverse(mirrored.candela_cd.begin(), mirrored.candela_cd.end());  // planes 0..360 evenly
    const ChiSquare r2 = chi_square(PhotometryDistribution(f), bin_probabilities(mirrored), kSamples, 8u);
    std::printf("  chi-square mirrored: %.2f with %d dof\n", r2.stat, r2.dof);
    EXPECT_GT(r2.stat, chi2_quantile(r2.dof, kZ999));
}

TEST(IesSample, OfficeEmitsOnlyDownward) {
    const PhotometryDistribution d(load_ies(office()));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < 20000; ++k) EXPECT_GE(d.sample(u(rng), u(rng)).z, 0.0);
    EXPECT_GE(d.sample(0.0, 0.0).z, 0.0);
    EXPECT_GE(d.sample(1.0, 1.0).z, 0.0);  // out-of-range uniforms are clamped
}

TEST(IesSample, WiderUniformsAreUnitVectors) {
    const PhotometryDistribution d(load_ies(data("uniform_sphere.ies")), 90, 45);
    for (double u1 : {0.0, 0.25, 0.5, 0.999999})
        for (double u2 : {0.0, 0.5, 0.999999}) EXPECT_NEAR(glm::length(d.sample(u1, u2)), 1.0, 1e-12);
    EXPECT_NEAR(d.sample(0.5, 0.0).z, 0.0, 1e-12);  // median of uniform cos(gamma) is 0
}

// ---- bad input -----------------------------------------------------------------------

struct BadFile {
    const char* name;
    int line;
    const char* what;  // a phrase the message must contain
};

class IesBadInput : public testing::TestWithParam<BadFile> {};

TEST_P(IesBadInput, ThrowsWithFileAndLine) {
    const BadFile& b = GetParam();
    const std::filesystem::path f = data(b.name);
    ASSERT_TRUE(std::filesystem::exists(f)) << f;
    try {
        load_ies(f);
        FAIL() << "no InputError for " << b.name;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(std::string(b.name) + ":" + std::to_string(b.line) + ": "), std::string::npos) << msg;
        EXPECT_NE(msg.find(b.what), std::string::npos) << msg;
    }
}

INSTANTIATE_TEST_SUITE_P(Files, IesBadInput,
                         testing::Values(BadFile{"bad_truncated.ies", 6, "unexpected end of file"},
                                         BadFile{"bad_nonnumeric.ies", 9, "found '7O0'"},
                                         BadFile{"bad_count_short.ies", 10, "expected 12 candela values"},
                                         BadFile{"bad_count_extra.ies", 9, "expected 6 candela values"},
                                         BadFile{"bad_decreasing.ies", 7, "vertical angles must increase"},
                                         BadFile{"bad_negative.ies", 8, "negative candela value -4"},
                                         BadFile{"bad_tilt_missing.ies", 3, "TILT file 'no_such_tilt.dat' not found"},
                                         BadFile{"bad_no_tilt.ies", 7, "no TILT= line"},
                                         BadFile{"bad_horizontal_range.ies", 7, "found 0-120"}),
                         [](const testing::TestParamInfo<BadFile>& param_info) {
                             const std::string n = param_info.param.name;
                             return n.substr(4, n.size() - 8);  // "bad_xxx.ies" -> "xxx"
                         });

TEST(IesBadInputMissing, NamesTheFile) {
    try {
        load_ies(data("does_not_exist.ies"));
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("does_not_exist.ies"), std::string::npos);
    }
}

// ---------------------------------------------------------------------------------
// A real maker's file (tests/data/real/README.md): American Electric Lighting ASA 15M R2,
// a 150 W metal-halide roadway luminaire, type II full cutoff, LM-63-2002, relative
// photometry (one 13000 lm lamp), 37 vertical x 73 horizontal angles (bilateral 0-180).

std::filesystem::path real(const std::string& name) {
    return std::filesystem::path(LUXTRACE_TEST_DATA_DIR) / "real" / name;
}

TEST(IesRealFile, AmericanElectricAsa15mR2Parses) {
    const Photometry p = load_ies(real("ASA_15M_R2.ies"));
    EXPECT_EQ(p.num_lamps, 1);
    EXPECT_DOUBLE_EQ(p.lamp_flux_lm, 13000.0 * p.num_lamps);
    EXPECT_DOUBLE_EQ(p.input_watts, 185.0);
    ASSERT_EQ(p.vertical_deg.size(), 37u);
    ASSERT_EQ(p.horizontal_deg.size(), 73u);
    EXPECT_DOUBLE_EQ(p.vertical_deg.back(), 90.0);
    EXPECT_DOUBLE_EQ(p.horizontal_deg[1], 2.5);
    EXPECT_EQ(p.symmetry(), CPlaneSymmetry::Bilateral);
    const auto keyword = [&](const std::string& k) {
        for (const auto& [key, value] : p.keywords)
            if (key == k) return value;
        return std::string("(missing)");
    };
    EXPECT_EQ(keyword("MANUFAC"), "American Electric Lighting");
    EXPECT_EQ(keyword("LUMCAT"), "ASA 15M R2");
    EXPECT_EQ(keyword("LAMP"), "ONE 150-WATT CLEAR ED23.5 CERAMIC METAL HALIDE PULSE START, HORIZONTAL\nPOS.");
    // Values straight from the file (multiplier and ballast factor are 1).
    EXPECT_DOUBLE_EQ(I(p, 0, 0), 1666.0);
    EXPECT_DOUBLE_EQ(I(p, 2.5, 0), 1817.0);
    EXPECT_DOUBLE_EQ(I(p, 90, 0), 0.0);
    EXPECT_DOUBLE_EQ(I(p, 2.5, 2.5), 1861.0);  // second plane, second angle
    // Full cutoff: nothing above the horizontal.
    EXPECT_EQ(I(p, 100, 45), 0.0);
    EXPECT_EQ(I(p, 180, 0), 0.0);
    // Bilateral: the 180-360 half mirrors the file's 0-180 planes.
    for (double g : {10.0, 37.5, 61.0, 80.0})
        for (double c : {5.0, 47.5, 91.0, 170.0}) EXPECT_NEAR(I(p, g, 360.0 - c), I(p, g, c), 1e-9) << g << " " << c;
}

TEST(IesRealFile, AmericanElectricAsa15mR2Flux) {
    // The file is relative photometry: its candelas integrate to the luminaire's output,
    // the lamp's 13000 lm times the luminaire's efficiency. An independent midpoint
    // quadrature of the same bilinear interpolant (20000 x 4000 cells, numpy) gives
    // 9560.83 lm, an efficiency of 73.5 % (tests/data/real/README.md).
    const Photometry p = load_ies(real("ASA_15M_R2.ies"));
    EXPECT_NEAR(p.flux_lm(), 9560.83, 0.01 * 9560.83 * 1e-2);  // 0.01 %
    const double efficiency = p.flux_lm() / p.lamp_flux_lm;
    EXPECT_GT(efficiency, 0.6);
    EXPECT_LT(efficiency, 1.0);
    // The sampling table integrates the same distribution on its own grid.
    const PhotometryDistribution dist(p);
    EXPECT_NEAR(dist.flux_lm() / p.flux_lm(), 1.0, 2e-3);
}

TEST(IesRealFile, AmericanElectricAsa15mR2Sampling) { expect_passes(real("ASA_15M_R2.ies"), 0xA5Au); }

// ---------------------------------------------------------------------------------
// Hardening made with the fuzz targets (tests/fuzz/README.md): numbers that are finite
// alone but not once scaled, photometry without a finite positive flux and files that
// are not regular files are refused with the file named.

class IesHardening : public testing::Test {
protected:
    std::filesystem::path write(const std::string& text) {
        path_ = std::filesystem::temp_directory_path() /
                ("luxtrace_ies_test_" + std::to_string(::getpid()) + "_" +
                 testing::UnitTest::GetInstance()->current_test_info()->name() + ".ies");
        std::ofstream(path_) << text;
        return path_;
    }
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove(path_, ec);
    }
    std::string error_of(const std::string& text) {
        try {
            load_ies(write(text));
        } catch (const InputError& e) {
            return e.what();
        }
        return "(no InputError)";
    }
    std::filesystem::path path_;
};

TEST_F(IesHardening, ScaledCandelaOverflowIsRefused) {
    const std::string msg = error_of("TILT=NONE\n1 -1 1e300 2 1 1 2 0 0 0\n1e10 1 0\n0 90\n0\n1e10 1\n");
    EXPECT_NE(msg.find(path_.string() + ":6: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("too large"), std::string::npos) << msg;
}

TEST_F(IesHardening, FluxOverflowIsRefused) {
    // Every value is finite after scaling, but their integral is not.
    const std::string msg = error_of("TILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 180\n0\n1.7e308 1.7e308\n");
    EXPECT_NE(msg.find(path_.string() + ":"), std::string::npos) << msg;
    EXPECT_NE(msg.find("flux"), std::string::npos) << msg;
}

// Found by fuzz_ies (tests/fuzz/crashers/ies/tilt_name_too_long): a TILT= file name
// longer than the file system allows made std::filesystem::exists throw
// filesystem_error (exit 1) instead of the InputError for a missing tilt file.
TEST_F(IesHardening, TiltFileNameTooLongForTheFileSystem) {
    const std::string tilt(5000, 'x');
    const std::string msg = error_of("IESNA:LM-63-2002\nTILT=" + tilt + "\n1 -1 1 2 1 1 2 0 0 0\n");
    EXPECT_NE(msg.find(path_.string() + ":2: TILT file '" + tilt + "' not found"), std::string::npos) << msg;
}

TEST_F(IesHardening, NotARegularFileIsRefused) {
    try {
        load_ies("/dev/zero");  // would otherwise be read for ever
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/zero: not a regular file"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace luxtrace
