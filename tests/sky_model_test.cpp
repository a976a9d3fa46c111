// Sky luminance distributions (docs/DAYLIGHT.md, "Sky luminance distributions"): the CIE
// standard general skies are 1 at the zenith, symmetric about the sun's vertical plane,
// azimuth-independent exactly when their indicatrix is flat (c = e = 0) and brightest
// towards the sun otherwise; the illuminances by quadrature meet the closed forms of the
// uniform and traditional overcast skies and an independent brute-force rule for the rest.
#include "luxtrace/light/sky_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace luxtrace {
namespace {

double deg(double d) { return d * kPi / 180.0; }

constexpr double kQuadratureTol = 1e-6;  // relative accuracy the quadrature promises

// Sun positions the properties must hold for: (zenith, azimuth) in degrees.
constexpr double kSuns[][2] = {{0.0, 0.0}, {15.0, 90.0}, {30.0, 180.0}, {50.0, 200.0}, {60.0, 300.0}, {85.0, 45.0}};

// The four facades: north, east, south, west.
constexpr double kFacades[] = {0.0, 90.0, 180.0, 270.0};

// Brute force: the product midpoint rule in (Z, alpha) on an n x 2n grid, for E / L_z with
// the plane's normal horizontal towards facing_deg or, with vertical = false, straight up.
double midpoint_illuminance(const SkyModel& sky, bool vertical, double facing_deg, int n) {
    const double dz = 0.5 * kPi / n, da = kPi / n;
    const double a0 = vertical ? deg(facing_deg) - 0.5 * kPi : 0.0;
    const int na = vertical ? n : 2 * n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double z = (i + 0.5) * dz;
        for (int j = 0; j < na; ++j) {
            const double a = a0 + (j + 0.5) * da;
            const double cos_incidence = vertical ? std::sin(z) * std::cos(a - deg(facing_deg)) : std::cos(z);
            sum += sky.relative_luminance(z, a) * cos_incidence * std::sin(z);
        }
    }
    return sum * dz * da;
}

// The midpoint rule's error is c h^2 + O(h^3) (the kink at the sun costs one cell):
// Richardson extrapolation from n and 2n removes the h^2 term.
double brute_force_illuminance(const SkyModel& sky, bool vertical, double facing_deg) {
    return (4.0 * midpoint_illuminance(sky, vertical, facing_deg, 800) -
            midpoint_illuminance(sky, vertical, facing_deg, 400)) /
           3.0;
}

TEST(SkyTable, ParametersAsPublished) {
    // Spot checks of ISO 15469 table 1 and the groups it is made of: types 1-2 share
    // gradation group I, types 12 and 11 indicatrix group 4.
    const CieSkyParameters t1 = cie_general_sky_parameters(1), t12 = cie_general_sky_parameters(12);
    EXPECT_EQ(t1.a, 4.0);
    EXPECT_EQ(t1.b, -0.70);
    EXPECT_EQ(t12.a, -1.0);
    EXPECT_EQ(t12.b, -0.32);
    EXPECT_EQ(t12.c, 10.0);
    EXPECT_EQ(t12.d, -3.0);
    EXPECT_EQ(t12.e, 0.45);
    EXPECT_EQ(cie_general_sky_parameters(2).a, t1.a);
    EXPECT_EQ(cie_general_sky_parameters(11).c, t12.c);
    EXPECT_EQ(cie_general_sky_parameters(15).c, 24.0);
    EXPECT_THROW(cie_general_sky_parameters(0), std::invalid_argument);
    EXPECT_THROW(cie_general_sky_parameters(16), std::invalid_argument);
    EXPECT_THROW(SkyModel::cie(17, 0.5, 0.0), std::invalid_argument);
    EXPECT_THROW(SkyModel::cie(12, deg(95.0), 0.0), std::invalid_argument);
    EXPECT_NO_THROW(SkyModel::cie(16, deg(95.0), 0.0));  // the traditional sky has no sun
}

