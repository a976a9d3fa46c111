// The annual errors against their scatter over seeds (issue 24 §3; docs/VALIDATION.md
// "Annual daylight", where scripts/annual_calibration.py does the same for the office).
// A black 2 m cube with a 0.5 m skylight (a portal) over a floor grid of 16 sensors, a year
// of Chicago weather, 10 seeds of 1 M photons: for a correct error model the scatter of a
// figure over the seeds, in units of its reported sigma, is 1. Pooled over sensors (and
// hours) and seeds, (x_k - mean x) / sigma_k has K - 1 degrees of freedom per entry; the
// bound [0.8, 1.25] is the issue's, at least 3 standard deviations of the pooled ratio wide
// here (per-sensor DA: 144 degrees of freedom, 6 %; ASE hours, 8 sensors in the sun patch:
// 72, 8 %), so a factor-2 wrong sigma fails.
// Plus: `luxtrace check` accepts the annual example (its probe counts a sky patch's photons
// that miss the portal as escaped, as the tracer does).
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr int kSeeds = 10;

// A strip of the roof (facing down, into the cube).
std::string roof(double cx, double cy, double sx, double sy) {
    return "[[shape]]\ntype = \"rectangle\"\ncenter = [" + std::to_string(cx) + ", " + std::to_string(cy) +
           ", 2]\nnormal = [0, 0, -1]\nup = [0, 1, 0]\nsize = [" + std::to_string(sx) + ", " + std::to_string(sy) +
           "]\nmaterial = \"black\"\n";
}

std::string skylight_scene() {
    std::string s = "[annual]\nweather = \"" + std::string(LUXTRACE_TEST_DATA_DIR) +
                    "/weather/chicago.epw\"\n"
                    "[[material]]\nname = \"black\"\ntype = \"black\"\n"
                    "[[material]]\nname = \"open\"\ntype = \"glass\"\nior = 1\n";
    const char* walls[] = {"[0, 0, 0]\nnormal = [0, 0, 1]\nup = [0, 1, 0]",
                           "[-1, 0, 1]\nnormal = [1, 0, 0]\nup = [0, 0, 1]",
                           "[1, 0, 1]\nnormal = [-1, 0, 0]\nup = [0, 0, 1]",
                           "[0, -1, 1]\nnormal = [0, 1, 0]\nup = [0, 0, 1]",
                           "[0, 1, 1]\nnormal = [0, -1, 0]\nup = [0, 0, 1]"};
    for (const char* w : walls)
        s += std::string("[[shape]]\ntype = \"rectangle\"\ncenter = ") + w + "\nsize = [2, 2]\nmaterial = \"black\"\n";
    s += roof(0, 0.625, 2, 0.75) + roof(0, -0.625, 2, 0.75) + roof(0.625, 0, 0.75, 0.5) + roof(-0.625, 0, 0.75, 0.5);
    s += "[[shape]]\nname = \"hole\"\ntype = \"rectangle\"\ncenter = [0, 0, 2]\nnormal = [0, 0, -1]\nsize = [0.5, "
         "0.5]\nmaterial = \"open\"\n[[portal]]\nshape = \"hole\"\n"
         "[[detector]]\nname = \"floor\"\ncenter = [0, 0, 0.01]\nnormal = [0, 0, 1]\nup = [0, 1, 0]\nsize = [2, 2]\n"
         "cells = [4, 4]\n[run]\nphotons = 1000000\n";
    return s;
}

// Per seed: values and sigmas of one figure, flattened in the same order.
struct Series {
    std::vector<std::vector<double>> x, s;
};

// sqrt of the pooled mean of ((x_k - mean x) / sigma_k)^2 (K - 1 degrees of freedom per
// entry) over the entries every seed gives a positive sigma; `entries` counts them.
double scatter_over_sigma(const Series& f, std::size_t& entries) {
    const std::size_t k = f.x.size(), n = f.x.front().size();
    double sum = 0.0;
    entries = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double mean = 0.0;
        bool ok = true;
        for (std::size_t r = 0; r < k; ++r) {
            mean += f.x[r][i] / static_cast<double>(k);
            ok = ok && f.s[r][i] > 0.0;
        }
        if (!ok) continue;
        for (std::size_t r = 0; r < k; ++r) sum += std::pow((f.x[r][i] - mean) / f.s[r][i], 2);
        ++entries;
    }
    return std::sqrt(sum / static_cast<double>((k - 1) * entries));
}

