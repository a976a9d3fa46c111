// Tests of the detector part of load_scene (src/scene/detector_loader.cpp: [[detector]]
// with its [[detector.task_area]], [[observer]]): illuminance, luminance and cylindrical
// detectors and task areas land as they should, and bad ones are InputErrors naming the
// file, the line (or key) and what is wrong.
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once (tests/data/scenes/every_key.toml).

TEST_F(EveryKey, Detectors) {
    ASSERT_EQ(s().detectors.size(), 2u);
    const Detector& a = s().detectors[0];
    EXPECT_EQ(a.name, "desk");
    EXPECT_EQ(a.type, DetectorType::illuminance);
    expect_vec(a.center, Vec3(0, 0, 0.76));
    expect_vec(a.normal, Vec3(0, 0, 1));
    expect_vec(a.up, Vec3(0, 1, 0));
    expect_vec(a.u_axis, Vec3(1, 0, 0));  // up x normal
    EXPECT_EQ(a.size_u, 1.2);
    EXPECT_EQ(a.size_v, 0.8);
    EXPECT_EQ(a.nx, 12);
    EXPECT_EQ(a.ny, 8);
    ASSERT_EQ(a.task_areas.size(), 1u);
    EXPECT_EQ(a.task_areas[0].name, "work");
    EXPECT_EQ(a.task_areas[0].i0, 2);
    EXPECT_EQ(a.task_areas[0].i1, 10);
    EXPECT_EQ(a.task_areas[0].j0, 1);
    EXPECT_EQ(a.task_areas[0].j1, 5);

    const Detector& b = s().detectors[1];
    EXPECT_EQ(b.name, "wall_view");
    EXPECT_EQ(b.type, DetectorType::luminance);
    expect_vec(b.u_axis, Vec3(0, 1, 0));  // z x x
    EXPECT_EQ(b.nx, 4);
    EXPECT_EQ(b.ny, 2);
    EXPECT_EQ(b.half_angle_deg, 10.0);
    EXPECT_NEAR(b.cos_half_angle, std::cos(10.0 * kPi / 180.0), 1e-15);
    // The view direction points into the wall; the cone leaves its front side.
    expect_vec(b.cone_axis, Vec3(0.8, -0.6, 0), 1e-15);
}

// ---------------------------------------------------------------------------------
// Detectors written by the test, and bad ones.

TEST_F(Loader, LuminanceViewDirectionOfEitherSign) {
    for (const std::string vd : {"[0.6, 0, 0.8]", "[-0.6, 0, -0.8]"}) {
        const Scene s = load(kMat + kFloor + kLamp +
                             "[[detector]]\nname = \"l\"\ntype = \"luminance\"\ncenter = [0, 0, 0]\n"
                             "size = [1, 1]\nview_direction = " +
                             vd + "\nhalf_angle_deg = 3\n");
        ASSERT_EQ(s.detectors.size(), 1u);
        expect_vec(s.detectors[0].cone_axis, Vec3(0.6, 0, 0.8), 1e-15);
        EXPECT_NEAR(s.detectors[0].cos_half_angle, std::cos(3 * kPi / 180), 1e-15);
    }
}

TEST_F(Loader, ZeroAreaDetector) {
    expect_bad(kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [0, 1]\n",
               "size = [0, 1]", {"key 'size'", "zero or negative area"});
}

TEST_F(Loader, DetectorUpParallelToNormal) {
    expect_bad(kMat + kFloor + kLamp +
                   "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1, 1]\n"
                   "normal = [0, 0, 1]\nup = [0, 0, -2]\n",
               "up =", {"key 'up'", "parallel to 'normal'"});
}

TEST_F(Loader, DetectorCellLimitIsNamed) {
    const std::string head = kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1, 1]\n";
    expect_bad(head + "cells = [20000, 20000]\n",
               "cells =", {"key 'cells'", "20000 x 20000 = 400000000 cells", "at most 100000000"});
    expect_bad(head + "cells = [2.5, 3]\n", "cells =", {"key 'cells'", "positive whole numbers"});
    // The limit itself is accepted (the grid is only described here, not allocated).
    EXPECT_EQ(load(head + "cells = [10000, 10000]\n").detectors.at(0).cells(), 100'000'000);
}

// ---------------------------------------------------------------------------------
// Hardening made with the fuzz targets (tests/fuzz/README.md): absurd sizes are refused
// before anything is allocated, and values that are finite alone but overflow or vanish
// together are refused with the entry named.