TEST(SkyLuminance, QuotedValues) {
    // Values quoted for the model by an independent implementation (colour-science's
    // CIE 2003 sky, to 7 decimals): element Z = 45, alpha = 180 deg under a sun at
    // Z_s = 30, alpha_s = 0 deg. By hand for type 12: chi = 75 deg, f(chi) = 1.137296,
    // f(Z_s) = 3.326463, phi(45) = 0.363950, phi(0) = 0.273851.
    EXPECT_NEAR(SkyModel::cie(1, deg(30), 0.0).relative_luminance(deg(45), deg(180)), 0.83258465, 6e-8);
    EXPECT_NEAR(SkyModel::cie(12, deg(30), 0.0).relative_luminance(deg(45), deg(180)), 0.45445245, 6e-8);
    // Type 16 at the horizon: (1 + 2 sin 0) / 3.
    EXPECT_NEAR(SkyModel::cie(16, 0.0, 0.0).relative_luminance(deg(90), 0.0), 1.0 / 3.0, 1e-15);
}

TEST(SkyLuminance, DirectionConvention) {
    // North = +y, east = +x, azimuth clockwise from north: a direction and its angles
    // give the same luminance.
    const Vec3 east = sky_direction(deg(60), deg(90));
    EXPECT_NEAR(east.x, std::sin(deg(60)), 1e-15);
    EXPECT_NEAR(east.y, 0.0, 1e-15);
    const SkyModel sky = SkyModel::cie(12, deg(40), deg(120));
    for (double z : {10.0, 45.0, 80.0})
        for (double a : {0.0, 90.0, 135.0, 250.0})
            EXPECT_NEAR(sky.relative_luminance(sky_direction(deg(z), deg(a))), sky.relative_luminance(deg(z), deg(a)),
                        1e-12);
    // Towards the sun is brighter than away from it for a clear sky.
    EXPECT_GT(sky.relative_luminance(sky_direction(deg(40), deg(120))),
              sky.relative_luminance(sky_direction(deg(40), deg(300))));
    EXPECT_EQ(sky.relative_luminance(Vec3(0.0, 1.0, -0.1)), 0.0);  // below the horizon
}

TEST(SkyLuminance, ZenithIsOneAndSymmetricAboutTheSunsPlane) {
    for (int type = 1; type <= 16; ++type)
        for (const auto& sun : kSuns) {
            const SkyModel sky = SkyModel::cie(type, deg(sun[0]), deg(sun[1]));
            EXPECT_NEAR(sky.relative_luminance(0.0, deg(17.0)), 1.0, 1e-14) << "type " << type;
            EXPECT_NEAR(sky.relative_luminance(Vec3(0.0, 0.0, 2.0)), 1.0, 1e-14) << "type " << type;
            for (double z : {5.0, 30.0, 60.0, 89.0})
                for (double d : {1.0, 20.0, 90.0, 170.0})
                    EXPECT_NEAR(sky.relative_luminance(deg(z), deg(sun[1] + d)),
                                sky.relative_luminance(deg(z), deg(sun[1] - d)), 1e-13)
                        << "type " << type << " Z " << z << " offset " << d;
        }
}

TEST(SkyLuminance, AzimuthIndependentExactlyWhenIndicatrixIsFlat) {
    // f(chi) = 1 for all chi iff c = e = 0 (types 1, 3, 5): then only the zenith angle counts.
    int flat = 0;
    for (int type = 1; type <= 15; ++type) {
        const CieSkyParameters p = cie_general_sky_parameters(type);
        const bool is_flat = p.c == 0.0 && p.e == 0.0;
        flat += is_flat;
        const SkyModel sky = SkyModel::cie(type, deg(45), deg(135));
        double lo = 1e300, hi = 0.0;
        for (double a = 0.0; a < 360.0; a += 15.0) {
            const double l = sky.relative_luminance(deg(60), deg(a));
            lo = std::min(lo, l);
            hi = std::max(hi, l);
        }
        if (is_flat) EXPECT_NEAR(hi / lo, 1.0, 1e-14) << "type " << type;
        else EXPECT_GT(hi / lo, 1.05) << "type " << type;
    }
    EXPECT_EQ(flat, 3);
}

