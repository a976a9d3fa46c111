// The ray / lateral-surface test of cylindrical and semi-cylindrical detectors
// (detector/cylinder.hpp) and the grid walk that picks the points a ray can reach
// (Detector::cylinder_entries): hand-computed rays, a parallel beam whose count is the
// lit surface's projected area, and the walk against testing every point; and the
// modelling ratio (stats/modelling_ratio.hpp) by hand.
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/stats/modelling_ratio.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace luxtrace {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

CylinderShape shape(bool half = false, double fx = 1.0, double fy = 0.0) {
    CylinderShape c;
    c.radius_m = 0.05;
    c.height_m = 0.1;
    c.half = half;
    c.facing_x = fx;
    c.facing_y = fy;
    return c;
}

TEST(LateralEntry, RayThroughTheSideEntersAtRadius) {
    // From x = -1 along +x: the surface is met at x = -r, t = 1 - r.
    EXPECT_NEAR(lateral_entry(shape(), Vec3(-1, 0, 0), Vec3(1, 0, 0), kInf), 0.95, 1e-15);
    // Oblique, still within the height: from (-0.1, 0, 0.06) along (1, 0, -1)/sqrt 2 the
    // point x = -0.05 is reached at z = 0.01, t = 0.05 sqrt 2.
    const Vec3 d = glm::normalize(Vec3(1, 0, -1));
    EXPECT_NEAR(lateral_entry(shape(), Vec3(-0.1, 0, 0.06), d, kInf), 0.05 * std::sqrt(2.0), 1e-15);
    // A direction of any length gives the same point.
    EXPECT_NEAR(lateral_entry(shape(), Vec3(-1, 0, 0), Vec3(4, 0, 0), kInf), 0.95 / 4.0, 1e-15);
}

TEST(LateralEntry, RaysThroughTheCapsDoNotCount) {
    // Along the axis: through both caps, never across the lateral surface.
    EXPECT_LT(lateral_entry(shape(), Vec3(0.01, 0, 1), Vec3(0, 0, -1), kInf), 0.0);
    // In through the top cap (z = 0.05 at x = -0.03), out through the side from inside:
    // the infinite cylinder is entered at z = 0.07, above the height.
    const Vec3 d = glm::normalize(Vec3(1, 0, -1));
    EXPECT_LT(lateral_entry(shape(), Vec3(-0.08, 0, 0.1), d, kInf), 0.0);
    // Passing above or below the cylinder.
    EXPECT_LT(lateral_entry(shape(), Vec3(-1, 0, 0.051), Vec3(1, 0, 0), kInf), 0.0);
    EXPECT_LT(lateral_entry(shape(), Vec3(-1, 0, -0.051), Vec3(1, 0, 0), kInf), 0.0);
}

TEST(LateralEntry, TangentRaysTouchWithoutEntering) {
    EXPECT_LT(lateral_entry(shape(), Vec3(-1, 0.05, 0), Vec3(1, 0, 0), kInf), 0.0);
    EXPECT_LT(lateral_entry(shape(), Vec3(-1, 0.0500001, 0), Vec3(1, 0, 0), kInf), 0.0);
    // Just inside the tangent, it enters near x = 0.
    const double t = lateral_entry(shape(), Vec3(-1, 0.0499999, 0), Vec3(1, 0, 0), kInf);
    EXPECT_GT(t, 0.99);
    EXPECT_LT(t, 1.0);
}

TEST(LateralEntry, RaysFromInsideOrGoingAwayDoNotEnter) {
    EXPECT_LT(lateral_entry(shape(), Vec3(0, 0, 0), Vec3(1, 0, 0), kInf), 0.0);         // inside
    EXPECT_LT(lateral_entry(shape(), Vec3(0.05, 0, 0), Vec3(-1, 0, 0), kInf), 0.0);     // on the surface
    EXPECT_LT(lateral_entry(shape(), Vec3(0.02, 0, 0.3), Vec3(-1, 0, -1), kInf), 0.0);  // above, within r
    EXPECT_LT(lateral_entry(shape(), Vec3(1, 0, 0), Vec3(1, 0, 0), kInf), 0.0);         // moving away
}

TEST(LateralEntry, FlightEndsBeforeTheSurface) {
    EXPECT_LT(lateral_entry(shape(), Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.9499), 0.0);
    EXPECT_NEAR(lateral_entry(shape(), Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.9501), 0.95, 1e-15);
}

TEST(LateralEntry, HalfCylinderCountsItsFacingHalfOnly) {
    const CylinderShape east = shape(true, 1.0, 0.0);
    // From +x going -x: enters at (r, 0), normal +x.
    EXPECT_NEAR(lateral_entry(east, Vec3(1, 0, 0), Vec3(-1, 0, 0), kInf), 0.95, 1e-15);
    // From -x going +x: enters the back half, and leaves through the front one from inside.
    EXPECT_LT(lateral_entry(east, Vec3(-1, 0, 0), Vec3(1, 0, 0), kInf), 0.0);
    // Going -y: the entry point's x decides which half it is on.
    EXPECT_GT(lateral_entry(east, Vec3(0.01, 1, 0), Vec3(0, -1, 0), kInf), 0.0);
    EXPECT_LT(lateral_entry(east, Vec3(-0.01, 1, 0), Vec3(0, -1, 0), kInf), 0.0);
    // The whole cylinder counts both.
    EXPECT_GT(lateral_entry(shape(), Vec3(-0.01, 1, 0), Vec3(0, -1, 0), kInf), 0.0);
}

// A parallel beam of unit flux density from the direction l (toward the source, at gamma
// from the axis) meets the cylinder's lit side; the entries per unit beam area equal the
// lit lateral surface's projection across the beam: width 2r, height h sin(gamma), so
// the mean illuminance on the lateral surface is 2 r h sin(gamma) / (2 pi r h) =
// sin(gamma) / pi (the cylindrical illuminance of a beam of 1 lx across it). For the half
// facing f, at horizontal angle phi from l, the lit part of the facing half projects to a
// width r (1 + cos phi): the semi-cylindrical illuminance sin(gamma) (1 + cos phi) / pi.
// The rays are a 1200 x 1200 midpoint grid across the beam; the edges of the projection
// cut few cells, so the count is exact to ~1e-3.
double beam_entries_m2(const CylinderShape& c, double gamma, double phi_source) {
    const Vec3 l(std::sin(gamma) * std::cos(phi_source), std::sin(gamma) * std::sin(phi_source), std::cos(gamma));
    const Vec3 d = -l;
    // Two axes across the beam.
    const Vec3 a = glm::normalize(glm::cross(l, std::abs(l.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0)));
    const Vec3 b = glm::cross(l, a);
    const double half = 0.1;  // covers the cylinder's projection (r = 0.05, h = 0.1)
    const int n = 1200;
    const double cell = 2.0 * half / n;
    int hits = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 o = 2.0 * l + (-half + (i + 0.5) * cell) * a + (-half + (j + 0.5) * cell) * b;
            if (lateral_entry(c, o, d, kInf) > 0.0) ++hits;
        }
    return hits * cell * cell;
}

