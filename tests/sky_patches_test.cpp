// Sky patches (issue 24 §2): Tregenza's and Reinhart's subdivisions in Radiance's order,
// exact solid angles, direction <-> patch, uniform sampling and the patch means.
#include "luxtrace/light/sky_patches.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>

using luxtrace::kPi;
using luxtrace::SkyModel;
using luxtrace::SkyPatches;
using luxtrace::Vec3;

namespace {

constexpr double kDeg = kPi / 180.0;

// Radiance's reinhart.cal written out as its formulas read (the specification of the
// bins): alpha = 90 / (7 MF + .5); rnaz(r) = 1 on the top row, else MF tnaz(floor((r + .5)
// / MF)); raccum sums rnaz below a row; a direction's bin is raccum(row) + column + 1, the
// column floor((azi + inc / 2) / inc) or 0 past 359.9999 - inc / 2, azi = atan2(Dx, Dy).
int reinhart_cal_bin(int mf, const Vec3& d) {
    static const int tnaz[7] = {30, 30, 24, 24, 18, 12, 6};
    const double alpha = 90.0 / (mf * 7 + 0.5);
    const auto rnaz = [&](int r) { return r > 7 * mf - 1 ? 1 : mf * tnaz[(r * 2 + 1) / (2 * mf)]; };
    const double alt = std::asin(d.z) / kDeg;
    double azi = std::atan2(d.x, d.y);
    if (azi < 0.0) azi += 2.0 * kPi;
    azi /= kDeg;
    if (alt < 0.0) return 0;
    const int row = static_cast<int>(std::floor(alt / alpha));
    int accum = 0;
    for (int r = 0; r < row; ++r) accum += rnaz(r);
    const double inc = 360.0 / rnaz(row);
    const int col = 359.9999 - 0.5 * inc - azi > 0.0 ? static_cast<int>(std::floor((azi + 0.5 * inc) / inc)) : 0;
    return accum + col + 1;
}

// Radiance's reinsrc.cal at x1 = x2 = .5: the centre of bin b >= 1.
Vec3 reinsrc_cal_center(int mf, int bin) {
    static const int tnaz[7] = {30, 30, 24, 24, 18, 12, 6};
    const double rah = 90.0 / (mf * 7 + 0.5) * kDeg;
    int row = 0, rem = bin;
    for (;;) {
        const int n = row > 7 * mf - 1 ? 1 : mf * tnaz[row / mf];
        if (rem - n <= 0) break;
        rem -= n;
        ++row;
    }
    const int n = row > 7 * mf - 1 ? 1 : mf * tnaz[row / mf];
    const double azi = (rem - 1) * 2.0 * kPi / n, alt = (row + 0.5) * rah;
    return {std::sin(azi) * std::cos(alt), std::cos(azi) * std::cos(alt), std::sin(alt)};
}

Vec3 direction(double alt_deg, double az_deg) {
    return {std::cos(alt_deg * kDeg) * std::sin(az_deg * kDeg), std::cos(alt_deg * kDeg) * std::cos(az_deg * kDeg),
            std::sin(alt_deg * kDeg)};
}

// Altitude and azimuth (degrees, azimuth in [0, 360)) of a unit direction.
void alt_az(const Vec3& d, double& alt_deg, double& az_deg) {
    alt_deg = std::asin(std::min(1.0, d.z)) / kDeg;
    az_deg = std::atan2(d.x, d.y) / kDeg;
    if (az_deg < 0.0) az_deg += 360.0;
}

bool contains(const SkyPatches::Patch& p, double alt_deg, double az_deg, double tol) {
    if (alt_deg < p.alt_lo_deg - tol || alt_deg > p.alt_hi_deg + tol) return false;
    const auto in = [&](double a) { return a >= p.az_lo_deg - tol && a <= p.az_hi_deg + tol; };
    return in(az_deg) || in(az_deg - 360.0);
}

}  // namespace

TEST(SkyPatches, CountsAreTregenzaAndReinhart) {
    EXPECT_EQ(SkyPatches(1).count(), 145u);
    EXPECT_EQ(SkyPatches(2).count(), 577u);
    EXPECT_EQ(SkyPatches(4).count(), 2305u);
    for (int mf : {1, 2, 3, 4, 6}) {
        const SkyPatches p(mf);
        EXPECT_EQ(p.count(), static_cast<std::size_t>(144 * mf * mf + 1)) << mf;
        EXPECT_EQ(p.rows(), 7 * mf + 1);
        EXPECT_NEAR(p.row_step_deg(), 90.0 / (7 * mf + 0.5), 1e-14);
    }
    EXPECT_THROW(SkyPatches(0), std::invalid_argument);
    EXPECT_THROW(SkyPatches(-2), std::invalid_argument);
    EXPECT_THROW(SkyPatches(SkyPatches::kMaxMf + 1), std::invalid_argument);
}