TEST(SkyLuminance, SunnySkiesBrightestTowardsTheSun) {
    for (int type = 1; type <= 15; ++type) {
        const CieSkyParameters p = cie_general_sky_parameters(type);
        if (p.c == 0.0) continue;
        for (double sun_z : {30.0, 60.0}) {
            const SkyModel sky = SkyModel::cie(type, deg(sun_z), deg(200));
            // Along the sun's almucantar, luminance falls monotonically away from the sun as
            // far as 90 deg of azimuth (chi < 90 deg; beyond, e cos^2 chi brightens the
            // anti-solar sky again), and the anti-solar point is darker than the sun's side.
            const double anti = sky.relative_luminance(deg(sun_z), deg(20));
            EXPECT_LT(anti, sky.relative_luminance(deg(sun_z), deg(210))) << "type " << type;
            double prev = sky.relative_luminance(deg(sun_z), deg(201));
            for (double d = 10.0; d <= 90.0; d += 10.0) {
                const double l = sky.relative_luminance(deg(sun_z), deg(200 + d));
                EXPECT_LT(l, prev) << "type " << type << " sun Z " << sun_z << " offset " << d;
                prev = l;
            }
        }
    }
    // With a solar corona (indicatrix groups 4-6: types 8, 11-15) the brightest element of
    // the whole sky lies next to the sun.
    for (int type : {8, 11, 12, 13, 14, 15}) {
        const SkyModel sky = SkyModel::cie(type, deg(50), deg(200));
        double best = 0.0, best_z = 0.0, best_a = 0.0;
        for (double z = 0.5; z < 90.0; z += 1.0)
            for (double a = 0.5; a < 360.0; a += 1.0)
                if (const double l = sky.relative_luminance(deg(z), deg(a)); l > best) {
                    best = l;
                    best_z = z;
                    best_a = a;
                }
        EXPECT_NEAR(best_z, 50.0, 1.0) << "type " << type;
        EXPECT_NEAR(best_a, 200.0, 1.0) << "type " << type;
    }
}

TEST(SkyIlluminance, UniformSkiesMeetClosedForms) {
    // L = L_z everywhere: E_h = L_z int cos Z dOmega = pi L_z; a vertical plane sees half of
    // that, 2 int_0^{pi/2} sin^2 Z dZ = pi/2.
    for (const SkyModel& sky : {SkyModel::uniform(), SkyModel::cie(5, deg(30), deg(180)), SkyModel::cie(5, 0.0, 0.0),
                                SkyModel::cie(5, deg(80), deg(10))}) {
        EXPECT_NEAR(sky.horizontal_illuminance_per_zenith_luminance_sr() / kPi, 1.0, kQuadratureTol);
        for (double f : kFacades)
            EXPECT_NEAR(sky.vertical_illuminance_per_zenith_luminance_sr(deg(f)) / (0.5 * kPi), 1.0, kQuadratureTol);
    }
}

TEST(SkyIlluminance, TraditionalOvercastMeetsClosedForms) {
    // L = L_z (1 + 2 cos Z) / 3.
    // E_h / L_z = 2 pi int_0^{pi/2} (1 + 2 cos Z)/3 cos Z sin Z dZ = (2 pi / 3)(1/2 + 2/3) = 7 pi / 9.
    // A vertical plane facing any azimuth: E_v / L_z = int_{-pi/2}^{pi/2} cos a da
    // int_0^{pi/2} (1 + 2 cos Z)/3 sin^2 Z dZ = (2/3)(pi/4 + 2/3) = pi/6 + 4/9 = (pi/2 + 4/3)/3.
    const SkyModel sky = SkyModel::cie(16, deg(30), 0.0);
    EXPECT_NEAR(sky.horizontal_illuminance_per_zenith_luminance_sr() / (7.0 * kPi / 9.0), 1.0, kQuadratureTol);
    for (double f : kFacades)
        EXPECT_NEAR(sky.vertical_illuminance_per_zenith_luminance_sr(deg(f)) / (kPi / 6.0 + 4.0 / 9.0), 1.0,
                    kQuadratureTol);
}