TEST(LateralEntry, ParallelBeamGivesTheCylindricalIlluminance) {
    const CylinderShape whole = shape();
    for (const double gamma_deg : {20.0, 55.0, 90.0}) {
        const double g = gamma_deg * kPi / 180.0;
        const double expected = 2.0 * 0.05 * 0.1 * std::sin(g);
        EXPECT_NEAR(beam_entries_m2(whole, g, 0.7), expected, 2e-3 * expected) << "gamma " << gamma_deg;
    }
    // The half facing +x, the source at phi = 0, 60, 120 and 180 degrees from it.
    const CylinderShape east = shape(true);
    const double g = 50.0 * kPi / 180.0;
    for (const double phi_deg : {0.0, 60.0, 120.0, 180.0}) {
        const double phi = phi_deg * kPi / 180.0;
        const double expected = 0.05 * 0.1 * std::sin(g) * (1.0 + std::cos(phi));
        EXPECT_NEAR(beam_entries_m2(east, g, phi), expected, 2e-3 * 0.05 * 0.1) << "phi " << phi_deg;
    }
}

// Every point's cylinder, tested one by one in scene coordinates.
std::vector<int> brute_force(const Detector& det, const Vec3& o, const Vec3& d, double t_max) {
    std::vector<int> out;
    for (int j = 0; j < det.ny; ++j)
        for (int i = 0; i < det.nx; ++i) {
            const Vec3 p = det.center + ((i + 0.5) / det.nx - 0.5) * det.size_u * det.u_axis +
                           ((j + 0.5) / det.ny - 0.5) * det.size_v * det.v_axis;
            const Vec3 r = o - p;
            const Vec3 ol(glm::dot(r, det.u_axis), glm::dot(r, det.v_axis), glm::dot(r, det.normal));
            const Vec3 dl(glm::dot(d, det.u_axis), glm::dot(d, det.v_axis), glm::dot(d, det.normal));
            if (lateral_entry(det.cylinder, ol, dl, t_max) > 0.0) out.push_back(j * det.nx + i);
        }
    return out;
}

