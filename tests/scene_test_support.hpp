#pragma once
// Helpers shared by the tests of load_scene (tests/*_loader_test.cpp): the committed scene
// that uses every key once (EveryKey), scenes written into a scratch folder and bad input
// expected as an InputError naming the file, the line and the key (Loader), and measures of
// the loaded triangles.
#include "luxtrace/scene/scene.hpp"

#include "luxtrace/core/error.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifndef LUXTRACE_TEST_DATA_DIR
#error "define LUXTRACE_TEST_DATA_DIR (the tests/data folder)"
#endif

namespace luxtrace::test_support {

namespace fs = std::filesystem;

inline fs::path data(const std::string& rel) { return fs::path(LUXTRACE_TEST_DATA_DIR) / rel; }

// Vertices are stored as floats: positions carry ~1e-7 relative rounding.
inline constexpr double kPosTol = 1e-5;

inline std::uint32_t material_id(const Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return static_cast<std::uint32_t>(i);
    ADD_FAILURE() << "no material " << name;
    return UINT32_MAX;
}

inline std::vector<std::size_t> triangles_of(const Scene& s, const std::string& material) {
    const std::uint32_t m = material_id(s, material);
    std::vector<std::size_t> out;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        if (s.triangle_material[t] == m) out.push_back(t);
    return out;
}

inline double area_of(const Scene& s, const std::vector<std::size_t>& tris) {
    double a = 0.0;
    for (std::size_t t : tris) a += s.triangle_area_m2[t];
    return a;
}

inline Vec3 centroid(const Scene& s, std::size_t t) {
    const glm::uvec3 v = s.triangles[t];
    return (Vec3(s.vertices[v.x]) + Vec3(s.vertices[v.y]) + Vec3(s.vertices[v.z])) / 3.0;
}

// Front sides face away from `center` (outward) or toward it (inward) for every triangle.
inline void expect_facing(const Scene& s, const std::vector<std::size_t>& tris, const Vec3& center, bool inward) {
    for (std::size_t t : tris) {
        const double d = glm::dot(s.triangle_normal[t], centroid(s, t) - center);
        EXPECT_TRUE(inward ? d < 0.0 : d > 0.0) << "triangle " << t << " faces the wrong way";
    }
}

// Spread of the triangles' vertices along a unit axis.
inline double extent_along(const Scene& s, const std::vector<std::size_t>& tris, const Vec3& axis) {
    double lo = 1e300, hi = -1e300;
    for (std::size_t t : tris)
        for (int k = 0; k < 3; ++k) {
            const double p = glm::dot(Vec3(s.vertices[s.triangles[t][k]]), axis);
            lo = std::min(lo, p);
            hi = std::max(hi, p);
        }
    return hi - lo;
}

inline void expect_vec(const Vec3& got, const Vec3& want, double tol = 1e-12) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

// The committed scene that uses every key once, loaded once per test suite.
class EveryKey : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new Scene(load_scene(data("scenes/every_key.toml"))); }
    static void TearDownTestSuite() { delete scene_; }
    static const Scene& s() { return *scene_; }
    inline static Scene* scene_ = nullptr;
};

// Pieces of scenes written by the tests.
inline const std::string kMat = "[[material]]\nname = \"m\"\nreflectance = 0.5\n";
inline const std::string kFloor = "[[shape]]\ntype = \"rectangle\"\nsize = [2, 2]\nmaterial = \"m\"\n";
inline const std::string kLamp = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 100\n";
inline const std::string kDesk = "[[detector]]\nname = \"desk\"\ncenter = [0, 0, 0.5]\nsize = [1, 1]\ncells = [4, 3]\n";

inline std::string cube_obj() { return data("scenes/cube.obj").string(); }

// A point light of 100 lm at height z, in `group` (none when empty).
inline std::string lamp_in(const std::string& group, double z = 1.0) {
    return "[[light]]\ntype = \"point\"\nposition = [0, 0, " + std::to_string(z) + "]\nflux_lm = 100\n" +
           (group.empty() ? "" : "group = \"" + group + "\"\n");
}

// Scenes written by the test into a fresh temporary folder.
class Loader : public ::testing::Test {
protected:
    ScratchDir scratch_{std::string("scene_test_") + ::testing::UnitTest::GetInstance()->current_test_info()->name()};
    const fs::path& dir_ = scratch_.path();

    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(dir_ / name) << text;
        return dir_ / name;
    }
    Scene load(const std::string& text) const { return load_scene(write("scene.toml", text)); }

    // Loading must throw InputError naming scene.toml, at the line holding `at` (when
    // given), and containing every fragment.
    void expect_bad(const std::string& text, const std::string& at, const std::vector<std::string>& fragments) const {
        const fs::path file = write("scene.toml", text);
        std::string where = file.string();
        if (!at.empty()) {
            const std::size_t pos = text.find(at);
            ASSERT_NE(pos, std::string::npos) << "test bug: '" << at << "' not in the scene";
            const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n');
            where.append(":").append(std::to_string(line)).append(":");
        }
        try {
            (void)load_scene(file);
            ADD_FAILURE() << "no InputError for:\n" << text;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(where), std::string::npos) << "'" << where << "' not in: " << msg;
            for (const std::string& f : fragments)
                EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
        }
    }
};

}  // namespace luxtrace::test_support
