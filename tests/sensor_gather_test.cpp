// What a sensor sees of the scene's surfaces (tracer/sensor_gather.hpp, issue 37), against
// what geometry says it must be:
// - in a closed room every ray meets a wall: the weights fill the hemisphere, pi, exactly;
// - a rectangle parallel to the sensor gets its configuration factor times pi (a closed
//   form), on and off its axis, within the stratified rays' scatter over seeds;
// - behind a glazing pane, a ceiling gets the pane's transmittance and a floor its
//   reflectance, each integrated over the projected hemisphere (2 pi int T(mu) mu dmu).
#include "luxtrace/tracer/sensor_gather.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
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
            if (sides.empty() || sides[g.side[i]]) sum += g.weight_sr[i];
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
                EXPECT_LT(g.side[i], scene.triangle_count());
                if (i > g.offset[c]) {
                    EXPECT_GT(g.side[i], g.side[i - 1]);
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

}  // namespace
}  // namespace luxtrace
