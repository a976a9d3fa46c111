// Tests of the light part of load_scene (src/scene/light_loader.cpp, [[light]], and
// src/scene/light_scene_loader.cpp, [[light_scene]]): every kind of light lands as it should,
// lights are numbered into their groups, light scenes weigh the groups, and bad lights,
// groups and light scenes are InputErrors naming the file, the line (or key) and what is
// wrong.
#include "luxtrace/light/ies.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"

#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once (tests/data/scenes/every_key.toml).

TEST_F(EveryKey, Lights) {
    const auto& L = s().lights.lights();
    ASSERT_EQ(L.size(), 5u);
    ASSERT_TRUE(L[0].is<PointLight>());
    expect_vec(L[0].as<PointLight>()->position, Vec3(0, 0, 2.5));
    EXPECT_EQ(L[0].flux_lm, 1200.0);
    ASSERT_EQ(L[0].band_share.size(), 3u);  // colour [2,1,1], normalised
    EXPECT_NEAR(L[0].band_share[0], 0.5, 1e-15);
    EXPECT_NEAR(L[0].band_share[1], 0.25, 1e-15);
    EXPECT_NEAR(L[0].band_share[2], 0.25, 1e-15);

    // IES: the flux is the file's times the multiplier; +z of the frame is the aim.
    const PointLight& ies = *L[1].as<PointLight>();
    ASSERT_NE(ies.distribution, nullptr);
    const double file_flux = load_ies(data("ies/cosine.ies")).flux_lm();
    EXPECT_NEAR(L[1].flux_lm, 2.5 * file_flux, 1e-12 * file_flux);
    expect_vec(ies.frame.n, Vec3(0, 0.6, -0.8));
    expect_vec(ies.frame.t, Vec3(1, 0, 0));  // C0 plane: scene +x, already normal to the aim

    ASSERT_TRUE(L[2].is<SpotLight>());
    EXPECT_EQ(L[2].flux_lm, 800.0);
    expect_vec(L[2].as<SpotLight>()->frame.n, Vec3(0, 0, -1));  // direction [0,0,-2], normalised
    EXPECT_NEAR(L[2].as<SpotLight>()->cos_half_angle, std::cos(30.0 * kPi / 180.0), 1e-15);

    ASSERT_TRUE(L[3].is<AreaLight>());
    EXPECT_EQ(L[3].flux_lm, 3000.0);
    const EmitterSurface& surface = L[3].as<AreaLight>()->surface;
    EXPECT_NEAR(surface.area_m2, 0.18, 1e-6);
    for (const Vec3& n : surface.normal) expect_vec(n, Vec3(0, 0, -1), 1e-6);
    const std::uint32_t mixed = material_id(s(), "mixed");
    for (int t : surface.scene_triangle) EXPECT_EQ(s().triangle_material[t], mixed);
    for (double share : L[3].band_share) EXPECT_NEAR(share, 1.0 / 3.0, 1e-15);

    // Directional: flux = E * pi R^2 of a beam that covers every vertex of the scene.
    ASSERT_TRUE(L[4].is<DirectionalLight>());
    const DirectionalLight& d = *L[4].as<DirectionalLight>();
    expect_vec(d.aim, glm::normalize(Vec3(1, 0, -1)));
    EXPECT_EQ(d.illuminance_lx, 100.0);
    EXPECT_NEAR(L[4].flux_lm, 100.0 * kPi * d.beam.radius * d.beam.radius, 1e-9 * L[4].flux_lm);
    for (const Vec3& v : s().vertices) {
        const Vec3 r = v - d.beam.center;
        EXPECT_GT(glm::dot(r, d.aim), 0.0);
        EXPECT_LE(glm::length(r - glm::dot(r, d.aim) * d.aim), d.beam.radius);
    }
    EXPECT_NEAR(s().lights.total_flux_lm(), 1200 + L[1].flux_lm + 800 + 3000 + L[4].flux_lm, 1e-9);
}

// ---------------------------------------------------------------------------------
// Bad input.

TEST_F(Loader, NegativeFlux) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = -5\n", "flux_lm",
               {"key 'flux_lm'", "must be positive"});
}

TEST_F(Loader, ZeroFlux) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nilluminance_lx = 0\n",
               "illuminance_lx", {"key 'illuminance_lx'", "must be positive"});
}

TEST_F(Loader, MissingIesFile) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nies = \"absent.ies\"\n",
               "ies =", {"key 'ies'", "absent.ies", "cannot open"});
}

TEST_F(Loader, BadIesFile) {
    const std::string ies = data("ies/bad_truncated.ies").string();
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nies = \"" + ies + "\"\n",
               "ies =", {"key 'ies'", ies + ":", "unexpected end of file"});
}

TEST_F(Loader, AreaLightNamingAnUnknownShape) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"area\"\nflux_lm = 10\nshape = \"panel\"\n",
               "shape =", {"key 'shape'", "no [[shape]] is named 'panel'"});
}