TEST(SkyPatches, RowsAreTregenzasSubdivided) {
    const SkyPatches t(1);
    const std::vector<std::size_t> tregenza{30, 30, 24, 24, 18, 12, 6, 1};
    for (int r = 0; r < t.rows(); ++r) {
        EXPECT_EQ(t.row_count(r), tregenza[static_cast<std::size_t>(r)]) << r;
        const SkyPatches::Patch& first = t.patch(t.row_first(r));
        EXPECT_DOUBLE_EQ(first.alt_lo_deg, 12.0 * r);
        EXPECT_DOUBLE_EQ(first.alt_hi_deg, r < 7 ? 12.0 * (r + 1) : 90.0);
    }
    // MF 2: each Tregenza row becomes two rows of twice as many patches, the cap stays one.
    const SkyPatches r2(2);
    for (int r = 0; r < 14; ++r) EXPECT_EQ(r2.row_count(r), 2 * tregenza[static_cast<std::size_t>(r / 2)]) << r;
    EXPECT_EQ(r2.row_count(14), 1u);
}

TEST(SkyPatches, OrderIsRadiancesFromNorthTowardsEast) {
    const SkyPatches t(1);
    // Patch 0 (Radiance bin 1): lowest row, centred on north; patch 1 is 12 degrees east.
    EXPECT_EQ(t.patch(0).row, 0);
    EXPECT_DOUBLE_EQ(t.patch(0).az_lo_deg, -6.0);
    EXPECT_DOUBLE_EQ(t.patch(0).az_hi_deg, 6.0);
    const Vec3 c0 = t.center(0), c1 = t.center(1);
    EXPECT_NEAR(c0.x, 0.0, 1e-15);
    EXPECT_NEAR(c0.y, std::cos(6.0 * kDeg), 1e-15);
    EXPECT_NEAR(c0.z, std::sin(6.0 * kDeg), 1e-15);
    EXPECT_GT(c1.x, 0.0);  // east
    EXPECT_NEAR(std::atan2(c1.x, c1.y) / kDeg, 12.0, 1e-12);
    EXPECT_EQ(t.index_of(direction(6.0, 84.0)), 7u);  // column 7 of 30 is centred at 84 degrees (east-north-east)
    EXPECT_EQ(t.index_of(direction(6.0, 276.0)), 23u);
    EXPECT_EQ(t.index_of(direction(6.0, 355.0)), 0u);  // column 0 straddles north
    EXPECT_EQ(t.patch(30).row, 1);
    EXPECT_EQ(t.index_of(Vec3(0.0, 0.0, 1.0)), 144u);
    // Radiance's bins: ground 0, our patch i is bin i + 1.
    EXPECT_EQ(t.radiance_bin(0), 1u);
    EXPECT_EQ(t.radiance_bin(144), 145u);
    EXPECT_EQ(t.index_of(Vec3(0.3, 0.2, -0.5)), t.count());
    EXPECT_EQ(t.radiance_bin(t.count()), 0u);
}

TEST(SkyPatches, BinsAndCentresAreReinhartCals) {
    for (int mf : {1, 2, 4}) {
        const SkyPatches p(mf);
        // A grid kept off the bin edges (reinhart.cal's 1e-4-degree tolerance at north).
        for (double alt = 0.013; alt < 90.0; alt += 0.2371)
            for (double az = 0.0071; az < 360.0; az += 0.3119) {
                const Vec3 d = direction(alt, az);
                ASSERT_EQ(p.radiance_bin(p.index_of(d)), static_cast<std::size_t>(reinhart_cal_bin(mf, d)))
                    << "MF " << mf << " alt " << alt << " az " << az;
            }
        for (std::size_t i = 0; i < p.count(); ++i) {
            const Vec3 c = p.center(i), r = reinsrc_cal_center(mf, static_cast<int>(i) + 1);
            ASSERT_NEAR(glm::length(c - r), 0.0, 1e-12) << "MF " << mf << " patch " << i;
        }
    }
}

