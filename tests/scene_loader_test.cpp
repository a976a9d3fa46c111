// Tests of load_scene as a whole (docs/REFERENCE.md §2): the [scene] table, a minimal
// scene's defaults, and the classes of bad input every part of the loader shares (TOML
// syntax, unknown keys, missing keys, wrong types, unknown types, names defined twice), each
// an InputError whose message names the scene file, the line (or key) and what is wrong.
// The parts of a scene are tested beside their loaders: geometry_loader_test.cpp,
// light_loader_test.cpp, detector_loader_test.cpp and run_loader_test.cpp.
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once (tests/data/scenes/every_key.toml).

TEST_F(EveryKey, SceneTableAndMaterials) {
    EXPECT_EQ(s().name, "every key");
    EXPECT_EQ(s().bands, (std::vector<std::string>{"R", "G", "B"}));
    ASSERT_EQ(s().materials.size(), 7u);
    const auto& m = s().materials;
    using V = std::vector<double>;
    EXPECT_EQ(m[0].type, MaterialType::diffuse);
    EXPECT_EQ(m[0].diffuse_reflectance, (V{0.5, 0.5, 0.5}));  // a scalar fills every band
    EXPECT_EQ(m[1].diffuse_reflectance, (V{0.7, 0.2, 0.1}));
    EXPECT_EQ(m[2].type, MaterialType::diffuse);  // the default type
    EXPECT_EQ(m[2].diffuse_reflectance, (V{0.8, 0.8, 0.75}));
    EXPECT_EQ(m[3].type, MaterialType::mirror);
    EXPECT_EQ(m[3].specular_reflectance, (V{0.9, 0.85, 0.8}));
    EXPECT_EQ(m[4].type, MaterialType::glass);
    EXPECT_EQ(m[4].ior, 1.52);
    EXPECT_EQ(m[4].transmittance, (V{0.92, 0.92, 0.92}));
    EXPECT_EQ(m[5].type, MaterialType::general);
    EXPECT_EQ(m[5].diffuse_reflectance, (V{0.2, 0.2, 0.2}));
    EXPECT_EQ(m[5].specular_reflectance, (V{0.1, 0.2, 0.3}));
    EXPECT_EQ(m[5].diffuse_transmittance, (V{0.15, 0.15, 0.15}));
    EXPECT_EQ(m[5].specular_transmittance, (V{0.25, 0.25, 0.25}));
    EXPECT_EQ(m[6].type, MaterialType::black);
    EXPECT_EQ(m[6].name, "soot");
}

// ---------------------------------------------------------------------------------
// Scenes written by the test into a fresh temporary folder.

TEST_F(Loader, DefaultsOfAMinimalScene) {
    const Scene s = load(kMat + kFloor + kLamp);
    EXPECT_EQ(s.name, "scene");  // the file's stem
    EXPECT_EQ(s.bands, std::vector<std::string>{"Y"});
    EXPECT_TRUE(s.detectors.empty());
    EXPECT_TRUE(s.run.targets.empty());
}

// ---------------------------------------------------------------------------------
// Bad input: one test per class.

TEST_F(Loader, TomlSyntaxError) {
    expect_bad(kMat + "[[shape]]\ntype = \"rectangle\nsize = [2, 2]\n" + kLamp, "type = \"rectangle",
               {"TOML syntax error"});
}

TEST_F(Loader, UnknownKeys) {
    expect_bad("bogus = 1\n" + kMat + kFloor + kLamp, "bogus", {"unknown key 'bogus'"});
    // A misspelt table must not be hidden behind "no lights".
    expect_bad(kMat + kFloor + "[[lights]]\ntype = \"point\"\n", "[[lights]]", {"unknown key 'lights'"});
    expect_bad(kMat + "colour = 0.3\n" + kFloor + kLamp, "colour", {"[[material]] #1 'm'", "unknown key 'colour'"});
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"x.obj\"\ntransform = { translate = [0, 0, 0], spin = 3 }\n", "spin",
               {"transform", "unknown key 'spin'"});
    expect_bad(kMat + kFloor + kLamp + "[[run.target]]\nrelative_error = 0.1\ntolerance = 2\n", "tolerance",
               {"[[run.target]] #1", "unknown key 'tolerance'"});
}

TEST_F(Loader, MissingRequiredKey) {
    expect_bad("[[material]]\nname = \"m\"\ntype = \"mirror\"\n" + kFloor + kLamp, "[[material]]",
               {"needs 'specular_reflectance'"});
    expect_bad(kMat + "[[shape]]\ntype = \"rectangle\"\nmaterial = \"m\"\n" + kLamp, "[[shape]]", {"needs 'size'"});
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"spot\"\nposition = [0, 0, 1]\nflux_lm = 1\n", "[[light]]",
               {"needs 'half_angle_deg'"});
}

TEST_F(Loader, WrongType) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = \"bright\"\n", "flux_lm",
               {"key 'flux_lm'", "expected a finite number"});
    expect_bad(kMat + "[[shape]]\ntype = \"box\"\nsize = [1, 1, 1]\nmaterial = \"m\"\ninward = 1\n" + kLamp, "inward",
               {"key 'inward'", "expected true or false"});
    expect_bad(kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ncenter = [0, 0]\nsize = [1, 1]\n", "center",
               {"key 'center'", "expected an array of 3 numbers"});
}

TEST_F(Loader, UnknownTypes) {
    expect_bad("[[material]]\nname = \"m\"\ntype = \"plastic\"\n" + kFloor + kLamp, "plastic",
               {"unknown material type 'plastic'"});
    expect_bad(kMat + "[[shape]]\ntype = \"cone\"\nmaterial = \"m\"\n" + kLamp, "cone", {"unknown shape type 'cone'"});
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"laser\"\n", "laser", {"unknown light type 'laser'"});
    expect_bad(kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ntype = \"radiance\"\n", "radiance",
               {"unknown detector type 'radiance'"});
}

TEST_F(Loader, DuplicateNames) {
    // The second definition's name line carries "# again": the message must point there.
    auto again = [](std::string block) { return block.insert(block.find('\n', block.find("name")), " # again"); };
    expect_bad(kMat + again(kMat) + kFloor + kLamp, "# again", {"key 'name'", "material 'm' is defined twice"});
    const std::string named = "[[shape]]\ntype = \"disk\"\nradius = 1\nmaterial = \"m\"\nname = \"lamp\"\n";
    expect_bad(kMat + named + again(named) + kLamp, "# again", {"key 'name'", "shape 'lamp' is defined twice"});
    expect_bad(kMat + kFloor + kLamp + kDesk + again(kDesk), "# again",
               {"key 'name'", "detector 'desk' is defined twice"});
}

}  // namespace
}  // namespace luxtrace
