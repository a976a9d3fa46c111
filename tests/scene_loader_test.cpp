// Tests of load_scene (docs/REFERENCE.md §2): every key of tests/data/scenes/every_key.toml lands
// where it should; built-in shapes and transformed meshes have the right areas,
// positions and front sides; and each class of bad input is an InputError whose
// message names the scene file, the line (or key) and what is wrong.
#include "luxtrace/sampler/sampler.hpp"
#include "luxtrace/scene/scene.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/light/ies.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#ifndef LUXTRACE_TEST_DATA_DIR
#error "define LUXTRACE_TEST_DATA_DIR (the tests/data folder)"
#endif

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

fs::path data(const std::string& rel) { return fs::path(LUXTRACE_TEST_DATA_DIR) / rel; }

// Vertices are stored as floats: positions carry ~1e-7 relative rounding.
constexpr double kPosTol = 1e-5;

std::uint32_t material_id(const Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return static_cast<std::uint32_t>(i);
    ADD_FAILURE() << "no material " << name;
    return UINT32_MAX;
}

std::vector<std::size_t> triangles_of(const Scene& s, const std::string& material) {
    const std::uint32_t m = material_id(s, material);
    std::vector<std::size_t> out;
    for (std::size_t t = 0; t < s.triangle_count(); ++t)
        if (s.triangle_material[t] == m) out.push_back(t);
    return out;
}

double area_of(const Scene& s, const std::vector<std::size_t>& tris) {
    double a = 0.0;
    for (std::size_t t : tris) a += s.triangle_area_m2[t];
    return a;
}

Vec3 centroid(const Scene& s, std::size_t t) {
    const glm::uvec3 v = s.triangles[t];
    return (Vec3(s.vertices[v.x]) + Vec3(s.vertices[v.y]) + Vec3(s.vertices[v.z])) / 3.0;
}

// Front sides face away from `center` (outward) or toward it (inward) for every triangle.
void expect_facing(const Scene& s, const std::vector<std::size_t>& tris, const Vec3& center, bool inward) {
    for (std::size_t t : tris) {
        const double d = glm::dot(s.triangle_normal[t], centroid(s, t) - center);
        EXPECT_TRUE(inward ? d < 0.0 : d > 0.0) << "triangle " << t << " faces the wrong way";
    }
}

// Spread of the triangles' vertices along a unit axis.
double extent_along(const Scene& s, const std::vector<std::size_t>& tris, const Vec3& axis) {
    double lo = 1e300, hi = -1e300;
    for (std::size_t t : tris)
        for (int k = 0; k < 3; ++k) {
            const double p = glm::dot(Vec3(s.vertices[s.triangles[t][k]]), axis);
            lo = std::min(lo, p);
            hi = std::max(hi, p);
        }
    return hi - lo;
}

void expect_vec(const Vec3& got, const Vec3& want, double tol = 1e-12) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once.

class EveryKey : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new Scene(load_scene(data("scenes/every_key.toml"))); }
    static void TearDownTestSuite() { delete scene_; }
    static const Scene& s() { return *scene_; }
    static Scene* scene_;
};
Scene* EveryKey::scene_ = nullptr;

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