TEST(SkyIlluminance, AzimuthIndependentSkiesLightEveryFacadeAlike) {
    for (int type : {1, 3, 5, 16}) {
        const SkyModel sky = SkyModel::cie(type, deg(40), deg(160));
        const double north = sky.vertical_illuminance_per_zenith_luminance_sr(0.0);
        for (double f : kFacades)
            EXPECT_NEAR(sky.vertical_illuminance_per_zenith_luminance_sr(deg(f)) / north, 1.0, kQuadratureTol)
                << "type " << type << " facing " << f;
    }
}

TEST(SkyIlluminance, AzimuthIndependentSkiesMatchOneDimensionalIntegral) {
    // For c = e = 0, E_h / L_z = 2 pi int_0^1 phi(Z)/phi(0) u du with u = cos Z, by a
    // composite Simpson rule in u (phi is smooth in u, exp(b/u) -> 0 at u = 0).
    for (int type : {1, 3}) {
        const CieSkyParameters p = cie_general_sky_parameters(type);
        const auto integrand = [&](double u) {
            return u > 0.0 ? (1.0 + p.a * std::exp(p.b / u)) / (1.0 + p.a * std::exp(p.b)) * u : 0.0;
        };
        const int n = 20000;
        double s = integrand(0.0) + integrand(1.0);
        for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * integrand(static_cast<double>(i) / n);
        const double expected = 2.0 * kPi * s / (3.0 * n);
        EXPECT_NEAR(SkyModel::cie(type, deg(35), 0.0).horizontal_illuminance_per_zenith_luminance_sr() / expected, 1.0,
                    kQuadratureTol)
            << "type " << type;
    }
}

TEST(SkyIlluminance, SunnySkiesMatchBruteForce) {
    // The adaptive quadrature against extrapolated midpoint rules, for a range of sky types and sun positions.
    for (int type : {2, 9, 15})
        for (const auto& sun : {std::pair{30.0, 180.0}, std::pair{60.0, 100.0}}) {
            const SkyModel sky = SkyModel::cie(type, deg(sun.first), deg(sun.second));
            const double eh = sky.horizontal_illuminance_per_zenith_luminance_sr();
            EXPECT_NEAR(eh / brute_force_illuminance(sky, false, 0.0), 1.0, kQuadratureTol)
                << "type " << type << " sun Z " << sun.first;
            for (double f : {sun.second, sun.second + 90.0}) {
                const double ev = sky.vertical_illuminance_per_zenith_luminance_sr(deg(f));
                EXPECT_NEAR(ev / brute_force_illuminance(sky, true, f), 1.0, kQuadratureTol)
                    << "type " << type << " sun Z " << sun.first << " facing " << f;
            }
        }
}

TEST(SkyIlluminance, SunFacingFacadeIsBrightest) {
    // A sky that brightens towards the sun lights the facade facing the sun more than the
    // one facing away, and the two side facades alike (mirror symmetry).
    for (int type : {2, 6, 12, 15}) {
        const SkyModel sky = SkyModel::cie(type, deg(60), deg(135));
        const double toward = sky.vertical_illuminance_per_zenith_luminance_sr(deg(135));
        const double away = sky.vertical_illuminance_per_zenith_luminance_sr(deg(315));
        const double left = sky.vertical_illuminance_per_zenith_luminance_sr(deg(45));
        const double right = sky.vertical_illuminance_per_zenith_luminance_sr(deg(225));
        EXPECT_GT(toward, 1.05 * away) << "type " << type;
        EXPECT_NEAR(left / right, 1.0, kQuadratureTol) << "type " << type;
    }
}

}  // namespace
}  // namespace luxtrace