TEST_F(Loader, SceneWithNoLights) { expect_bad(kMat + kFloor, "", {"no [[light]]"}); }

// ---------------------------------------------------------------------------------
// Hardening made with the fuzz targets (tests/fuzz/README.md): absurd sizes are refused
// before anything is allocated, and values that are finite alone but overflow or vanish
// together are refused with the entry named.

TEST_F(Loader, AreaLightOnAShapeWithoutArea) {
    // Every triangle of the panel is degenerate (dropped), so it has nothing to emit from.
    expect_bad(kMat + kFloor +
                   "[[shape]]\nname = \"panel\"\ntype = \"rectangle\"\nsize = [1e-200, 1e-200]\n"
                   "material = \"m\"\n[[light]]\ntype = \"area\"\nshape = \"panel\"\nflux_lm = 10\n",
               "shape = \"panel\"", {"key 'shape'", "no area to emit from"});
}

TEST_F(Loader, FluxesThatOverflowTogetherAreRefused) {
    const std::string big = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 1e308\n";
    expect_bad(kMat + kFloor + big + big, "", {"light 2 (point)", "total flux"});
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nilluminance_lx = 1e308\n",
               "", {"light 1 (directional)", "total flux"});
    expect_bad(kMat + kFloor +
                   "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 1\ncolour = [1e308, 1e308]\n"
                   "[scene]\nbands = [\"a\", \"b\"]\n",
               "colour", {"key 'colour'", "too large"});
}

TEST_F(Loader, IesBeamNarrowerThanTheSamplingGrid) {
    // Light only within 0.1 degree of the nadir, in a file whose angles run to 90: no
    // direction of the 0.5-degree sampling table sees it.
    write("narrow.ies", "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 0.1 90\n0\n100 0 0\n");
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nies = \"narrow.ies\"\n",
               "ies =", {"key 'ies'", "narrow.ies", "too narrow a beam"});
    // The same beam in a file that ends at 0.1 degree: the table covers the file's range,
    // and every direction lies within it.
    write("pencil.ies", "TILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 0.1\n0\n100 100\n");
    const Scene s = load(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nies = \"pencil.ies\"\n");
    const Light& l = s.lights.lights().at(0);
    PhiloxSampler u(5);
    for (std::uint64_t k = 0; k < 1000; ++k) {
        u.start_photon(k);
        const double a = u.next(), b = u.next();
        EXPECT_GE(l.as<PointLight>()->distribution->sample(a, b).z, std::cos(0.1 * kPi / 180.0) - 1e-12);
    }
}

// ---------------------------------------------------------------------------------
// Light groups and light scenes (issue 22).

std::vector<std::size_t> groups_of(const Scene& s) {
    std::vector<std::size_t> out;
    for (const Light& l : s.lights.lights()) out.push_back(l.group);
    return out;
}

TEST_F(Loader, LightGroupsAreNumberedInOrderOfFirstAppearance) {
    // Without any `group` every light is in the one default group.
    const Scene plain = load(kMat + kFloor + kLamp + kLamp);
    EXPECT_EQ(plain.light_groups, std::vector<std::string>{Scene::kDefaultLightGroup});
    EXPECT_EQ(groups_of(plain), (std::vector<std::size_t>{0, 0}));
    // The default group takes its place where the first light without `group` stands.
    const Scene mixed = load(kMat + kFloor + lamp_in("b") + lamp_in("") + lamp_in("a.1") + lamp_in("b") + lamp_in(""));
    EXPECT_EQ(mixed.light_groups, (std::vector<std::string>{"b", "default", "a.1"}));
    EXPECT_EQ(groups_of(mixed), (std::vector<std::size_t>{0, 1, 2, 0, 1}));
    // Every light named: no default group. Naming "default" is that group.
    const Scene named = load(kMat + kFloor + lamp_in("desk") + lamp_in("window-row_2"));
    EXPECT_EQ(named.light_groups, (std::vector<std::string>{"desk", "window-row_2"}));
    const Scene explicit_default = load(kMat + kFloor + lamp_in("default") + lamp_in("x") + lamp_in(""));
    EXPECT_EQ(explicit_default.light_groups, (std::vector<std::string>{"default", "x"}));
    EXPECT_EQ(groups_of(explicit_default), (std::vector<std::size_t>{0, 1, 0}));
}

TEST_F(Loader, EveryCopyOfALightEntryIsInItsGroup) {
    const Scene s = load(kMat + kFloor + lamp_in("first") +
                         "[[light]]\ntype = \"point\"\npositions = [[0, 0, 1], [1, 0, 1], [2, 0, 1]]\nflux_lm = 10\n"
                         "group = \"row\"\n"
                         "[[light]]\ntype = \"spot\"\nhalf_angle_deg = 30\nflux_lm = 10\ngroup = \"grid\"\n"
                         "grid = { first = [0, 0, 2], spacing = [1, 1], count = [2, 2] }\n");
    EXPECT_EQ(s.light_groups, (std::vector<std::string>{"first", "row", "grid"}));
    EXPECT_EQ(groups_of(s), (std::vector<std::size_t>{0, 1, 1, 1, 2, 2, 2, 2}));
}