TEST_F(EveryKey, GeometryByMaterial) {
    // Mesh 1: cube of side 2 (scale 2.0), default "grey"; its +-x faces say `usemtl red`.
    // Mesh 2: cube scaled [1,2,-1], default "soot"; its +-x faces (2 m^2 each) are red.
    // The `usemtl nosuch` faces match no [[material]] and keep the default.
    EXPECT_NEAR(area_of(s(), triangles_of(s(), "grey")), 4 * 4.0, 1e-5);
    EXPECT_NEAR(area_of(s(), triangles_of(s(), "red")), 2 * 4.0 + 2 * 2.0, 1e-5);
    EXPECT_NEAR(area_of(s(), triangles_of(s(), "soot")), 2 * 2.0 + 2 * 1.0, 1e-5);
    expect_facing(s(), triangles_of(s(), "grey"), Vec3(1, 1.5, 1), false);
    expect_facing(s(), triangles_of(s(), "soot"), Vec3(-1.5, 0, 1), false);

    // Panel: size [0.6, 0.3], up = +x, normal -z, so u = up x normal = +y carries 0.6.
    const auto panel = triangles_of(s(), "mixed");
    EXPECT_NEAR(area_of(s(), panel), 0.6 * 0.3, 1e-6);
    EXPECT_NEAR(extent_along(s(), panel, Vec3(0, 1, 0)), 0.6, kPosTol);
    EXPECT_NEAR(extent_along(s(), panel, Vec3(1, 0, 0)), 0.3, kPosTol);
    for (std::size_t t : panel) expect_vec(s().triangle_normal[t], Vec3(0, 0, -1), 1e-6);

    const auto room = triangles_of(s(), "silver");  // inward box 6 x 5 x 3
    EXPECT_NEAR(area_of(s(), room), 2 * (6 * 5 + 5 * 3 + 3 * 6), 1e-4);
    expect_facing(s(), room, Vec3(0, 0, 1.5), true);

    const auto ball = triangles_of(s(), "pane");  // sphere r 0.4: inscribed, so a bit less
    EXPECT_LT(area_of(s(), ball), 4 * kPi * 0.16);
    EXPECT_GT(area_of(s(), ball), 0.98 * 4 * kPi * 0.16);
    expect_facing(s(), ball, Vec3(2, -1.5, 0.5), false);

    const auto disk = triangles_of(s(), "white");
    EXPECT_LT(area_of(s(), disk), kPi * 0.25);
    EXPECT_GT(area_of(s(), disk), 0.99 * kPi * 0.25);
    for (std::size_t t : disk) expect_vec(s().triangle_normal[t], Vec3(0, 0, 1), 1e-6);

    expect_vec(s().bounds_min, Vec3(-3, -2.5, 0), kPosTol);
    expect_vec(s().bounds_max, Vec3(3, 2.5, 3), kPosTol);
}

TEST_F(EveryKey, Lights) {
    const auto& L = s().lights.lights();
    ASSERT_EQ(L.size(), 5u);
    EXPECT_EQ(L[0].type, LightType::point);
    expect_vec(L[0].position, Vec3(0, 0, 2.5));
    EXPECT_EQ(L[0].flux_lm, 1200.0);
    ASSERT_EQ(L[0].band_share.size(), 3u);  // colour [2,1,1], normalised
    EXPECT_NEAR(L[0].band_share[0], 0.5, 1e-15);
    EXPECT_NEAR(L[0].band_share[1], 0.25, 1e-15);
    EXPECT_NEAR(L[0].band_share[2], 0.25, 1e-15);

    // IES: the flux is the file's times the multiplier; +z of the frame is the aim.
    ASSERT_NE(L[1].distribution, nullptr);
    const double file_flux = load_ies(data("ies/cosine.ies")).flux_lm();
    EXPECT_NEAR(L[1].flux_lm, 2.5 * file_flux, 1e-12 * file_flux);
    expect_vec(L[1].aim, Vec3(0, 0.6, -0.8));
    expect_vec(L[1].frame.n, Vec3(0, 0.6, -0.8));
    expect_vec(L[1].frame.t, Vec3(1, 0, 0));  // C0 plane: scene +x, already normal to the aim

    EXPECT_EQ(L[2].type, LightType::spot);
    EXPECT_EQ(L[2].flux_lm, 800.0);
    expect_vec(L[2].aim, Vec3(0, 0, -1));  // direction [0,0,-2], normalised
    EXPECT_NEAR(L[2].cos_half_angle, std::cos(30.0 * kPi / 180.0), 1e-15);

    EXPECT_EQ(L[3].type, LightType::area);
    EXPECT_EQ(L[3].flux_lm, 3000.0);
    EXPECT_NEAR(L[3].surface.area_m2, 0.18, 1e-6);
    for (const Vec3& n : L[3].surface.normal) expect_vec(n, Vec3(0, 0, -1), 1e-6);
    const std::uint32_t mixed = material_id(s(), "mixed");
    for (int t : L[3].surface.scene_triangle) EXPECT_EQ(s().triangle_material[t], mixed);
    for (double share : L[3].band_share) EXPECT_NEAR(share, 1.0 / 3.0, 1e-15);

    // Directional: flux = E * pi R^2 of a beam that covers every vertex of the scene.
    const Light& d = L[4];
    EXPECT_EQ(d.type, LightType::directional);
    expect_vec(d.aim, glm::normalize(Vec3(1, 0, -1)));
    EXPECT_EQ(d.illuminance_lx, 100.0);
    EXPECT_NEAR(d.flux_lm, 100.0 * kPi * d.beam_radius * d.beam_radius, 1e-9 * d.flux_lm);
    for (const Vec3& v : s().vertices) {
        const Vec3 r = v - d.beam_center;
        EXPECT_GT(glm::dot(r, d.aim), 0.0);
        EXPECT_LE(glm::length(r - glm::dot(r, d.aim) * d.aim), d.beam_radius);
    }
    EXPECT_NEAR(s().lights.total_flux_lm(), 1200 + L[1].flux_lm + 800 + 3000 + d.flux_lm, 1e-9);
}

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
// Scenes written by the test into a fresh temporary folder.