TEST_F(Loader, DetectorTooSmallToMeasureIsRefused) {
    expect_bad(kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1e-200, 1e-200]\n", "",
               {"[[detector]] #1 'd'", "too small"});
    expect_bad(kMat + kFloor + kLamp +
                   "[[detector]]\nname = \"d\"\ntype = \"luminance\"\ncenter = [0, 0, 0]\n"
                   "size = [1, 1]\nhalf_angle_deg = 1e-300\n",
               "", {"[[detector]] #1 'd'", "too narrow"});
}

// ---------------------------------------------------------------------------------
// Cylindrical detectors and task areas.

// Cylindrical and semicylindrical detectors: defaults, the facing direction, and the
// horizontal detector of the modelling ratio, which may be defined after the cylinders.
TEST_F(Loader, CylindricalDetectors) {
    const std::string grid = "center = [0, 0, 1.2]\nsize = [2, 1]\ncells = [4, 2]\n";
    const Scene s = load(kMat + kFloor + kLamp + "[[detector]]\nname = \"c\"\ntype = \"cylindrical\"\n" + grid +
                         "horizontal = \"h\"\n[[detector]]\nname = \"sc\"\ntype = \"semicylindrical\"\n" + grid +
                         "radius = 0.05\nheight = 0.1\nfacing = [0, -3, 0]\n[[detector]]\nname = \"h\"\n" + grid);
    ASSERT_EQ(s.detectors.size(), 3u);
    const Detector& c = s.detectors[0];
    EXPECT_EQ(c.type, DetectorType::cylindrical);
    EXPECT_EQ(c.radius_m, 0.01);
    EXPECT_EQ(c.height_m, 0.2);
    EXPECT_NEAR(c.lateral_area_m2(), 2 * kPi * 0.01 * 0.2, 1e-15);
    EXPECT_NEAR(c.value_per_lm(), 1.0 / (2 * kPi * 0.01 * 0.2), 1e-9);
    EXPECT_EQ(c.horizontal, "h");
    EXPECT_EQ(c.horizontal_index, 2);
    EXPECT_STREQ(c.units(), "lx");
    const Detector& sc = s.detectors[1];
    EXPECT_EQ(sc.type, DetectorType::semicylindrical);
    EXPECT_NEAR(sc.lateral_area_m2(), kPi * 0.05 * 0.1, 1e-15);
    expect_vec(sc.facing, Vec3(0, -1, 0), 1e-15);
    // In the grid's frame (u = +x, v = +y) the half faces -v.
    EXPECT_NEAR(sc.cylinder.facing_x, 0.0, 1e-15);
    EXPECT_NEAR(sc.cylinder.facing_y, -1.0, 1e-15);
    EXPECT_TRUE(sc.cylinder.half);
    EXPECT_EQ(sc.horizontal_index, -1);
}

TEST_F(Loader, BadCylindricalDetectors) {
    const std::string head = kMat + kFloor + kLamp + "[[detector]]\nname = \"c\"\ncenter = [0, 0, 1]\nsize = [1, 1]\n";
    const std::string cyl = head + "type = \"cylindrical\"\n", semi = head + "type = \"semicylindrical\"\n";
    expect_bad(cyl + "radius = 0\n", "radius", {"[[detector]] #1 'c'", "key 'radius'", "must be positive"});
    expect_bad(cyl + "height = -0.1\n", "height", {"key 'height'", "must be positive"});
    expect_bad(semi, "", {"[[detector]] #1 'c'", "needs 'facing'"});
    expect_bad(semi + "facing = [0, 1, 0.5]\n", "facing", {"key 'facing'", "perpendicular to the cylinder axis"});
    expect_bad(semi + "facing = [0, 0, 0]\n", "facing", {"key 'facing'", "non-zero"});
    // Keys of other types are unknown here.
    expect_bad(cyl + "facing = [1, 0, 0]\n", "facing", {"key 'facing' does not apply here"});
    expect_bad(semi + "facing = [1, 0, 0]\nhorizontal = \"h\"\n", "horizontal",
               {"key 'horizontal' does not apply here"});
    expect_bad(head + "radius = 0.1\n", "radius", {"key 'radius' does not apply here"});
    expect_bad(cyl + "horizontal = \"\"\n", "horizontal", {"key 'horizontal'", "needs the name"});
    expect_bad(cyl + "horizontal = \"nosuch\"\n", "horizontal",
               {"key 'horizontal'", "no [[detector]] is named 'nosuch'"});
    const std::string other = "[[detector]]\nname = \"h\"\ncenter = [0, 0, 1]\nsize = [1, 1]\n";
    expect_bad(cyl + "horizontal = \"h\"\n" + other + "type = \"luminance\"\n", "horizontal",
               {"key 'horizontal'", "detector 'h' is luminance", "needs an illuminance detector"});
    expect_bad(cyl + "horizontal = \"h\"\n" + other + "cells = [2, 2]\n", "horizontal",
               {"key 'horizontal'", "same grid", "'cells' differs"});
    expect_bad(cyl + "horizontal = \"h\"\n" + other + "normal = [0, 0, -1]\n", "horizontal", {"'normal' differs"});
    expect_bad(cyl + "horizontal = \"c\"\n", "horizontal", {"detector 'c' is cylindrical"});
}