class AnnualCalibration : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = std::make_unique<test_support::ScratchDir>("annual_calibration");
        const fs::path scene = dir_->path() / "skylight.toml";
        std::ofstream(scene) << skylight_scene();
        for (int seed = 1; seed <= kSeeds; ++seed) {
            const fs::path out = dir_->path() / ("seed_" + std::to_string(seed) + ".h5");
            const auto o = test_support::run_luxtrace("run \"" + scene.string() + "\" --seed " + std::to_string(seed) +
                                                      " --output \"" + out.string() + "\" --quiet --threads 2");
            ASSERT_EQ(o.code, 0) << o.out;
            results_.push_back(out);
        }
    }
    static void TearDownTestSuite() {
        results_.clear();
        dir_.reset();
    }

    // A per-sensor figure of the floor grid, over the seeds.
    static Series sensors(const std::string& name) {
        Series f;
        for (const fs::path& p : results_) {
            const ResultReader r(p);
            f.x.push_back(r.f64("/annual/detectors/floor/" + name));
            f.s.push_back(r.f64("/annual/detectors/floor/" + name + "_sigma"));
        }
        return f;
    }
    // Every sensor's illuminance at the occupied daylit hours with (or without) a direct sun.
    static Series hours(bool with_sun) {
        Series f;
        for (const fs::path& p : results_) {
            const ResultReader r(p);
            std::vector<std::size_t> shape;
            const std::vector<double> e = r.f64("/annual/detectors/floor/illuminance_lx", &shape);
            const std::vector<double> s = r.f64("/annual/detectors/floor/illuminance_sigma_lx");
            const std::vector<std::uint64_t> occupied = r.u64("/annual/occupied"), daylit = r.u64("/annual/daylit");
            const std::vector<std::uint64_t> sun = r.u64("/annual/sun_group");
            std::vector<double> x, sx;
            for (std::size_t h = 0; h < shape[0]; ++h) {
                if (!occupied[h] || !daylit[h] || (sun[h] != ~std::uint64_t{0}) != with_sun) continue;
                for (std::size_t c = 0; c < shape[1]; ++c) {
                    x.push_back(e[h * shape[1] + c]);
                    sx.push_back(s[h * shape[1] + c]);
                }
            }
            f.x.push_back(std::move(x));
            f.s.push_back(std::move(sx));
        }
        return f;
    }
    static void expect_calibrated(const std::string& what, const Series& f, std::size_t min_entries) {
        std::size_t entries = 0;
        const double ratio = scatter_over_sigma(f, entries);
        std::cout << "[annual calibration] " << what << ": scatter / sigma " << ratio << " over " << entries
                  << " entries x " << kSeeds << " seeds\n";
        EXPECT_GE(entries, min_entries) << what;
        EXPECT_GE(ratio, 0.8) << what << ": the reported sigma is too large";
        EXPECT_LE(ratio, 1.25) << what << ": the reported sigma is too small";
    }

    static inline std::unique_ptr<test_support::ScratchDir> dir_;
    static inline std::vector<fs::path> results_;
};

// Per-sensor DA, continuous DA, UDI useful and ASE hours (the replicates' sigma), and every
// sensor's illuminance at the hours without a direct sun (sky patches and ground only); one
// case, so that ctest runs the 10 seeds once.
TEST_F(AnnualCalibration, SensorFiguresAndSkyHoursScatterAsTheirSigma) {
    expect_calibrated("per-sensor DA", sensors("da"), 16);
    expect_calibrated("per-sensor continuous DA", sensors("continuous_da"), 16);
    expect_calibrated("per-sensor UDI useful", sensors("udi_useful"), 16);
    expect_calibrated("per-sensor ASE hours", sensors("ase_hours"), 8);
    expect_calibrated("hourly illuminance, sky-only hours", hours(false), 16 * 200);
}

// Disabled: conservative by construction here (scatter / sigma 0.62, docs/VALIDATION.md
// "Annual daylight"). In this black room every cell outside the hour's sun patch is a true
// shadow, yet a cell that neither this sun nor the same hour's suns of the neighbouring
// days reached gets the detector's dark rate as its hourly variance (docs/ANNUAL.md step 5).
TEST_F(AnnualCalibration, DISABLED_SunHoursScatterAsTheirSigma) {
    expect_calibrated("hourly illuminance, hours with a direct sun", hours(true), 16 * 2000);
}

TEST(AnnualExample, CheckAcceptsIt) {
    const auto o = test_support::run_luxtrace("check \"" + std::string(LUXTRACE_EXAMPLES_DIR) +
                                              "/annual/annual_office.toml\"");
    EXPECT_EQ(o.code, 0) << o.out;
    EXPECT_NE(o.out.find("sky patch"), std::string::npos) << o.out;
}

}  // namespace
}  // namespace luxtrace