const std::string kMat = "[[material]]\nname = \"m\"\nreflectance = 0.5\n";
const std::string kFloor = "[[shape]]\ntype = \"rectangle\"\nsize = [2, 2]\nmaterial = \"m\"\n";
const std::string kLamp = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 100\n";
const std::string kDesk = "[[detector]]\nname = \"desk\"\ncenter = [0, 0, 0.5]\nsize = [1, 1]\ncells = [4, 3]\n";

std::string cube_obj() { return data("scenes/cube.obj").string(); }

class Loader : public ::testing::Test {
protected:
    test_support::ScratchDir scratch_{std::string("scene_test_") +
                                      ::testing::UnitTest::GetInstance()->current_test_info()->name()};
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

TEST_F(Loader, DefaultsOfAMinimalScene) {
    const Scene s = load(kMat + kFloor + kLamp);
    EXPECT_EQ(s.name, "scene");  // the file's stem
    EXPECT_EQ(s.bands, std::vector<std::string>{"Y"});
    EXPECT_TRUE(s.detectors.empty());
    EXPECT_TRUE(s.run.targets.empty());
}

TEST_F(Loader, PhotonCountForms) {
    for (const auto& [text, want] : std::vector<std::pair<std::string, std::uint64_t>>{{"5000", 5000},
                                                                                       {"1e6", 1'000'000},
                                                                                       {"\"100M\"", 100'000'000},
                                                                                       {"\"2.5k\"", 2500}}) {
        const Scene s = load(kMat + kFloor + kLamp + "[run]\nphotons = " + text + "\n");
        EXPECT_EQ(s.run.photons, want) << text;
    }
}

TEST_F(Loader, MeshTransformScalesThenRotatesXYZThenTranslates) {
    write("tri.obj", "v 1 0 0\nv 0 2 0\nv 0 0 3\nf 1 2 3\n");
    const Scene s = load(kMat + kLamp +
                         "[[mesh]]\nfile = \"tri.obj\"\nmaterial = \"m\"\ntransform = { translate = "
                         "[10, 20, 30], rotate_deg = [90, 90, 90], scale = [2, 3, 4] }\n");
    // By hand: (1,0,0) -> (2,0,0) -> Rx (2,0,0) -> Ry (0,0,-2) -> Rz (0,0,-2);
    // (0,2,0) -> (0,6,0) -> (0,0,6) -> (6,0,0) -> (0,6,0); (0,0,3) -> (0,0,12) ->
    // (0,-12,0) -> (0,-12,0) -> (12,0,0); all right-handed, then + (10,20,30).
    const std::vector<Vec3> want{{10, 20, 28}, {10, 26, 30}, {22, 20, 30}};
    ASSERT_EQ(s.triangle_count(), 1u);
    for (int k = 0; k < 3; ++k) expect_vec(Vec3(s.vertices[s.triangles[0][k]]), want[k], kPosTol);
    const Vec3 n = glm::normalize(glm::cross(want[1] - want[0], want[2] - want[0]));
    expect_vec(s.triangle_normal[0], n, 1e-6);
}

TEST_F(Loader, MirroringScaleKeepsTheFrontSideOutward) {
    // A mirror image of a closed outward cube is still outward, whatever the scale's signs.
    for (const std::string scale : {"-1.0", "[1, 1, -1]", "[-2, 3, 0.5]", "[-1, -1, 1]", "[-1, -2, -3]"}) {
        const Scene s = load(kMat + kLamp + "[[mesh]]\nfile = \"" + cube_obj() +
                             "\"\nmaterial = \"m\"\ntransform = { translate = [5, 6, 7], scale = " + scale + " }\n");
        std::vector<std::size_t> all(s.triangle_count());
        for (std::size_t t = 0; t < all.size(); ++t) all[t] = t;
        SCOPED_TRACE(scale);
        EXPECT_EQ(all.size(), 12u);
        expect_facing(s, all, Vec3(5, 6, 7), false);
    }
}

TEST_F(Loader, RectangleAreaNormalAndAxes) {
    const Scene s = load(kMat + kLamp +
                         "[[shape]]\ntype = \"rectangle\"\ncenter = [1, 2, 3]\nnormal = [1, 1, 0]\n"
                         "up = [0, 0, 1]\nsize = [3, 1.5]\nsubdivisions = 5\nmaterial = \"m\"\n");
    const auto tris = triangles_of(s, "m");
    EXPECT_NEAR(area_of(s, tris), 3 * 1.5, 1e-6);
    const Vec3 n = glm::normalize(Vec3(1, 1, 0));
    for (std::size_t t : tris) expect_vec(s.triangle_normal[t], n, 1e-6);
    const Vec3 u = glm::cross(Vec3(0, 0, 1), n);  // up x normal carries size[0]
    EXPECT_NEAR(extent_along(s, tris, u), 3.0, kPosTol);
    EXPECT_NEAR(extent_along(s, tris, Vec3(0, 0, 1)), 1.5, kPosTol);
    EXPECT_NEAR(extent_along(s, tris, n), 0.0, kPosTol);
}

TEST_F(Loader, BoxAreaAndSides) {
    for (const bool inward : {false, true}) {
        const Scene s = load(kMat + kLamp +
                             "[[shape]]\ntype = \"box\"\ncenter = [1, 2, 3]\n"
                             "size = [1, 2, 3]\nsubdivisions = 2\nmaterial = \"m\"\ninward = " +
                             std::string(inward ? "true" : "false") + "\n");
        const auto tris = triangles_of(s, "m");
        EXPECT_NEAR(area_of(s, tris), 2 * (1 * 2 + 2 * 3 + 3 * 1), 1e-5);
        expect_facing(s, tris, Vec3(1, 2, 3), inward);
        EXPECT_NEAR(extent_along(s, tris, Vec3(1, 0, 0)), 1.0, kPosTol);
        EXPECT_NEAR(extent_along(s, tris, Vec3(0, 1, 0)), 2.0, kPosTol);
        EXPECT_NEAR(extent_along(s, tris, Vec3(0, 0, 1)), 3.0, kPosTol);
    }
}

// Inscribed triangulations: the area grows toward pi r^2 / 4 pi r^2 from below.
TEST_F(Loader, DiskAndSphereAreasApproachTheCircleFromBelow) {
    const double r = 0.7;
    double last_disk = 0.0, last_sphere = 0.0;
    for (const int sub : {3, 4, 8, 16, 32}) {  // spheres use at least 3 stacks
        const std::string n = std::to_string(sub);
        const Scene d = load(kMat + kLamp +
                             "[[shape]]\ntype = \"disk\"\ncenter = [0, 1, 2]\n"
                             "normal = [0, -1, 1]\nradius = 0.7\nmaterial = \"m\"\nsubdivisions = " +
                             n + "\n");
        const double ad = d.total_area_m2();
        EXPECT_LT(ad, kPi * r * r) << sub;
        EXPECT_GT(ad, last_disk) << sub;
        last_disk = ad;
        // Within 0.1 degree: the tiny central triangles carry the float vertices' rounding.
        for (const Vec3& nt : d.triangle_normal)
            EXPECT_GT(glm::dot(nt, glm::normalize(Vec3(0, -1, 1))), std::cos(0.1 * kPi / 180));
        for (const bool inward : {false, true}) {
            const Scene s = load(kMat + kLamp +
                                 "[[shape]]\ntype = \"sphere\"\ncenter = [0, 1, 2]\n"
                                 "radius = 0.7\nmaterial = \"m\"\ninward = " +
                                 (inward ? "true" : "false") + "\nsubdivisions = " + n + "\n");
            const double as = s.total_area_m2();
            EXPECT_LT(as, 4 * kPi * r * r) << sub;
            if (inward) EXPECT_DOUBLE_EQ(as, last_sphere) << sub;
            else EXPECT_GT(as, last_sphere) << sub;
            last_sphere = as;
            std::vector<std::size_t> all(s.triangle_count());
            for (std::size_t t = 0; t < all.size(); ++t) all[t] = t;
            expect_facing(s, all, Vec3(0, 1, 2), inward);
        }
    }
    EXPECT_GT(last_disk, 0.999 * kPi * r * r);
    EXPECT_GT(last_sphere, 0.995 * 4 * kPi * r * r);
}

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

TEST_F(Loader, NegativeFlux) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = -5\n", "flux_lm",
               {"key 'flux_lm'", "must be positive"});
}

