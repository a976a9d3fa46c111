// Tests of the run part of load_scene (src/scene/run_loader.cpp: [run] and its
// [[run.target]]): the run table and the targets land as they should, and bad photon
// counts, samplers, target ranges, light-scene keys and BVH qualities are InputErrors
// naming the file, the line (or key) and what is wrong; "auto" picks the BVH quality by size.
#include "luxtrace/tracer/embree_scene.hpp"
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once (tests/data/scenes/every_key.toml).

TEST_F(EveryKey, RunTableAndTargets) {
    const RunConfig& r = s().run;
    EXPECT_EQ(r.seed, 42u);
    EXPECT_EQ(r.photons, 100'000'000u);  // "100M"
    EXPECT_EQ(r.time_limit_s, 600.0);
    EXPECT_EQ(r.report_every_s, 5.0);
    EXPECT_EQ(r.checkpoint_every_s, 120.0);
    EXPECT_EQ(fs::path(r.output), data("scenes") / "results" / "every_key.h5");
    EXPECT_EQ(fs::path(r.checkpoint), data("scenes") / "results" / "every_key.ckpt");
    EXPECT_EQ(r.sampler, "random");
    EXPECT_EQ(r.max_bounces, 500);
    ASSERT_EQ(r.targets.size(), 3u);
    const Target& g = r.targets[0];
    EXPECT_TRUE(g.detector.empty());
    EXPECT_EQ(g.relative_error, 0.02);
    EXPECT_EQ(g.averaging, Averaging::arithmetic);
    const Target& d = r.targets[1];
    EXPECT_EQ(d.detector, "desk");
    EXPECT_EQ(d.absolute_error, 5.0);
    EXPECT_EQ(d.averaging, Averaging::quadratic);  // the default
    EXPECT_EQ(std::vector<int>({d.i0, d.i1, d.j0, d.j1}), std::vector<int>({0, 12, 0, 8}));
    const Target& c = r.targets[2];
    EXPECT_EQ(c.detector, "wall_view");
    EXPECT_EQ(std::vector<int>({c.i0, c.i1, c.j0, c.j1}), std::vector<int>({1, 3, 0, 2}));
    EXPECT_EQ(c.photons_received, 1e6);
    EXPECT_EQ(c.relative_error, 0.0);
    EXPECT_EQ(c.averaging, Averaging::quadratic);
}

// ---------------------------------------------------------------------------------
// Run tables written by the test, and bad ones.

TEST_F(Loader, PhotonCountForms) {
    for (const auto& [text, want] : std::vector<std::pair<std::string, std::uint64_t>>{{"5000", 5000},
                                                                                       {"1e6", 1'000'000},
                                                                                       {"\"100M\"", 100'000'000},
                                                                                       {"\"2.5k\"", 2500}}) {
        const Scene s = load(kMat + kFloor + kLamp + "[run]\nphotons = " + text + "\n");
        EXPECT_EQ(s.run.photons, want) << text;
    }
}

TEST_F(Loader, SamplersAndReplicates) {
    // sobol with its R; an unknown sampler and a bad R are clear errors naming the key,
    // not failures inside a tracing thread.
    const Scene s = load(kMat + kFloor + kLamp + "[run]\nsampler = \"sobol\"\nreplicates = 16\n");
    EXPECT_EQ(s.run.sampler, "sobol");
    EXPECT_EQ(s.run.replicates, 16u);
    EXPECT_EQ(load(kMat + kFloor + kLamp).run.replicates, 8u);
    expect_bad(kMat + kFloor + kLamp + "[run]\nsampler = \"halton\"\n", "sampler",
               {"key 'sampler'", "unknown sampler 'halton'", "random, sobol"});
    for (const char* bad : {"7", "0", "2048", "-2"})
        expect_bad(kMat + kFloor + kLamp + "[run]\nsampler = \"sobol\"\nreplicates = " + bad + "\n", "replicates",
                   {"key 'replicates'", "even number from 2 to 1024"});
}

TEST_F(Loader, BadTargetRange) {
    const std::string head = kMat + kFloor + kLamp + kDesk + "[[run.target]]\nrelative_error = 0.1\non = ";
    for (const std::string on : {"\"detector:desk[0:2]\"", "\"detector:desk[0:2,0:1\"", "\"detector:desk[0-2,0:1]\"",
                                 "\"detector:desk[0:2,0:1]x\"", "\"detector:[0:2,0:1]\"", "\"detectors:desk\""})
        expect_bad(head + on + "\n", "on = \"", {"key 'on'"});
    expect_bad(head + "\"detector:desk[0:2,0:1]x\"\n", "on = \"", {"cell range must read [i0:i1,j0:j1]"});
    for (const std::string on : {"\"detector:desk[0:5,0:1]\"", "\"detector:desk[0:2,1:4]\"",
                                 "\"detector:desk[2:2,0:1]\"", "\"detector:desk[-1:2,0:1]\""})
        expect_bad(head + on + "\n", "on = \"", {"key 'on'", "outside the 4 x 3 grid or is empty"});
}

