// The exact sky-component integration of daylight_reference.hpp against closed forms, and
// luxtrace's sky light through the CIE 171:2006 §5.9-5.14 openings against that integration
// (docs/VALIDATION.md, "CIE 171:2006 daylight test cases").
#include "cie171_cases.hpp"
#include "daylight_reference.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace luxtrace {
namespace {

using daylight_reference::Polygon;
using daylight_reference::rectangle;
using daylight_reference::SkyComponentQuery;

constexpr double kRelTol = 1e-6;

// Lambert's contour formula: the configuration factor from a differential area with unit
// normal n at p to a polygon is (1 / 2 pi) sum over edges of the angle the edge subtends
// times n . (unit normal of the plane through p and the edge), vertices counter-clockwise
// seen from p. Exact for any polygon wholly above the receiving plane.
double lambert_factor(const Vec3& p, const Vec3& n, const Polygon& poly) {
    double sum = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3 a = glm::normalize(poly[i] - p), b = glm::normalize(poly[(i + 1) % poly.size()] - p);
        const Vec3 c = glm::cross(a, b);
        sum += std::atan2(glm::length(c), glm::dot(a, b)) * glm::dot(n, glm::normalize(c));
    }
    return std::abs(sum) / (2.0 * kPi);
}

// A differential area facing a parallel rectangle, normal through one corner, sides a, b at
// distance c (Howell's catalogue, configuration A-3).
double corner_factor(double a, double b, double c) {
    const double x = a / c, y = b / c;
    return (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
           (2.0 * kPi);
}

TEST(DaylightReference, UniformSkyThroughAParallelRectangleIsItsConfigurationFactor) {
    // Under a uniform sky E = L F pi and E_h,ext = L pi, so SC = F.
    const SkyModel sky = SkyModel::uniform();
    const double a = 1.5, b = 0.7, c = 2.0;
    const Polygon corner = {Vec3(0, 0, c), Vec3(a, 0, c), Vec3(a, b, c), Vec3(0, b, c)};
    const double sc = daylight_reference::sky_component(sky, {Vec3(0.0), Vec3(0, 0, 1), corner, {}, {}});
    EXPECT_NEAR(sc, corner_factor(a, b, c), kRelTol * sc);
    // The 5.9 roof opening seen from the middle of the floor: four corner rectangles.
    const Polygon roof = rectangle(Vec3(2, 2, 3), Vec3(2, 0, 0), Vec3(0, 2, 0));
    const double centre = daylight_reference::sky_component(sky, {Vec3(2, 2, 0), Vec3(0, 0, 1), roof, {}, {}});
    EXPECT_NEAR(centre, 4.0 * corner_factor(2, 2, 3), kRelTol * centre);
}

TEST(DaylightReference, UniformSkyThroughAnyOpeningIsLambertsContourIntegral) {
    const SkyModel sky = SkyModel::uniform();
    struct Probe {
        Vec3 p, n;
        Polygon opening;
    };
    const Probe probes[] = {
        // 5.9 point A: 0.25 m below the whole-roof opening, whose edge lies in its plane.
        {Vec3(2, 4, 2.75), Vec3(0, -1, 0), rectangle(Vec3(2, 2, 3), Vec3(2, 0, 0), Vec3(0, 2, 0))},
        // Floor points in front of a window, perpendicular planes (5.11 points N and G).
        {Vec3(2, 0.25, 0), Vec3(0, 0, 1), rectangle(Vec3(2, 0, 1.5), Vec3(2, 0, 0), Vec3(0, 0, 1.5))},
        {Vec3(2, 3.75, 0), Vec3(0, 0, 1), rectangle(Vec3(2, 0, 1.5), Vec3(1, 0, 0), Vec3(0, 0, 0.5))},
        // A tilted receiver and a tilted, off-axis opening.
        {Vec3(0.3, -0.2, 0.1), glm::normalize(Vec3(0.3, 0.2, 1)),
         rectangle(Vec3(1, 1, 2), glm::normalize(Vec3(1, 0, 0.4)) * 0.8, Vec3(0, 0.6, 0))},
    };
    for (const Probe& pr : probes) {
        const double sc = daylight_reference::sky_component(sky, {pr.p, pr.n, pr.opening, {}, {}});
        EXPECT_NEAR(sc, lambert_factor(pr.p, pr.n, pr.opening), kRelTol * sc) << "point " << pr.p.x << ", " << pr.p.y;
    }
}

TEST(DaylightReference, OvercastSkyOnTheAxisOfAHorizontalSquareIsARadialIntegral) {
    // L = L_z (1 + 2 cos Z) / 3: the ring integral up to Z_max in closed form,
    //   int_0^Zm L cos Z sin Z dZ / L_z = sin^2 Zm / 6 + 2 (1 - cos^3 Zm) / 9,
    // Z_max(phi) = atan(w / (h cos phi)) for phi in [0, pi/4] (eighth of the square), and
    // E_h,ext = 7 pi L_z / 9.
    const SkyModel sky = SkyModel::cie(16, 0.0, 0.0);
    const double w = 1.3, h = 2.1;  // half-width, height
    const auto ring = [&](double phi) {
        const double zm = std::atan(w / (h * std::cos(phi)));
        return std::pow(std::sin(zm), 2) / 6.0 + 2.0 * (1.0 - std::pow(std::cos(zm), 3)) / 9.0;
    };
    const double e = 8.0 *
                     boost::math::quadrature::gauss_kronrod<double, 31>::integrate(ring, 0.0, 0.25 * kPi, 15, 1e-13);
    const double expected = e / (7.0 * kPi / 9.0);
    const Polygon square = rectangle(Vec3(0, 0, h), Vec3(w, 0, 0), Vec3(0, w, 0));
    const double sc = daylight_reference::sky_component(sky, {Vec3(0.0), Vec3(0, 0, 1), square, {}, {}});
    EXPECT_NEAR(sky.horizontal_illuminance_per_zenith_luminance_sr(), 7.0 * kPi / 9.0, 1e-8);
    EXPECT_NEAR(sc, expected, kRelTol * expected);
}

TEST(DaylightReference, ObstructionsHideWhatTheirConeCovers) {
    const SkyModel sky = cie171::report_sky(12);
    const Polygon window = rectangle(Vec3(2, 0, 1.5), Vec3(1, 0, 0), Vec3(0, 0, 0.5));
    const Vec3 p(2, 2, 0), up(0, 0, 1);
    // A plate beyond the window that covers its whole cone hides it.
    const Polygon big = rectangle(Vec3(2, -1, 3), Vec3(5, 0, 0), Vec3(0, 0, 3));
    EXPECT_EQ(daylight_reference::sky_component(sky, {p, up, window, {big}, {}}), 0.0);
    // A plate whose cone covers exactly the window's upper half (its edges on the rays
    // through the window's middle line and top edge, scaled from p) leaves the lower half.
    const double s = 3.0;  // plate at y = -(s - 1) * 2: every ray through the window scaled by s
    const Polygon upper_half = rectangle(Vec3(2, 0, 1.75), Vec3(1, 0, 0), Vec3(0, 0, 0.25));
    Polygon plate;
    for (const Vec3& v : upper_half) plate.push_back(p + s * (v - p));
    const Polygon lower_half = rectangle(Vec3(2, 0, 1.25), Vec3(1, 0, 0), Vec3(0, 0, 0.25));
    const double seen = daylight_reference::sky_component(sky, {p, up, window, {plate}, {}});
    const double lower = daylight_reference::sky_component(sky, {p, up, lower_half, {}, {}});
    EXPECT_NEAR(seen, lower, kRelTol * lower);
    // An obstruction beside the cone changes nothing.
    const Polygon aside = rectangle(Vec3(20, -3, 1), Vec3(1, 0, 0), Vec3(0, 0, 1));
    const double open = daylight_reference::sky_component(sky, {p, up, window, {}, {}});
    EXPECT_NEAR(daylight_reference::sky_component(sky, {p, up, window, {aside}, {}}), open, kRelTol * open);
}

TEST(DaylightReference, PaneTransmittanceIsTwoFresnelInterfacesWithInternalReflections) {
    const double n = 1.52, r0 = std::pow((n - 1) / (n + 1), 2);
    // Without absorption the internal reflections sum to (1 - R) / (1 + R) at normal incidence.
    EXPECT_NEAR(daylight_reference::pane_transmittance(1.0, (1 - r0) / (1 + r0), n), (1 - r0) / (1 + r0), 1e-12);
    EXPECT_NEAR(daylight_reference::pane_transmittance(1.0, 0.88, n), 0.88, 1e-12);
    double previous = 1.0;
    for (int deg = 0; deg <= 90; deg += 5) {
        const double t = daylight_reference::pane_transmittance(std::cos(deg * kPi / 180.0), 0.88, n);
        EXPECT_LE(t, previous) << deg << " deg";
        previous = t;
    }
    EXPECT_NEAR(previous, 0.0, 1e-12);  // grazing incidence reflects everything
    EXPECT_THROW(daylight_reference::pane_transmittance(1.0, 0.95, n), std::invalid_argument);
}

TEST(DaylightReference, SymmetricSkiesGiveSymmetricRoofPoints) {
    // Types 1, 5 and 16 do not depend on the sun's azimuth: the 5.9 floor row is symmetric
    // about the room's middle, which also checks the point order of the case table.
    for (const cie171::Case& c : cie171::report_cases()) {
        if (c.id != "5.9 1x1") continue;
        for (const int type : {1, 5, 16}) {
            const double g = cie171::exact_sc_percent(c, c.points[6], type);
            const double n = cie171::exact_sc_percent(c, c.points[13], type);
            EXPECT_NEAR(g, n, 1e-6 * g) << "type " << type;
        }
    }
}

// ---------------------------------------------------------------------------------------
// luxtrace's sky light through the openings (tests/data/cie171/*.toml). The geometry below
// must match the scene files (cie171::run_cases). Each detector cell (3 m x 0.5 m, centred
// on a report point) is judged by the run's own error, z = (E - E_ref) / (sigma_rel E) with
// E_ref = SC x 10 000 lx averaged over the cell (cie171::exact_cell_lx): |z| < 5 in every
// cell and the mean z^2 within 1 +- 5 sqrt(2 / K) per strip (docs/VALIDATION.md, "luxtrace
// runs").

TEST(Cie171Run, SkyComponentsWithinTheRunsOwnErrors) {
    for (const cie171::RunCase& rc : cie171::run_cases()) {
        test_support::ScratchDir dir("cie171_" + rc.scene);
        const std::filesystem::path out = dir.path() / "result.h5";
        const std::filesystem::path scene = std::filesystem::path(LUXTRACE_TEST_DATA_DIR) / "cie171" /
                                            (rc.scene + ".toml");
        const std::string cmd = std::string("\"") + LUXTRACE_BINARY + "\" run \"" + scene.string() + "\" --output \"" +
                                out.string() + "\" --quiet --threads 2 --photons " + std::to_string(rc.photons) +
                                " --seed " + std::to_string(rc.seed) + " > /dev/null";
        const int status = std::system(cmd.c_str());
        ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << rc.scene;
        const ResultReader r(out);
        for (const cie171::Strip& s : rc.strips) {
            const std::vector<double> value = r.f64("/detectors/" + s.name + "/value");
            const std::vector<double> sigma_rel = r.f64("/detectors/" + s.name + "/sigma_rel");
            ASSERT_EQ(value.size(), static_cast<std::size_t>(s.cells)) << rc.scene << " " << s.name;
            double sum_z2 = 0.0;
            int judged = 0;
            for (int k = 0; k < s.cells; ++k) {
                const double ref = cie171::exact_cell_lx(rc, s, k);
                if (ref == 0.0) {  // the masks hide the sky from the whole cell: no photon may arrive
                    EXPECT_EQ(value[k], 0.0) << rc.scene << " " << s.name << " cell " << k;
                    continue;
                }
                const double z = (value[k] - ref) / (sigma_rel[k] * value[k]);
                EXPECT_LT(std::abs(z), 5.0) << rc.scene << " " << s.name << " cell " << k << ": " << value[k]
                                            << " lx, exact " << ref << " lx, sigma_rel " << sigma_rel[k];
                sum_z2 += z * z;
                ++judged;
                std::cout << "[cie171] " << rc.scene << " " << s.name << " cell " << k << ": SC "
                          << 100.0 * value[k] / cie171::kDiffuseHorizontalLx << " % +- "
                          << 100.0 * sigma_rel[k] * value[k] / cie171::kDiffuseHorizontalLx << ", exact "
                          << 100.0 * ref / cie171::kDiffuseHorizontalLx << " %, z " << z << '\n';
            }
            EXPECT_NEAR(sum_z2 / judged, 1.0, 5.0 * std::sqrt(2.0 / judged)) << rc.scene << " " << s.name;
            std::cout << "[cie171] " << rc.scene << " " << s.name << ": mean z^2 " << sum_z2 / judged << " over "
                      << judged << " cells, " << rc.photons << " photons, seed " << rc.seed << '\n';
        }
    }
}

}  // namespace
}  // namespace luxtrace