TEST_F(Loader, ZeroFlux) {
    expect_bad(kMat + kFloor + "[[light]]\ntype = \"directional\"\ndirection = [0, 0, -1]\nilluminance_lx = 0\n",
               "illuminance_lx", {"key 'illuminance_lx'", "must be positive"});
}

TEST_F(Loader, ReflectanceOutsideZeroOne) {
    for (const std::string v : {"1.2", "-0.1"})
        expect_bad("[[material]]\nname = \"m\"\nreflectance = " + v + "\n" + kFloor + kLamp, "reflectance",
                   {"key 'reflectance'", "must lie in [0, 1]"});
}

TEST_F(Loader, GeneralMaterialSummingOverOne) {
    expect_bad("[scene]\nbands = [\"R\", \"G\"]\n[[material]]\nname = \"m\"\ntype = \"general\"\n"
               "diffuse_reflectance = 0.5\nspecular_transmittance = [0.4, 0.6]\n" +
                   kFloor + kLamp,
               "[[material]]", {"sum to", "> 1 in band 'G'"});
}

TEST_F(Loader, PerBandArrayOfWrongLength) {
    expect_bad("[scene]\nbands = [\"R\", \"G\", \"B\"]\n[[material]]\nname = \"m\"\nreflectance = [0.5, 0.5]\n" +
                   kFloor + kLamp,
               "reflectance", {"key 'reflectance'", "one value per band (3), got 2"});
}