TEST_F(Loader, LightScenesWeighTheGroupsTheyNameAndTurnTheOthersOff) {
    const Scene s = load(kMat + kFloor + lamp_in("desk") + lamp_in("") + lamp_in("window.row") +
                         "[[light_scene]]\nname = \"evening\"\ndimming = { desk = 0.3, \"window.row\" = 1 }\n"
                         "[[light_scene]]\nname = \"boost\"\n[light_scene.dimming]\ndefault = 2.5\n");
    ASSERT_EQ(s.light_scenes.size(), 2u);
    EXPECT_EQ(s.light_scenes[0].name, "evening");
    EXPECT_EQ(s.light_scenes[0].weights, (std::vector<double>{0.3, 0.0, 1.0}));  // desk, default, window.row
    EXPECT_EQ(s.light_scenes[1].name, "boost");
    EXPECT_EQ(s.light_scenes[1].weights, (std::vector<double>{0.0, 2.5, 0.0}));  // a weight above 1 boosts
    EXPECT_TRUE(load(kMat + kFloor + kLamp).light_scenes.empty());
}

TEST_F(Loader, BadLightGroupsAreRefused) {
    const std::string base = kMat + kFloor + kLamp;
    expect_bad(base + lamp_in("", 2) + "group = \"\"\n", "group = \"\"",
               {"[[light]] #2", "key 'group'", "not be empty"});
    for (const std::string name : {"a b", "a/b", "a=b", "a,b", "a:b", "\u00e9t\u00e9"})
        expect_bad(base + lamp_in(name), "group = ", {"key 'group'", "only letters, digits, '_', '-' and '.'"});
    expect_bad(base + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 1\ngroup = 3\n", "group = 3",
               {"key 'group'", "expected a string"});
}

TEST_F(Loader, BadLightScenesAreRefused) {
    const std::string base = kMat + kFloor + lamp_in("desk") + lamp_in("");
    const std::string ls = "[[light_scene]]\n";
    expect_bad(base + ls + "dimming = { desk = 1 }\n", "[[light_scene]]", {"[[light_scene]] #1", "needs a 'name'"});
    expect_bad(base + ls + "name = \"x y\"\ndimming = { desk = 1 }\n", "name = \"x y", {"key 'name'", "only letters"});
    expect_bad(base + ls + "name = \"\"\ndimming = { desk = 1 }\n", "name = \"\"", {"key 'name'", "not be empty"});
    expect_bad(base + ls + "name = \"e\"\ndimming = { desk = 1 }\n" + ls +
                   "name = \"e\" # again\ndimming = { desk = 1 }\n",
               "# again", {"[[light_scene]] #2 'e'", "key 'name'", "light scene 'e' is defined twice"});
    expect_bad(base + ls + "name = \"e\"\n", "[[light_scene]]", {"needs 'dimming'"});
    expect_bad(base + ls + "name = \"e\"\ndimming = 1\n", "dimming", {"key 'dimming'", "expected a table"});
    // A key that is no group names the key and lists the groups.
    expect_bad(base + ls + "name = \"e\"\n[light_scene.dimming]\ndesk = 1\nwindow = 0.5\n", "window",
               {"[[light_scene]] #1 'e'", "key 'dimming.window'", "no light group is named 'window'",
                "the groups: desk, default"});
    expect_bad(base + ls + "name = \"e\"\n[light_scene.dimming]\ndesk = -0.5\n", "desk = -0.5",
               {"key 'dimming.desk'", "a number >= 0"});
    for (const std::string w : {"\"full\"", "true", "inf", "nan", "[1]"})
        expect_bad(base + ls + "name = \"e\"\n[light_scene.dimming]\ndesk = " + w + "\n", "desk = " + w,
                   {"key 'dimming.desk'", "expected a weight"});
    expect_bad(base + ls + "name = \"e\"\n[light_scene.dimming]\ndesk.lamp = 1\n", "desk.lamp",
               {"key 'dimming.desk'", "quote a group name with '.'"});
    // All groups off.
    expect_bad(base + ls + "name = \"e\"\ndimming = { desk = 0, default = 0 }\n",
               "dimming =", {"key 'dimming'", "the light scene would be dark"});
    expect_bad(base + ls + "name = \"e\"\ndimming = {}\n", "dimming =", {"key 'dimming'", "would be dark"});
    expect_bad(base + ls + "name = \"e\"\ndimming = { desk = 1 }\nbrightness = 2\n", "brightness",
               {"unknown key 'brightness'"});
}

}  // namespace
}  // namespace luxtrace
