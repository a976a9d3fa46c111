// The replicates' normal numbers by the quantile (sampler/normal_quantile.hpp): the
// quantile against Phi^-1's known values, and draws from a Philox stream against the
// normal distribution (chi-square over equiprobable bins, the tails included).
#include "luxtrace/sampler/normal_quantile.hpp"
#include "luxtrace/sampler/philox_bits.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace luxtrace {
namespace {

double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

TEST(NormalQuantile, InvertsTheDistributionFunction) {
    EXPECT_EQ(normal_quantile(0.5), 0.0);
    EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 3e-9);
    EXPECT_NEAR(normal_quantile(0.001), -3.090232306167814, 4e-9);
    EXPECT_NEAR(normal_quantile(1e-12), -7.034483825, 1e-8);
    for (double p = 1e-15; p < 1.0; p = p < 0.5 ? p * 3.0 : 1.0 - (1.0 - p) / 3.0)
        EXPECT_NEAR(phi(normal_quantile(p)) / p, 1.0, 1e-7) << p;  // x within 1.2e-9: p within 1e-7
}

TEST(NormalQuantile, DrawsFromAStreamAreStandardNormal) {
    PhiloxBits bits(2026, 37);
    constexpr int kBins = 40;
    constexpr std::size_t kDraws = 400000;
    std::vector<double> count(kBins, 0.0);
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < kDraws; ++i) {
        const double x = standard_normal(bits);
        sum += x;
        sum2 += x * x;
        count[std::min(kBins - 1, static_cast<int>(phi(x) * kBins))] += 1.0;
    }
    const double expected = static_cast<double>(kDraws) / kBins;
    double chi2 = 0.0;
    for (const double c : count) chi2 += (c - expected) * (c - expected) / expected;
    const double n = static_cast<double>(kDraws), mean = sum / n, var = sum2 / n - mean * mean;
    std::cout << "[normal] chi2 " << chi2 << " on " << kBins - 1 << " dof, mean " << mean << ", variance " << var
              << "\n";
    EXPECT_LT(chi2, 39.0 + 5.0 * std::sqrt(78.0));  // 5 sigma of chi2 with 39 dof
    EXPECT_LT(std::abs(mean), 5.0 / std::sqrt(n));
    EXPECT_LT(std::abs(var - 1.0), 5.0 * std::sqrt(2.0 / n));
}

}  // namespace
}  // namespace luxtrace