TEST_F(Loader, UnknownMaterialReference) {
    expect_bad(kMat + "[[shape]]\ntype = \"disk\"\nradius = 1\nmaterial = \"nosuch\"\n" + kLamp,
               "material = \"nosuch\"", {"key 'material'", "no [[material]] is named 'nosuch'"});
    // A mesh without a default whose file material matches nothing.
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"" + cube_obj() + "\"\n", "[[mesh]]", {"no default 'material'"});
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

TEST_F(Loader, MissingMeshFile) {
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"absent.obj\"\nmaterial = \"m\"\n",
               "file =", {"absent.obj", "does not exist"});
}

TEST_F(Loader, UnreadableMesh) {
    // Assimp's OBJ reader skips lines it does not know: garbage yields no triangles.
    write("garbage.obj", "this is not\x01\x02 a mesh { f f f\n");
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"garbage.obj\"\nmaterial = \"m\"\n",
               "file =", {"[[mesh]] #1", "garbage.obj", "has no triangles"});
    write("broken.stl", "solid x\nfacet normal 0 0 1\n outer loop\n vertex 0 0");
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"broken.stl\"\nmaterial = \"m\"\n",
               "file =", {"[[mesh]] #1", "cannot read mesh", "broken.stl"});
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

TEST_F(Loader, SceneWithNoLights) { expect_bad(kMat + kFloor, "", {"no [[light]]"}); }

