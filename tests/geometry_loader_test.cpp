// Tests of the geometry part of load_scene (src/scene/geometry_loader.cpp: [[material]],
// [[mesh]], [[shape]]): built-in shapes and transformed meshes have the right areas,
// positions and front sides, real meshes load, and bad materials, meshes and shapes are
// InputErrors naming the file, the line (or key) and what is wrong.
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;

// ---------------------------------------------------------------------------------
// The committed scene that uses every key once (tests/data/scenes/every_key.toml).

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

// ---------------------------------------------------------------------------------
// Meshes and shapes written by the test.

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

// ---------------------------------------------------------------------------------
// Bad input.

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

TEST_F(Loader, VerticesFarAwayAreRefused) {
    expect_bad(kMat + kLamp +
                   "[[shape]]\ntype = \"rectangle\"\ncenter = [1e300, 0, 0]\nsize = [1, 1]\nmaterial = \"m\"\n",
               "", {"[[shape]] #1", "lies outside the +-1000000000 m"});
    write("far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_bad(kMat + kLamp + "[[mesh]]\nfile = \"far.obj\"\nmaterial = \"m\"\ntransform = { scale = 1e300 }\n", "",
               {"[[mesh]] #1", "lies outside"});
}

}  // namespace
}  // namespace luxtrace
