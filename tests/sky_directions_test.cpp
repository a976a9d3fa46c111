// The sky's direction table (sky_directions.hpp): its cell integrals add up to the sky's
// own illuminances by quadrature (sky_model.hpp), so the flux per photon is exact; the
// directions it draws follow its cells (chi-square); the ground glow is a uniform lower
// hemisphere.
#include "luxtrace/light/sky_directions.hpp"

#include "luxtrace/sampler/philox_sampler.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

namespace luxtrace {
namespace {

double deg(double d) { return d * kPi / 180.0; }

// Every sky the scene file offers, with the sun at 30 and at 60 degrees altitude.
std::vector<SkyModel> all_skies() {
    std::vector<SkyModel> skies{SkyModel::uniform(), SkyModel::cie(16, 0.0, 0.0)};
    for (int type = 1; type <= 15; ++type)
        for (const double altitude : {30.0, 60.0})
            skies.push_back(SkyModel::cie(type, deg(90.0 - altitude), deg(altitude == 30.0 ? 180.0 : 135.0)));
    return skies;
}

TEST(SkyDirections, HorizontalIlluminanceMatchesQuadrature) {
    // The tabulated sky, as its photons deliver it, against the adaptive quadrature: the
    // cells' integrals of L and L cos Z are the sky's own to the rules' accuracy (uniform
    // directions within the cells would be off by up to 1e-4 for the turbid skies).
    for (const SkyModel& sky : all_skies()) {
        const SkyDirections table(sky, 1000.0, 0.0);
        const double exact = 1000.0 * sky.horizontal_illuminance_per_zenith_luminance_sr();
        EXPECT_NEAR(table.horizontal_illuminance_lx() / exact, 1.0, 1e-7)
            << "type " << sky.cie_type() << ", sun zenith " << sky.sun_zenith_rad();
    }
}

TEST(SkyDirections, VerticalIlluminanceMatchesQuadrature) {
    // E_v on the four facades from the cell probabilities (cell centres; the cells' own
    // size bounds the difference) against the quadrature of sky_model.
    for (const SkyModel& sky : all_skies()) {
        const SkyDirections table(sky, 1.0, 0.0);
        for (const double facing : {0.0, 90.0, 180.0, 270.0}) {
            const Vec3 n = sky_direction(0.5 * kPi, deg(facing));
            double e = 0.0;
            for (int row = 0; row < SkyDirections::kRows / 2; ++row)
                for (int col = 0; col < SkyDirections::kColumns; ++col) {
                    const Vec3 w = sky_direction(deg(row + 0.5), deg(col + 0.5));
                    e += table.cell_probability(row, col) * std::max(0.0, glm::dot(n, w));
                }
            e *= table.luminance_integral_cd_m2_sr();
            const double exact = sky.vertical_illuminance_per_zenith_luminance_sr(deg(facing));
            EXPECT_NEAR(e / exact, 1.0, 2e-4) << "type " << sky.cie_type() << ", facing " << facing;
        }
    }
}

TEST(SkyDirections, UniformSkyAndGroundGlowIntegrateInClosedForm) {
    // A uniform sky of L = 1 has integral 2 pi over the upper hemisphere and gives pi
    // on the horizontal; a ground of luminance 0.3 adds 0.3 x 2 pi below, and no
    // horizontal illuminance from above.
    const SkyDirections sky(SkyModel::uniform(), 1.0, 0.3);
    EXPECT_NEAR(sky.luminance_integral_cd_m2_sr(), 2.0 * kPi * 1.3, 1e-9);
    EXPECT_NEAR(sky.horizontal_illuminance_lx(), kPi, 1e-9);
    double below = 0.0;
    for (int row = SkyDirections::kRows / 2; row < SkyDirections::kRows; ++row)
        for (int col = 0; col < SkyDirections::kColumns; ++col) below += sky.cell_probability(row, col);
    EXPECT_NEAR(below, 0.3 / 1.3, 1e-12);
    const SkyDirections ground(std::nullopt, 0.0, 2.0);
    EXPECT_NEAR(ground.luminance_integral_cd_m2_sr(), 4.0 * kPi, 1e-9);
    EXPECT_EQ(ground.horizontal_illuminance_lx(), 0.0);
    EXPECT_THROW(SkyDirections(std::nullopt, 0.0, 0.0), std::invalid_argument);
}

TEST(SkyDirections, LuminanceIsTheCellsMean) {
    // Pictures read the table's luminance: the sky's own at cell centres to the cells'
    // resolution, the ground glow's below the horizon.
    const SkyModel sky = SkyModel::cie(12, deg(50.0), deg(170.0));
    const SkyDirections table(sky, 2000.0, 150.0);
    for (const double zenith : {5.5, 30.5, 60.5, 85.5})
        for (const double azimuth : {0.5, 90.5, 170.5, 300.5}) {
            const double exact = 2000.0 * sky.relative_luminance(deg(zenith), deg(azimuth));
            EXPECT_NEAR(table.luminance_cd_m2(sky_direction(deg(zenith), deg(azimuth))) / exact, 1.0, 2e-3)
                << zenith << " " << azimuth;
        }
    EXPECT_NEAR(table.luminance_cd_m2(Vec3(0.3, 0.2, -0.9) / glm::length(Vec3(0.3, 0.2, -0.9))), 150.0, 1e-9);
}

TEST(SkyDirections, DrawnDirectionsFollowTheTable) {
    // Chi-square of drawn directions in 9 x 12 bins of 10 x 30 degrees (upper hemisphere,
    // with the ground below as one more bin) against the table's cell probabilities,
    // for a clear sky with its peak near the sun; and every direction lies in its cell.
    const SkyModel clear = SkyModel::cie(12, deg(40.0), deg(200.0));
    const SkyDirections table(clear, 1.0, 0.05);
    constexpr int kZ = 9, kA = 12;
    std::vector<double> expected(kZ * kA + 1, 0.0);
    for (int row = 0; row < SkyDirections::kRows; ++row)
        for (int col = 0; col < SkyDirections::kColumns; ++col) {
            const int bin = row >= 90 ? kZ * kA : (row / 10) * kA + col / 30;
            expected[static_cast<std::size_t>(bin)] += table.cell_probability(row, col);
        }
    constexpr int kN = 400000;
    std::vector<double> observed(expected.size(), 0.0);
    PhiloxSampler rng(20261203);
    for (int k = 0; k < kN; ++k) {
        const auto b = rng.block(static_cast<std::uint64_t>(k), 0);
        const Vec3 w = table.sample(PhiloxSampler::uniform(b[0]), PhiloxSampler::uniform(b[1]));
        ASSERT_NEAR(glm::length(w), 1.0, 1e-12);
        const double zenith = std::acos(std::clamp(w.z, -1.0, 1.0)) * 180.0 / kPi;
        double azimuth = std::atan2(w.x, w.y) * 180.0 / kPi;
        if (azimuth < 0.0) azimuth += 360.0;
        const int bin = zenith >= 90.0
                            ? kZ * kA
                            : std::min(kZ - 1, int(zenith / 10.0)) * kA + std::min(kA - 1, int(azimuth / 30.0));
        observed[static_cast<std::size_t>(bin)] += 1.0;
    }
    double chi2 = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const double e = expected[i] * kN;
        ASSERT_GT(e, 20.0) << "bin " << i;
        chi2 += (observed[i] - e) * (observed[i] - e) / e;
    }
    const double dof = static_cast<double>(expected.size() - 1);
    EXPECT_LT(chi2, test_support::chi2_quantile(dof, test_support::kZ999)) << "dof " << dof;
}

}  // namespace
}  // namespace luxtrace