TEST_F(Loader, TaskAreasOfIlluminanceDetectors) {
    // Both TOML spellings: a [[detector.task_area]] table and an inline array.
    const Scene s = load(
        kMat + kFloor + kLamp + kDesk + "[[detector.task_area]]\nname = \"left\"\ncells = [0, 2, 0, 3]\n" +
        "[[detector]]\nname = \"d2\"\ncenter = [0, 0, 0.5]\nsize = [1, 1]\ncells = [4, 3]\n"
        "task_area = [{ name = \"a\", cells = [3, 4, 2, 3] }, { name = \"b\", cells = [0, 4, 0, 3] }]\n");
    ASSERT_EQ(s.detectors.size(), 2u);
    ASSERT_EQ(s.detectors[0].task_areas.size(), 1u);
    EXPECT_EQ(s.detectors[0].task_areas[0].name, "left");
    EXPECT_EQ(s.detectors[0].task_areas[0].i1, 2);
    EXPECT_EQ(s.detectors[0].task_areas[0].j1, 3);
    ASSERT_EQ(s.detectors[1].task_areas.size(), 2u);
    EXPECT_EQ(s.detectors[1].task_areas[0].i0, 3);
    EXPECT_EQ(s.detectors[1].task_areas[1].name, "b");
}

// daylight_factor and en17037 (issue 23): refused without a daylight source or on a
// detector that is not an illuminance grid, and their values checked.
TEST_F(Loader, BadDaylightFactorKeysAreRefused) {
    const std::string head = kMat + kFloor + kLamp + kDesk;
    expect_bad(head + "daylight_factor = true\n", "daylight_factor",
               {"[[detector]] #1 'desk'", "key 'daylight_factor'", "needs a daylight source", "E_h,ext"});
    expect_bad(head + "en17037 = { target_df = 2, minimum_df = 0.7 }\n", "en17037",
               {"key 'en17037'", "needs a daylight source"});
    expect_bad(head + "daylight_factor = 1\n", "daylight_factor", {"key 'daylight_factor'"});
    expect_bad(head + "en17037 = 2\n", "en17037", {"key 'en17037'", "expected a table"});
    expect_bad(head + "en17037 = { target_df = 2 }\n", "", {"en17037", "needs 'target_df'", "'minimum_df'"});
    expect_bad(head + "en17037 = { target_df = 0, minimum_df = 0.7 }\n", "en17037",
               {"key 'target_df'", "(0, 100] percent"});
    expect_bad(head + "en17037 = { target_df = 2, minimum_df = 120 }\n", "en17037",
               {"key 'minimum_df'", "(0, 100] percent"});
    expect_bad(head + "en17037 = { target_df = 2, minimum_df = 0.7, median = 1 }\n", "en17037",
               {"unknown key 'median'"});
    expect_bad(head + "daylight_factor = false\nen17037 = { target_df = 2, minimum_df = 0.7 }\n", "daylight_factor",
               {"key 'daylight_factor'", "is false, but en17037"});
    expect_bad(kMat + kFloor + kLamp +
                   "[[detector]]\nname = \"v\"\ntype = \"luminance\"\ncenter = [0, 0, 0]\nsize = [1, 1]\n"
                   "daylight_factor = true\n",
               "daylight_factor", {"key 'daylight_factor'", "belong to illuminance detectors", "luminance"});
    // Off by default, and `false` is accepted without a daylight source.
    EXPECT_FALSE(load(head).detectors[0].daylight_factor);
    const Scene off = load(head + "daylight_factor = false\n");
    EXPECT_FALSE(off.detectors[0].daylight_factor);
    EXPECT_FALSE(off.detectors[0].en17037.has_value());
}