TEST(SkyPatches, SolidAnglesAreExactAndFillTheHemisphere) {
    for (int mf : {1, 2, 4, 6}) {
        const SkyPatches p(mf);
        const double alpha = p.row_step_deg() * kDeg;
        double omega = 0.0, projected = 0.0;
        for (std::size_t i = 0; i < p.count(); ++i) {
            omega += p.solid_angle_sr(i);
            projected += p.projected_solid_angle_sr(i);
        }
        EXPECT_NEAR(omega, 2.0 * kPi, 1e-12) << mf;
        EXPECT_NEAR(projected, kPi, 1e-12) << mf;
        // gendaymtx's rh_dom: the zenith cap 2 pi (1 - cos(alpha / 2)), a row's patch
        // 2 pi (sin alpha (r + 1) - sin alpha r) / n.
        EXPECT_NEAR(p.solid_angle_sr(p.count() - 1), 2.0 * kPi * (1.0 - std::cos(0.5 * alpha)), 1e-14);
        const int r = 3 * mf;
        EXPECT_NEAR(p.solid_angle_sr(p.row_first(r)),
                    2.0 * kPi * (std::sin(alpha * (r + 1)) - std::sin(alpha * r)) / p.row_count(r), 1e-14);
    }
}

TEST(SkyPatches, CentresAndSamplesMapBackToTheirPatch) {
    for (int mf : {1, 2, 4}) {
        const SkyPatches p(mf);
        std::mt19937_64 rng(20240 + mf);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        const int per_patch = mf == 4 ? 16 : 200;
        for (std::size_t i = 0; i < p.count(); ++i) {
            ASSERT_EQ(p.index_of(p.center(i)), i) << "MF " << mf;
            ASSERT_NEAR(glm::length(p.center(i)), 1.0, 1e-15);
            for (int k = 0; k < per_patch; ++k) {
                const Vec3 d = p.sample(i, u(rng), u(rng));
                ASSERT_NEAR(glm::length(d), 1.0, 1e-14);
                ASSERT_EQ(p.index_of(d), i) << "MF " << mf << " sample " << k;
            }
        }
    }
}

TEST(SkyPatches, EveryDirectionLiesInExactlyOnePatch) {
    for (int mf : {1, 2}) {
        const SkyPatches p(mf);
        for (double alt = 0.0; alt < 90.0; alt += 0.73)
            for (double az = 0.0; az < 360.0; az += 0.91) {
                double a = 0.0, z = 0.0;
                alt_az(direction(alt, az), a, z);
                const std::size_t i = p.index_of(direction(alt, az));
                ASSERT_LT(i, p.count());
                ASSERT_TRUE(contains(p.patch(i), a, z, 1e-9)) << "alt " << alt << " az " << az;
                // Away from the edges no other patch holds it.
                int holders = 0;
                for (std::size_t j = 0; j < p.count(); ++j) holders += contains(p.patch(j), a, z, -1e-9) ? 1 : 0;
                ASSERT_LE(holders, 1) << "alt " << alt << " az " << az;
            }
    }
}

// Pearson's chi-square over 6 x 6 sub-cells of equal solid angle (equal steps in sin
// altitude and azimuth) of a row patch and of the zenith cap.
TEST(SkyPatches, SamplesAreUniformInSolidAngle) {
    const SkyPatches p(2);
    constexpr int kCells = 6, kSamples = 36000;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i : {p.row_first(5) + 17, p.count() - 1}) {
        const SkyPatches::Patch& patch = p.patch(i);
        const double s_lo = std::sin(patch.alt_lo_deg * kDeg), s_hi = std::sin(patch.alt_hi_deg * kDeg);
        std::vector<int> counts(kCells * kCells, 0);
        for (int k = 0; k < kSamples; ++k) {
            const Vec3 d = p.sample(i, u(rng), u(rng));
            double az = std::atan2(d.x, d.y) / kDeg;
            if (az < patch.az_lo_deg) az += 360.0;
            const int a = std::min(kCells - 1, static_cast<int>((d.z - s_lo) / (s_hi - s_lo) * kCells));
            const int b = std::min(kCells - 1, static_cast<int>((az - patch.az_lo_deg) /
                                                                (patch.az_hi_deg - patch.az_lo_deg) * kCells));
            ++counts[static_cast<std::size_t>(a * kCells + b)];
        }
        const double expected = static_cast<double>(kSamples) / (kCells * kCells);
        double chi2 = 0.0;
        for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
        EXPECT_LT(chi2, luxtrace::test_support::chi2_quantile(kCells * kCells - 1, luxtrace::test_support::kZ999))
            << "patch " << i;
    }
}