// The walk finds exactly the points that testing all of them finds, for rays of every
// kind: steep, oblique, horizontal inside the slab (which may cross a whole row), along
// the axis, ending early or escaping; on grids with cells far apart, anisotropic, and
// with cylinders wider than a cell (a ray then enters several neighbours).
TEST(CylinderGrid, WalkFindsExactlyThePointsOfAnExhaustiveTest) {
    struct Case {
        DetectorType type;
        Vec3 normal, up;
        double su, sv, r, h;
        int nx, ny;
    };
    const Case cases[] = {
        {DetectorType::cylindrical, {0, 0, 1}, {0, 1, 0}, 4.0, 3.0, 0.05, 0.1, 8, 6},
        {DetectorType::cylindrical, {0, 0, 1}, {0, 1, 0}, 2.0, 0.5, 0.05, 0.1, 40, 5},
        {DetectorType::semicylindrical, {0, 0, 1}, {1, 1, 0}, 1.0, 1.0, 0.3, 0.2, 7, 9},
        {DetectorType::cylindrical, glm::normalize(Vec3(0.2, -0.1, 1)), {0, 1, 0}, 3.0, 2.0, 0.1, 0.4, 12, 5},
    };
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::size_t found = 0, rays = 0;
    for (const Case& c : cases) {
        Detector det;
        det.type = c.type;
        det.center = Vec3(0.3, -0.2, 1.2);
        det.normal = c.normal;
        det.up = c.up;
        det.size_u = c.su;
        det.size_v = c.sv;
        det.nx = c.nx;
        det.ny = c.ny;
        det.radius_m = c.r;
        det.height_m = c.h;
        det.facing = Vec3(1, 2, 0);
        det.finalize();
        std::vector<int> walk;
        for (int k = 0; k < 20000; ++k) {
            // Origins around the grid; a quarter of the rays lie in the slab, across the axis.
            Vec3 o = det.center + Vec3(3 * u(rng), 3 * u(rng), 2 * u(rng));
            Vec3 d = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
            if (k % 4 == 1) {
                o = det.center + 3 * u(rng) * det.u_axis + 3 * u(rng) * det.v_axis + 0.4 * c.h * u(rng) * det.normal;
                d = glm::normalize(u(rng) * det.u_axis + u(rng) * det.v_axis);
            } else if (k % 4 == 2) {
                d = u(rng) < 0 ? det.normal : -det.normal;
            }
            const double t_max = k % 3 == 0 ? kInf : 4.0 * (u(rng) + 1.0);
            walk.clear();
            det.cylinder_entries(o, d, t_max, walk);
            std::sort(walk.begin(), walk.end());
            const std::vector<int> all = brute_force(det, o, d, t_max);
            ASSERT_EQ(walk, all) << "ray " << k << " of case nx " << c.nx;
            found += all.size();
            ++rays;
        }
    }
    // The rays must really reach cylinders for this to mean anything.
    EXPECT_GT(found, rays / 20);
}

// The modelling ratio from two estimates, by hand: two points, two bands.
TEST(ModellingRatio, RatiosAndPropagatedErrorsByHand) {
    DetectorEstimate c, h;
    c.value = {2.0, 1.0, 3.0, 0.5};  // [point][band]
    c.sigma_rel = {0.03, 0.06, 0.05, 0.1};
    h.value = {4.0, 4.0, 0.0, 1.5};
    h.sigma_rel = {0.04, 0.08, std::nan(""), 0.1};
    c.mean_value = 1.6;
    c.mean_sigma_rel = 0.012;
    h.mean_value = 3.2;
    h.mean_sigma_rel = 0.005;
    const ModellingRatio m = modelling_ratio(c, h, 2);
    ASSERT_EQ(m.ratio.size(), 4u);
    EXPECT_DOUBLE_EQ(m.ratio[0], 0.5);
    EXPECT_DOUBLE_EQ(m.sigma_rel[0], 0.05);  // sqrt(0.03^2 + 0.04^2)
    EXPECT_DOUBLE_EQ(m.ratio[1], 0.25);
    EXPECT_DOUBLE_EQ(m.sigma_rel[1], 0.1);  // sqrt(0.06^2 + 0.08^2)
    EXPECT_TRUE(std::isnan(m.ratio[2]));    // no horizontal illuminance in that band
    EXPECT_TRUE(std::isnan(m.sigma_rel[2]));
    EXPECT_DOUBLE_EQ(m.ratio[3], 0.5 / 1.5);
    EXPECT_DOUBLE_EQ(m.mean, 0.5);
    EXPECT_DOUBLE_EQ(m.mean_sigma_rel, 0.013);  // sqrt(0.012^2 + 0.005^2)
    // Over the points, bands summed: (2 + 1) / (4 + 4) and (3 + 0.5) / (0 + 1.5).
    EXPECT_DOUBLE_EQ(m.min, 3.0 / 8.0);
    EXPECT_DOUBLE_EQ(m.max, 3.5 / 1.5);
    // No horizontal light anywhere: nothing to divide by.
    h.value.assign(4, 0.0);
    h.mean_value = 0.0;
    const ModellingRatio none = modelling_ratio(c, h, 2);
    EXPECT_TRUE(std::isnan(none.mean));
    EXPECT_TRUE(std::isnan(none.min));
    EXPECT_TRUE(std::isnan(none.max));
}

}  // namespace
}  // namespace luxtrace