// With a sky the keys load; a sun below the horizon is no daylight source. Electric light
// beside the daylight is warned about unless a light scene lights with the daylight alone.
TEST_F(Loader, DaylightFactorWithASky) {
    const std::string sky = "[[light]]\ntype = \"sky\"\nsky = \"uniform\"\ndiffuse_horizontal_lx = 10000\n";
    const Scene s = load(kMat + kFloor + sky + kDesk + "en17037 = { target_df = 2.1, minimum_df = 0.7 }\n");
    const Detector& d = s.detectors[0];
    EXPECT_TRUE(d.daylight_factor);
    ASSERT_TRUE(d.en17037.has_value());
    EXPECT_EQ(d.en17037->target_df, 2.1);
    EXPECT_EQ(d.en17037->minimum_df, 0.7);
    EXPECT_TRUE(s.warnings.empty());
    EXPECT_TRUE(load(kMat + kFloor + sky + kDesk + "daylight_factor = true\n").detectors[0].daylight_factor);

    const std::string low_sun = "[[light]]\ntype = \"sun\"\ndirect_normal_lx = 50000\nsun_altitude_deg = -5\n"
                                "sun_azimuth_deg = 180\n";
    expect_bad(kMat + kFloor + low_sun + kLamp + kDesk + "daylight_factor = true\n", "daylight_factor",
               {"needs a daylight source"});

    auto mixed_warning = [](const Scene& scene) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(), [](const std::string& w) {
            return w.find("daylight factor with daylight and electric light together") != std::string::npos;
        });
    };
    const std::string df = kDesk + "daylight_factor = true\n";
    EXPECT_TRUE(mixed_warning(load(kMat + kFloor + sky + kLamp + df)));
    const std::string grouped = kMat + kFloor + sky + "group = \"day\"\n" + lamp_in("lamps");
    EXPECT_TRUE(
        mixed_warning(load(grouped + "[[light_scene]]\nname = \"all\"\ndimming = { day = 1, lamps = 1 }\n" + df)));
    EXPECT_FALSE(mixed_warning(load(grouped + "[[light_scene]]\nname = \"day\"\ndimming = { day = 1 }\n" + df)));
}

TEST_F(Loader, BadTaskAreasAreRefused) {
    const std::string head = kMat + kFloor + kLamp + kDesk + "[[detector.task_area]]\n";  // a 4 x 3 grid
    expect_bad(head + "name = \"t\"\ncells = [0, 5, 0, 3]\n", "cells = [0, 5",
               {"[[detector]] #1 'desk' task_area #1 't'", "key 'cells'",
                "[0, 5, 0, 3] is empty or outside the 4 x 3 cells"});
    expect_bad(head + "name = \"t\"\ncells = [2, 2, 0, 3]\n", "cells = [2", {"key 'cells'", "is empty or outside"});
    expect_bad(head + "name = \"t\"\ncells = [0, 2, 1, 0]\n", "cells = [0, 2", {"key 'cells'", "is empty or outside"});
    expect_bad(head + "name = \"t\"\ncells = [-1, 2, 0, 3]\n", "cells = [-1", {"key 'cells'", "none negative"});
    expect_bad(head + "name = \"t\"\ncells = [0.5, 2, 0, 3]\n", "cells = [0.5", {"key 'cells'", "whole numbers"});
    expect_bad(head + "name = \"t\"\ncells = [0, 2, 0]\n", "cells = [0, 2, 0]", {"key 'cells'", "array of 4 numbers"});
    expect_bad(head + "name = \"t\"\n", "", {"task_area #1 't'", "needs 'cells' = [i0, i1, j0, j1]"});
    expect_bad(head + "cells = [0, 2, 0, 3]\n", "", {"task_area #1", "needs a 'name'"});
    expect_bad(head + "name = \"a/b\"\ncells = [0, 2, 0, 3]\n", "name = \"a/b", {"key 'name'", "may not contain"});
    expect_bad(head + "name = \"t\"\ncells = [0, 2, 0, 3]\nwidth = 2\n", "width",
               {"task_area #1 't'", "unknown key 'width'"});
    expect_bad(head +
                   "name = \"t\"\ncells = [0, 2, 0, 3]\n[[detector.task_area]]\nname = \"t\"\ncells = [0, 1, 0, 1]\n",
               "name = \"t\"\ncells = [0, 1", {"task_area #2 't'", "task area 't' is defined twice"});
    expect_bad(kMat + kFloor + kLamp + kDesk + "task_area = 3\n", "task_area",
               {"key 'task_area'", "expected an array"});
    expect_bad(kMat + kFloor + kLamp + kDesk + "task_area = [1]\n", "task_area",
               {"key 'task_area'", "expected [[detector.task_area]]"});
    expect_bad(kMat + kFloor + kLamp +
                   "[[detector]]\nname = \"v\"\ntype = \"luminance\"\ncenter = [0, 0, 0]\n"
                   "size = [1, 1]\ntask_area = [{ name = \"t\", cells = [0, 1, 0, 1] }]\n",
               "task_area", {"key 'task_area'", "illuminance detectors", "no uniformity"});
}

}  // namespace
}  // namespace luxtrace