TEST_F(Loader, SceneWithNoSurfaces) { expect_bad(kMat + kLamp, "", {"no surfaces"}); }

// ---------------------------------------------------------------------------------
// Real meshes (tests/data/real/README.md): two Blender exports from LuxCoreRender's
// test scenes, ASCII PLY with normals, texture coordinates and (the cube) colours.

TEST_F(Loader, RealPlyCubeFromBlender) {
    const std::string ply = data("real/luxcore_simple-mat-cube1.ply").string();
    const Scene s = load(kMat + kLamp + "[[mesh]]\nfile = \"" + ply + "\"\nmaterial = \"m\"\n");
    ASSERT_EQ(s.triangle_count(), 12u);
    EXPECT_NEAR(s.total_area_m2(), 24.0, 1e-4);  // a 2 m cube, turned about z
    expect_vec(s.bounds_min, Vec3(-2.809938, -1.38206, 0.478389), kPosTol);
    expect_vec(s.bounds_max, Vec3(-0.318721, 1.109157, 2.478389), kPosTol);
    // Blender wrote the faces counter-clockwise seen from outside.
    std::vector<std::size_t> all(s.triangle_count());
    for (std::size_t t = 0; t < all.size(); ++t) all[t] = t;
    expect_facing(s, all, 0.5 * (s.bounds_min + s.bounds_max), false);
}

TEST_F(Loader, RealPlyCornellBlock) {
    const std::string ply = data("real/luxcore_cornell_box.ply").string();
    const Scene s = load(kMat + kLamp + "[[mesh]]\nfile = \"" + ply + "\"\nmaterial = \"m\"\n");
    ASSERT_EQ(s.triangle_count(), 12u);
    EXPECT_NEAR(s.total_area_m2(), 36.355554, 1e-4);  // the file's 12 triangles summed (numpy)
    expect_vec(s.bounds_min, Vec3(-5.232944, 1.801294, 0.00585), kPosTol);
    expect_vec(s.bounds_max, Vec3(-0.178533, 3.801294, 1.149667), kPosTol);
}

// ---------------------------------------------------------------------------------
// Hardening made with the fuzz targets (tests/fuzz/README.md): absurd sizes are refused
// before anything is allocated, and values that are finite alone but overflow or vanish
// together are refused with the entry named.