TEST_F(Loader, BadPhotonCounts) {
    expect_bad(kMat + kFloor + kLamp + "[run]\nphotons = 0\n", "photons", {"key 'photons'", "must be positive"});
    expect_bad(kMat + kFloor + kLamp + "[run]\nphotons = \"12X\"\n", "photons",
               {"key 'photons'", "expected a non-negative whole count"});
}

// ---------------------------------------------------------------------------------
// Hardening made with the fuzz targets (tests/fuzz/README.md): absurd sizes are refused
// before anything is allocated, and values that are finite alone but overflow or vanish
// together are refused with the entry named.

TEST_F(Loader, MaxBouncesPastTheIntRangeIsRefused) {
    expect_bad(kMat + kFloor + kLamp + "[run]\nmax_bounces = 4294967297\n", "max_bounces",
               {"key 'max_bounces'", "must lie in [1, 1000000]"});
}

// ---------------------------------------------------------------------------------
// Embree's build quality (docs/SCALING.md "Setup time of ten million triangles").

TEST_F(Loader, BvhQualityIsAutoUnlessGivenAndRefusesOtherNames) {
    EXPECT_EQ(load(kMat + kFloor + kLamp).run.bvh_quality, "auto");
    EXPECT_EQ(load(kMat + kFloor + kLamp + "[run]\nbvh_quality = \"low\"\n").run.bvh_quality, "low");
    expect_bad(kMat + kFloor + kLamp + "[run]\nbvh_quality = \"best\"\n", "bvh_quality",
               {"key 'bvh_quality'", "expected \"auto\", \"low\", \"medium\" or \"high\""});
}

// "auto" builds a large scene without spatial splits (MEDIUM) and a small one with them
// (HIGH); a name given wins.
TEST(BvhOptions, AutoIsMediumFromTheThresholdAndAGivenQualityWins) {
    Scene scene;
    scene.triangles.resize(BvhOptions::kMediumBvhTriangles - 1);
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_HIGH);
    scene.triangles.emplace_back(0u);
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_MEDIUM);
    scene.run.bvh_quality = "low";
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_LOW);
    EXPECT_EQ(BvhOptions::of(scene).geometry_quality, RTC_BUILD_QUALITY_LOW);
    scene.run.bvh_quality = "high";
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_HIGH);
    scene.run.bvh_quality = "medium";
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_MEDIUM);
    scene.triangles.resize(3);
    scene.run.bvh_quality = "low";
    EXPECT_EQ(BvhOptions::of(scene).quality, RTC_BUILD_QUALITY_LOW);
}

// ---------------------------------------------------------------------------------
// Light groups and light scenes (issue 22): group maps, and targets on a light scene.

TEST_F(Loader, GroupMapsAndTargetsOnALightScene) {
    EXPECT_TRUE(load(kMat + kFloor + kLamp).run.group_maps);  // the default
    EXPECT_FALSE(load(kMat + kFloor + kLamp + "[run]\ngroup_maps = false\n").run.group_maps);
    const Scene s = load(kMat + kFloor + lamp_in("a") + kDesk +
                         "[[observer]]\nname = \"eye\"\nposition = [0, -1, 1.2]\nview_direction = [0, 1, 0]\n"
                         "[[light_scene]]\nname = \"half\"\ndimming = { a = 0.5 }\n"
                         "[[run.target]]\nrelative_error = 0.1\nscene = \"half\"\n"
                         "[[run.target]]\non = \"detector:desk[0:2,0:1]\"\nrelative_error = 0.1\nscene = \"half\"\n"
                         "[[run.target]]\non = \"observer:eye\"\nrelative_error = 0.1\nscene = \"half\"\n"
                         "[[run.target]]\nrelative_error = 0.1\n");
    ASSERT_EQ(s.run.targets.size(), 4u);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(s.run.targets[i].light_scene, "half") << i;
    EXPECT_EQ(s.run.targets[1].detector, "desk");
    EXPECT_EQ(s.run.targets[2].detector, "observer:eye");
    EXPECT_TRUE(s.run.targets[3].light_scene.empty());  // the plain run
}

TEST_F(Loader, BadRunGroupKeysAreRefused) {
    const std::string base = kMat + kFloor + lamp_in("desk");
    expect_bad(base + "[run]\ngroup_maps = 1\n", "group_maps", {"[run]", "key 'group_maps'", "expected true or false"});
    expect_bad(base + "[[run.target]]\nrelative_error = 0.1\nscene = \"evening\"\n",
               "scene =", {"[[run.target]] #1", "key 'scene'", "no [[light_scene]] is named 'evening'", "has none"});
    expect_bad(base + "[[light_scene]]\nname = \"day\"\ndimming = { desk = 1 }\n"
                      "[[run.target]]\nrelative_error = 0.1\nscene = \"evening\"\n",
               "scene =", {"key 'scene'", "no [[light_scene]] is named 'evening'", "the light scenes: day"});
}

}  // namespace
}  // namespace luxtrace
