// What a sensor sees of the scene's surfaces (tracer/sensor_gather.hpp, issue 37), against
// what geometry says it must be:
// - in a closed room every ray meets a wall: the weights fill the hemisphere, pi, exactly;
// - a rectangle parallel to the sensor gets its configuration factor times pi (a closed
//   form), on and off its axis, within the stratified rays' scatter over seeds;
// - behind a glazing pane, a ceiling gets the pane's transmittance and a floor its
//   reflectance, each integrated over the projected hemisphere (2 pi int T(mu) mu dmu);
// - a triangle's patches are m^2 of equal area: points uniform over the triangle fall in
//   each equally often (chi-square), and the rays a triangle takes are shared out among its
//   patches, none lost.
#include "luxtrace/tracer/sensor_gather.hpp"
#include "luxtrace/sampler/philox_bits.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/gather_patches.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <string>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

class SensorGatherTest : public ::testing::Test {
protected:
    test_support::ScratchDir scratch_{std::string("sensor_gather_") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name()};

    // Two upward sensors, at the origin and at (0.3, -0.2, 0), and `text`.
    Scene load(const std::string& text) const {
        std::ofstream(scratch_.path() / "sensor.pts") << "0 0 0 0 0 1\n0.3 -0.2 0 0 0 1\n";
        const fs::path file = scratch_.path() / "scene.toml";
        // A light the scene needs, which the gather does not trace.
        std::ofstream(file) << "[[light]]\ntype = \"point\"\nposition = [0, 0, -0.25]\nflux_lm = 1\n"
                            << "[[detector]]\nname = \"points\"\ntype = \"points\"\npoints = \"sensor.pts\"\n"
                            << text;
        return load_scene(file);
    }
    static double total(const SensorGather& g, std::size_t cell, const std::vector<bool>& sides) {
        double sum = 0.0;
        for (std::size_t i = g.offset[cell]; i < g.offset[cell + 1]; ++i)
            if (sides.empty() || sides[g.site[i]]) sum += g.weight_sr[i];
        return sum;
    }
};

std::string rectangle(const std::string& centre, const std::string& normal, double sx, double sy,
                      const std::string& material, const std::string& up = "[0, 1, 0]") {
    return "[[shape]]\ntype = \"rectangle\"\ncenter = " + centre + "\nnormal = " + normal + "\nup = " + up +
           "\nsize = [" + std::to_string(sx) + ", " + std::to_string(sy) + "]\nmaterial = \"" + material + "\"\n";
}

const char* kMaterials = "[[material]]\nname = \"grey\"\nreflectance = 0.5\n"
                         "[[material]]\nname = \"pane\"\ntype = \"glazing\"\ntransmittance = 0.8\n"
                         "refractive_index = 1.52\n";

// The projected solid angle of an a x b rectangle parallel to the sensor, h above it, with
// a corner straight above it: pi times the configuration factor.
double corner(double a, double b, double h) {
    const double sa = std::hypot(a, h), sb = std::hypot(b, h);
    return 0.5 * (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb));
}

// The sides of the triangles of material `name`.
std::vector<bool> sides_of(const Scene& scene, const std::string& name) {
    std::vector<bool> out(2 * scene.triangle_count(), false);
    for (std::size_t t = 0; t < scene.triangle_count(); ++t)
        if (scene.materials[scene.triangle_material[t]].name == name) out[t] = out[scene.triangle_count() + t] = true;
    return out;
}

TEST_F(SensorGatherTest, AClosedRoomFillsTheHemisphere) {
    const Scene scene = load(std::string(kMaterials) + rectangle("[0, 0, -1]", "[0, 0, 1]", 4, 4, "grey") +
                             rectangle("[0, 0, 2]", "[0, 0, -1]", 4, 4, "grey") +
                             rectangle("[2, 0, 0.5]", "[-1, 0, 0]", 3, 4, "grey") +
                             rectangle("[-2, 0, 0.5]", "[1, 0, 0]", 3, 4, "grey") +
                             rectangle("[0, 2, 0.5]", "[0, -1, 0]", 4, 3, "grey", "[0, 0, 1]") +
                             rectangle("[0, -2, 0.5]", "[0, 1, 0]", 4, 3, "grey", "[0, 0, 1]") +
                             "[[detector]]\nname = \"grid\"\ncenter = [0, 0, 0]\nnormal = [0, 0, 1]\n"
                             "up = [0, 1, 0]\nsize = [2, 2]\ncells = [2, 2]\n");
    const EmbreeScene embree(scene);
    for (std::size_t det = 0; det < 2; ++det) {
        const std::size_t cells = static_cast<std::size_t>(scene.detectors[det].cells());
        const SensorGather g = sensor_gather(scene, embree, det, {}, 0, cells);
        ASSERT_EQ(g.cells, cells);
        for (std::size_t c = 0; c < cells; ++c) {
            EXPECT_NEAR(total(g, c, {}), kPi, 1e-9) << "detector " << det << ", cell " << c;
            for (std::size_t i = g.offset[c]; i < g.offset[c + 1]; ++i) {
                // Every wall is seen on its inner side, the side its normal points to.
                EXPECT_LT(g.site[i], scene.triangle_count());
                if (i > g.offset[c]) {
                    EXPECT_GT(g.site[i], g.site[i - 1]);
                }
            }
        }
    }
}