// Found by fuzz_mesh (tests/fuzz/crashers/mesh/ply_header_*): assimp 5.2.5's PLY reader
// never returns on a header without an "end_header" line, so `luxtrace check` hung on a
// PLY file cut short inside its header. The loader refuses such a file itself.
TEST_F(Loader, PlyHeaderWithoutEndHeaderIsRefused) {
    const std::string cube = [] {
        std::ifstream in(data("real/luxcore_simple-mat-cube1.ply"), std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }();
    const std::size_t end = cube.find("end_header");
    ASSERT_NE(end, std::string::npos);
    const std::string scene = kMat + kLamp + "[[mesh]]\nfile = \"cut.ply\"\nmaterial = \"m\"\n";
    write("cut.ply", cube.substr(0, end - 10));  // cut inside the header
    expect_bad(scene, "file =", {"[[mesh]] #1", "cut.ply", "no 'end_header' line"});
    write("cut.ply", cube.substr(0, end) + "pro" + cube.substr(end));  // "proend_header"
    expect_bad(scene, "file =", {"no 'end_header' line"});
    write("cut.ply", cube);  // the whole file still loads
    EXPECT_EQ(load(scene).triangle_count(), 12u);
}

TEST_F(Loader, AbsurdSubdivisionsAreRefused) {
    const std::string shape = kMat + kLamp + "[[shape]]\nmaterial = \"m\"\nradius = 1\nsize = [1, 1]\n";
    expect_bad(shape + "type = \"disk\"\nsubdivisions = 4096\n", "subdivisions",
               {"key 'subdivisions'", "4096 gives 268402688 triangles", "at most 4194304"});
    expect_bad(shape + "type = \"rectangle\"\nsubdivisions = 2000\n", "subdivisions",
               {"key 'subdivisions'", "8000000 triangles", "split it"});
    expect_bad(shape + "type = \"sphere\"\nsubdivisions = 1100\n", "subdivisions", {"4835600 triangles"});
    expect_bad(kMat + kLamp + "[[shape]]\ntype = \"box\"\nsize = [1, 1, 1]\nmaterial = \"m\"\nsubdivisions = 600\n",
               "subdivisions", {"4320000 triangles"});
    // Past the int range: refused, not wrapped to a small number.
    expect_bad(shape + "type = \"rectangle\"\nsubdivisions = 4294967297\n", "subdivisions", {"must lie in [1, 4096]"});
    // The largest shapes still load (a 1448 x 1448 rectangle is 4,193,408 triangles).
    EXPECT_EQ(load(kMat + kLamp +
                   "[[shape]]\ntype = \"rectangle\"\nsize = [1, 1]\nmaterial = \"m\"\n"
                   "subdivisions = 1448\n")
                  .triangle_count(),
              4193408u);
}

TEST_F(Loader, MaxBouncesPastTheIntRangeIsRefused) {
    expect_bad(kMat + kFloor + kLamp + "[run]\nmax_bounces = 4294967297\n", "max_bounces",
               {"key 'max_bounces'", "must lie in [1, 1000000]"});
}

TEST_F(Loader, VerticesFarAwayAreRefused) {
    expect_bad(kMat + kLamp +
                   "[[shape]]\ntype = \"rectangle\"\ncenter = [1e300, 0, 0]\nsize = [1, 1]\nmaterial = \"m\"\n",
               "", {"[[shape]] #1", "lies outside the +-1000000000 m"});
    write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"far.obj\"\nmaterial = \"m\"\ntransform = { scale = 1e300 }\n", "",
               {"[[mesh]] #1", "lies outside"});
}

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

TEST_F(Loader, DetectorTooSmallToMeasureIsRefused) {
    expect_bad(kMat + kFloor + kLamp + "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1e-200, 1e-200]\n", "",
               {"[[detector]] #1 'd'", "too small"});
    expect_bad(kMat + kFloor + kLamp +
                   "[[detector]]\nname = \"d\"\ntype = \"luminance\"\ncenter = [0, 0, 0]\n"
                   "size = [1, 1]\nhalf_angle_deg = 1e-300\n",
               "", {"[[detector]] #1 'd'", "too narrow"});
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
        EXPECT_GE(l.distribution->sample(a, b).z, std::cos(0.1 * kPi / 180.0) - 1e-12);
    }
}

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

// ---------------------------------------------------------------------------------
// Light groups and light scenes (issue 22).

std::string lamp_in(const std::string& group, double z = 1.0) {
    return "[[light]]\ntype = \"point\"\nposition = [0, 0, " + std::to_string(z) + "]\nflux_lm = 100\n" +
           (group.empty() ? "" : "group = \"" + group + "\"\n");
}

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
