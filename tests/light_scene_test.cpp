// Light groups and light scenes end to end (issue 22; tests/data/validation/light_scenes.toml).
// Every tally keeps the groups apart, so a light scene is a weighted sum of the groups'
// counts: at weights 1 it is the plain run to the bit, a group alone is a run of that
// group's lights alone (within the errors), and a dimmed scene's errors (the groups'
// second moments weighted by w_g^2) match the scatter over seeds.
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

int run(const std::string& scene, const fs::path& out, std::uint64_t photons, std::uint64_t seed) {
    const std::string cmd = std::string("\"") + LUXTRACE_BINARY + "\" run \"" + LUXTRACE_TEST_DATA_DIR +
                            "/validation/" + scene + ".toml\" --output \"" + out.string() +
                            "\" --quiet --threads 2 --photons " + std::to_string(photons) + " --seed " +
                            std::to_string(seed) + " > /dev/null";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const std::string kDesk = "/detectors/desk";

TEST(LightScenes, WeightsOfOneAreThePlainRunAndTheGroupsSumToIt) {
    test_support::ScratchDir dir("light_scenes_plain");
    const fs::path out = dir.path() / "r.h5";
    ASSERT_EQ(0, run("light_scenes", out, 200'000, 5));
    const ResultReader r(out);
    // The scene at full output: the plain run's numbers exactly (same tallies, same formulas).
    EXPECT_EQ(r.f64("/light_scenes/full" + kDesk + "/value"), r.f64(kDesk + "/value"));
    EXPECT_EQ(r.f64("/light_scenes/full" + kDesk + "/sigma_rel"), r.f64(kDesk + "/sigma_rel"));
    EXPECT_EQ(r.f64("/light_scenes/full/global/illuminance"), r.f64("/global/illuminance"));
    EXPECT_EQ(r.attr_f64("/light_scenes/full/global", "moment_sigma_lx"), r.attr_f64("/global", "moment_sigma_lx"));
    // The groups' own counts add up to the plain counts, word for word.
    for (const std::string& set :
         {kDesk + "/count", kDesk + "/sumsq", std::string("/global/count_odd"), std::string("/global/sumsq")}) {
        // A group keeps its surface counts at its root, its detectors under detectors/.
        const std::string rel = set.rfind("/global/", 0) == 0 ? set.substr(8) : set.substr(1);
        std::vector<std::uint64_t> sum;
        for (const std::string& g : r.children("/light_groups")) {
            const std::vector<std::uint64_t> v = r.u64("/light_groups/" + g + "/" + rel);
            if (sum.empty()) sum.assign(v.size(), 0);
            for (std::size_t i = 0; i < v.size(); ++i) sum[i] += v[i];
        }
        EXPECT_EQ(sum, r.u64(set)) << set;
    }
    EXPECT_EQ(r.attr_strs("/", "light_groups"), (std::vector<std::string>{"window_row", "desk"}));
}

TEST(LightScenes, AGroupAloneAgreesWithARunOfItsLightsAlone) {
    test_support::ScratchDir dir("light_scenes_alone");
    const fs::path both = dir.path() / "both.h5", alone = dir.path() / "alone.h5";
    ASSERT_EQ(0, run("light_scenes", both, 600'000, 7));
    ASSERT_EQ(0, run("light_scenes_desk_only", alone, 300'000, 8));
    const ResultReader a(both), b(alone);
    const std::vector<double> va = a.f64("/light_scenes/desk_only" + kDesk + "/value");
    const std::vector<double> sa = a.f64("/light_scenes/desk_only" + kDesk + "/sigma_rel");
    const std::vector<double> vb = b.f64(kDesk + "/value"), sb = b.f64(kDesk + "/sigma_rel");
    ASSERT_EQ(va.size(), vb.size());
    double z2 = 0.0, worst = 0.0;
    for (std::size_t c = 0; c < va.size(); ++c) {
        const double z = (va[c] - vb[c]) / std::hypot(va[c] * sa[c], vb[c] * sb[c]);
        z2 += z * z / static_cast<double>(va.size());
        worst = std::max(worst, std::abs(z));
    }
    // Mean z^2 of K = 80 cells: 1 +- 5 sqrt(2 / K); no cell beyond 5 sigma.
    const double allowed = 5.0 * std::sqrt(2.0 / static_cast<double>(va.size()));
    EXPECT_NEAR(z2, 1.0, allowed);
    EXPECT_LT(worst, 5.0);
    std::cout << "[light scenes] desk group alone against a run of the desk lamp alone: mean z^2 " << z2 << " over "
              << va.size() << " cells (allowed 1 +- " << allowed << "), worst |z| " << worst << "\n";
}

TEST(LightScenes, DimmedSceneErrorsMatchTheScatterOverSeeds) {
    // 20 seeds of the "evening" scene (window row at 0.1, desk lamp at 1). Per cell, the
    // file's sigma against the scatter of the cell over the seeds, pooled over the cells as
    // an RMS ratio: within [0.9, 1.1]. The plain run's relative error applied to the
    // scene's value (what a user would guess without the groups' second moments) is shown
    // beside it.
    constexpr int kSeeds = 20;
    test_support::ScratchDir dir("light_scenes_seeds");
    std::vector<std::vector<double>> values, sigmas, naive;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const fs::path out = dir.path() / (std::to_string(seed) + ".h5");  // no literal prefix: GCC 12 -Wrestrict
        ASSERT_EQ(0, run("light_scenes", out, 100'000, 300 + seed));
        const ResultReader r(out);
        const std::vector<double> v = r.f64("/light_scenes/evening" + kDesk + "/value");
        const std::vector<double> s = r.f64("/light_scenes/evening" + kDesk + "/sigma_rel");
        const std::vector<double> plain = r.f64(kDesk + "/sigma_rel");
        std::vector<double> abs(v.size()), guess(v.size());
        for (std::size_t c = 0; c < v.size(); ++c) {
            abs[c] = v[c] * s[c];
            guess[c] = v[c] * plain[c];
        }
        values.push_back(v);
        sigmas.push_back(abs);
        naive.push_back(guess);
    }
    double var_obs = 0.0, var_file = 0.0, var_naive = 0.0;
    const std::size_t K = values[0].size();
    for (std::size_t c = 0; c < K; ++c) {
        double mean = 0.0;
        for (const auto& v : values) mean += v[c] / kSeeds;
        for (int i = 0; i < kSeeds; ++i) {
            var_obs += (values[i][c] - mean) * (values[i][c] - mean) / (kSeeds - 1);
            var_file += sigmas[i][c] * sigmas[i][c] / kSeeds;
            var_naive += naive[i][c] * naive[i][c] / kSeeds;
        }
    }
    const double ratio = std::sqrt(var_file / var_obs), naive_ratio = std::sqrt(var_naive / var_obs);
    EXPECT_GT(ratio, 0.9);
    EXPECT_LT(ratio, 1.1);
    std::cout << "[light scenes] evening (0.1, 1.0) over " << kSeeds << " seeds, " << K
              << " cells: file error / scatter " << ratio << "; the plain run's relative error instead: " << naive_ratio
              << "\n";
}

TEST(LightScenes, ATargetOnASceneStopsTheRunWhenTheSceneMeetsIt) {
    // The room with a target on the evening scene's desk: the run (a budget it cannot
    // spend first) stops when that scene's error reaches the goal, forecasts it on the way,
    // and the scene's stored error meets it.
    test_support::ScratchDir dir("light_scenes_target");
    const fs::path scene = dir.path() / "target.toml", out = dir.path() / "t.h5";
    {
        std::ifstream in(std::string(LUXTRACE_TEST_DATA_DIR) + "/validation/light_scenes.toml");
        std::ofstream o(scene);
        o << in.rdbuf() << "\n[[run.target]]\non = \"detector:desk\"\nrelative_error = 0.03\nscene = \"evening\"\n";
    }
    const std::string cmd = std::string("\"") + LUXTRACE_BINARY + "\" run \"" + scene.string() + "\" --output \"" +
                            out.string() + "\" --quiet --threads 2 --photons 1G --report-every-photons 20k > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    const ResultReader r(out);
    EXPECT_EQ(r.attr_str("/", "stop_reason").rfind("target detector:desk@evening", 0), 0u)
        << r.attr_str("/", "stop_reason");
    const double err = r.attr_f64("/light_scenes/evening" + kDesk, "sigma_rel_quadratic");
    EXPECT_LE(err, 0.03);
    EXPECT_GT(err, 0.0);
    // The plain run's desk, lit by the window row at full output too, is further along.
    EXPECT_LT(r.attr_f64(kDesk, "sigma_rel_quadratic"), err);
    const std::vector<double> forecast = r.f64("/history/target_forecast_photons");
    EXPECT_TRUE(std::any_of(forecast.begin(), forecast.end(), [](double f) { return std::isfinite(f) && f > 0; }));
    EXPECT_LT(r.attr_u64("/", "photons"), 100'000'000u);
}

}  // namespace
}  // namespace luxtrace