TEST_F(SensorGatherTest, AParallelRectangleGetsItsConfigurationFactor) {
    const Scene scene = load(std::string(kMaterials) + rectangle("[0, 0, 1]", "[0, 0, -1]", 1, 1, "grey"));
    const EmbreeScene embree(scene);
    const double exact[2] = {4.0 * corner(0.5, 0.5, 1.0), corner(0.8, 0.3, 1.0) + corner(0.8, 0.7, 1.0) +
                                                              corner(0.2, 0.3, 1.0) + corner(0.2, 0.7, 1.0)};
    const int seeds = 24;
    for (std::size_t c = 0; c < 2; ++c) {
        double m = 0.0, m2 = 0.0;
        for (int seed = 1; seed <= seeds; ++seed) {
            SensorGatherOptions o;
            o.seed = static_cast<std::uint64_t>(seed);
            const double k = total(sensor_gather(scene, embree, 0, o, 0, 2), c, {});
            m += k;
            m2 += k * k;
        }
        const double mean = m / seeds,
                     scatter = std::sqrt(std::max(0.0, (m2 / seeds - mean * mean)) * seeds / (seeds - 1));
        std::cout << "[gather] sensor " << c << ": mean " << mean << " sr (closed form " << exact[c] << "), scatter "
                  << scatter << "\n";
        EXPECT_NEAR(mean, exact[c], 4.0 * scatter / std::sqrt(seeds) + 1e-12);
        EXPECT_LT(scatter, 6e-3 * exact[c]);  // 4,096 stratified rays: the edge's strata alone vary
        EXPECT_GT(scatter, 0.0);              // ... and they do, so the test above can fail
    }
}

TEST_F(SensorGatherTest, APaneTakesItsTransmittanceAndReflectance) {
    // A horizontal pane 0.5 m above the sensors, a grey ceiling 1 m above and a grey floor
    // 0.5 m below them, 400 m wide (what lies beyond is 1e-5 of the hemisphere).
    const Scene scene = load(std::string(kMaterials) + rectangle("[0, 0, 0.5]", "[0, 0, -1]", 400, 400, "pane") +
                             rectangle("[0, 0, 1]", "[0, 0, -1]", 400, 400, "grey") +
                             "[[material]]\nname = \"floor\"\nreflectance = 0.2\n" +
                             rectangle("[0, 0, -0.5]", "[0, 0, 1]", 400, 400, "floor"));
    const EmbreeScene embree(scene);
    const GlazingCurve* curve = nullptr;
    for (const Material& m : scene.materials)
        if (m.name == "pane") curve = &(*m.glazing)[0];
    ASSERT_NE(curve, nullptr);
    double through = 0.0, reflected = 0.0;  // 2 pi int X(mu) mu dmu, midpoints
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        through += 2.0 * kPi * curve->at(mu).transmittance * mu / n;
        reflected += 2.0 * kPi * curve->at(mu).reflectance * mu / n;
    }
    const SensorGather g = sensor_gather(scene, embree, 0, {}, 0, 2);
    for (std::size_t c = 0; c < 2; ++c) {
        const double ceiling = total(g, c, sides_of(scene, "grey")), floor = total(g, c, sides_of(scene, "floor"));
        std::cout << "[gather] sensor " << c << ": ceiling " << ceiling << " sr (T integrated " << through
                  << "), floor " << floor << " sr (R integrated " << reflected << ")\n";
        EXPECT_NEAR(ceiling, through, 2e-3 * through);
        EXPECT_NEAR(floor, reflected, 1e-2 * reflected);
        EXPECT_EQ(total(g, c, sides_of(scene, "pane")), 0.0);  // glass is passed, never taken
    }
}