TEST(SkyPatches, MeansOfPolynomialsAreExact) {
    const SkyPatches p(2);
    const double a = 0.7, b = 2.3;
    // Rows: 2 nodes integrate (a + b s) s exactly; the cap (zenith-angle rule) to 1e-13 at 8.
    for (int nodes : {2, 8}) {
        const auto constant = p.cosine_weighted_means([](const Vec3&) { return 4.5; }, nodes);
        const auto constant_plain = p.solid_angle_means([](const Vec3&) { return 4.5; }, nodes);
        const auto linear = p.cosine_weighted_means([&](const Vec3& d) { return a + b * d.z; }, nodes);
        const auto linear_plain = p.solid_angle_means([&](const Vec3& d) { return a + b * d.z; }, nodes);
        for (std::size_t i = 0; i < p.count(); ++i) {
            EXPECT_NEAR(constant[i], 4.5, 1e-13);
            EXPECT_NEAR(constant_plain[i], 4.5, 1e-13);
            if (nodes == 2 && i + 1 == p.count()) continue;
            const double s0 = std::sin(p.patch(i).alt_lo_deg * kDeg), s1 = std::sin(p.patch(i).alt_hi_deg * kDeg);
            // integral of (a + b s) s ds over integral of s ds; plain: a + b times the mean s.
            const double m1 = (s1 * s1 - s0 * s0) / 2.0, m2 = (s1 * s1 * s1 - s0 * s0 * s0) / 3.0;
            EXPECT_NEAR(linear[i], (a * m1 + b * m2) / m1, 1e-13) << i;
            EXPECT_NEAR(linear_plain[i], a + b * 0.5 * (s0 + s1), 1e-13) << i;
        }
    }
    EXPECT_THROW(p.solid_angle_means([](const Vec3&) { return 1.0; }, 0), std::invalid_argument);
    EXPECT_THROW(p.solid_angle_means([](const Vec3&) { return 1.0; }, 65), std::invalid_argument);
}

// sum_i mean_i * projected_i is the sky's horizontal illuminance: the overcast sky's
// (1 + 2 cos Z) / 3 gives 7 pi / 9 in closed form, and the model's own adaptive quadrature
// (with breakpoints at the sun) agrees; clear skies (types 12 and 7, the sun as cusp) are
// compared with the model's quadrature, the sun low, high, and inside the zenith cap.
TEST(SkyPatches, PatchMeansCarryTheSkysHorizontalIlluminance) {
    const auto illuminance = [](const SkyPatches& p, const SkyModel& sky, const std::optional<Vec3>& cusp) {
        const auto mean = p.cosine_weighted_means([&](const Vec3& d) { return sky.relative_luminance(d); }, 8, cusp);
        double e = 0.0;
        for (std::size_t i = 0; i < p.count(); ++i) e += mean[i] * p.projected_solid_angle_sr(i);
        return e;
    };
    const SkyModel overcast = SkyModel::cie(16, 0.0, 0.0);
    for (int mf : {1, 2, 4}) {
        const SkyPatches p(mf);
        const double e = illuminance(p, overcast, std::nullopt);
        EXPECT_NEAR(e / (7.0 * kPi / 9.0), 1.0, 1e-12) << mf;
        EXPECT_NEAR(e / overcast.horizontal_illuminance_per_zenith_luminance_sr(), 1.0, 1e-6) << mf;
        for (int type : {7, 12})
            for (double sun_alt_deg : {8.0, 47.0, 80.0, 86.5}) {
                const double z = (90.0 - sun_alt_deg) * kDeg, az = 200.0 * kDeg;
                const SkyModel clear = SkyModel::cie(type, z, az);
                EXPECT_NEAR(illuminance(p, clear, luxtrace::sky_direction(z, az)) /
                                clear.horizontal_illuminance_per_zenith_luminance_sr(),
                            1.0, 1e-6)
                    << "MF " << mf << " type " << type << " sun at " << sun_alt_deg;
            }
    }
}

// The sun's patch: cut at the sun, 8 nodes agree with 40 to 1e-5 of its mean; not cut,
// the kink costs accuracy (within 1e-3, and worse than cut).
TEST(SkyPatches, CuspCutResolvesTheSunsPatch) {
    const SkyPatches p(1);
    for (double sun_alt_deg : {30.0, 87.0}) {
        const double z = (90.0 - sun_alt_deg) * kDeg, az = 131.0 * kDeg;
        const Vec3 sun = luxtrace::sky_direction(z, az);
        const SkyModel clear = SkyModel::cie(12, z, az);
        const auto L = [&](const Vec3& d) { return clear.relative_luminance(d); };
        const std::size_t i = p.index_of(sun);
        const double fine = p.cosine_weighted_means(L, 40, sun)[i];
        const double cut = p.cosine_weighted_means(L, 8, sun)[i], uncut = p.cosine_weighted_means(L, 8)[i];
        EXPECT_NEAR(cut / fine, 1.0, 1e-5) << sun_alt_deg;
        EXPECT_NEAR(p.solid_angle_means(L, 8, sun)[i] / p.solid_angle_means(L, 40, sun)[i], 1.0, 1e-5);
        EXPECT_NEAR(uncut / fine, 1.0, 1e-3) << sun_alt_deg;
        EXPECT_LT(std::abs(cut - fine), std::abs(uncut - fine)) << sun_alt_deg;
    }
}