TEST_F(SensorGatherTest, WeightsDoNotDependOnWhichCellsAreComputedTogether) {
    const Scene scene = load(std::string(kMaterials) + rectangle("[0, 0, 1]", "[0, 0, -1]", 1, 1, "grey"));
    const EmbreeScene embree(scene);
    const SensorGather both = sensor_gather(scene, embree, 0, {}, 0, 2),
                       second = sensor_gather(scene, embree, 0, {}, 1, 2);
    ASSERT_EQ(second.first, 1u);
    EXPECT_EQ(std::vector<double>(both.weight_sr.begin() + static_cast<std::ptrdiff_t>(both.offset[1]),
                                  both.weight_sr.end()),
              second.weight_sr);
    EXPECT_THROW(sensor_gather(scene, embree, 0, {}, 0, 3), std::logic_error);
}

TEST(GatherPatches, PointsUniformOverATriangleFillItsPatchesEvenly) {
    PhiloxBits bits(7, 1);
    for (const std::uint32_t m : {1u, 2u, 3u, 7u}) {
        const std::size_t patches = static_cast<std::size_t>(m) * m, n = 2000 * patches;
        std::vector<double> seen(patches, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            // Uniform over the triangle u, v >= 0, u + v <= 1 (folding the unit square).
            double u = std::generate_canonical<double, 53>(bits), v = std::generate_canonical<double, 53>(bits);
            if (u + v > 1.0) {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            const std::size_t p = GatherPatches::within(m, static_cast<float>(u), static_cast<float>(v));
            ASSERT_LT(p, patches) << "m " << m;
            seen[p] += 1.0;
        }
        const double expected = static_cast<double>(n) / static_cast<double>(patches);
        double chi2 = 0.0;
        for (const double o : seen) chi2 += (o - expected) * (o - expected) / expected;
        const double dof = static_cast<double>(patches - 1);
        std::cout << "[gather] " << m << " x " << m << " patches: chi2 " << chi2 << " on " << dof << " dof\n";
        // Far beyond 5 sigma of chi2 (dof + 5 sqrt(2 dof)), and every patch reached.
        EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof) + 1.0) << "m " << m;
        for (const double o : seen) EXPECT_GT(o, 0.0) << "m " << m;
    }
    // The corners and the hypotenuse stay in the triangle's patches.
    for (const auto& [u, v] :
         std::vector<std::pair<float, float>>{{0.f, 0.f}, {1.f, 0.f}, {0.f, 1.f}, {0.5f, 0.5f}, {0.6f, 0.40001f}})
        EXPECT_LT(GatherPatches::within(5, u, v), 25u) << u << ", " << v;
}

TEST_F(SensorGatherTest, PatchesShareOutTheirTrianglesRays) {
    const Scene scene = load(std::string(kMaterials) + rectangle("[0, 0, 1]", "[0, 0, -1]", 3, 3, "grey"));
    const EmbreeScene embree(scene);
    const GatherPatches patches(scene, 0.4);  // the 4.2 m diagonal: 11 cuts
    ASSERT_EQ(scene.triangle_count(), 2u);
    ASSERT_EQ(patches.cuts(0), 11u);
    ASSERT_EQ(patches.cuts(1), 11u);
    double area = 0.0;
    for (std::size_t p = 0; p < patches.count(); ++p) area += patches.area_m2(p);
    EXPECT_NEAR(area, scene.total_area_m2(), 1e-9 * area);
    SensorGatherOptions o;
    o.patches = &patches;
    const SensorGather whole = sensor_gather(scene, embree, 0, {}, 0, 2),
                       cut = sensor_gather(scene, embree, 0, o, 0, 2);
    for (std::size_t c = 0; c < 2; ++c) {
        // Per triangle side, the patches' weights add to the whole triangle's (the same rays).
        std::vector<double> by_side(2 * scene.triangle_count(), 0.0), patched(by_side);
        std::size_t used = 0;
        for (std::size_t i = whole.offset[c]; i < whole.offset[c + 1]; ++i)
            by_side[whole.site[i]] += whole.weight_sr[i];
        for (std::size_t i = cut.offset[c]; i < cut.offset[c + 1]; ++i, ++used) {
            const std::size_t side = cut.site[i] / patches.count(), patch = cut.site[i] % patches.count();
            const std::size_t tri = patch / (11 * 11);  // both triangles have 11 x 11
            patched[side * scene.triangle_count() + tri] += cut.weight_sr[i];
        }
        EXPECT_GT(used, 50u);  // the rays fall on many patches
        for (std::size_t s = 0; s < by_side.size(); ++s) EXPECT_NEAR(patched[s], by_side[s], 1e-12) << "side " << s;
    }
}

}  // namespace
}  // namespace luxtrace
