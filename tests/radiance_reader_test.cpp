// The Radiance scene reader (issue 25 §1): every primitive against its exact geometry within
// the chord tolerance, the side conventions, xform's transforms, the refusals with file:line,
// and real public Radiance scenes (tests/data/radiance/SOURCES.md).
#include "luxtrace/scene/radiance_reader.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/radiance_shapes.hpp"
#include "luxtrace/scene/radiance_xform.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;
using test_support::ScratchDir;

const fs::path kData = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance";

void write(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
}

Vec3 area_vector(const RadianceModel& m, std::size_t t) {  // twice the triangle's vector area
    const glm::uvec3 k = m.mesh.triangles[t];
    const Vec3 &a = m.mesh.vertices[k.x], &b = m.mesh.vertices[k.y], &c = m.mesh.vertices[k.z];
    return glm::cross(b - a, c - a);
}

double surface_area(const RadianceModel& m, const RadianceSurface& s) {
    double a = 0.0;
    for (std::size_t t = s.first_triangle; t < s.first_triangle + s.triangle_count; ++t)
        a += 0.5 * glm::length(area_vector(m, t));
    return a;
}

double total_area(const RadianceModel& m) {
    double a = 0.0;
    for (const RadianceSurface& s : m.surfaces) a += surface_area(m, s);
    return a;
}

// Reads `text` as scene.rad in a scratch folder; `tag` names the folder.
RadianceModel read_text(const ScratchDir& dir, const std::string& text, const RadianceOptions& options = {}) {
    write(dir.path() / "scene.rad", text);
    return read_radiance(dir.path() / "scene.rad", options);
}

// The InputError's message reading `text`, "" if it was accepted.
std::string error_of(const ScratchDir& dir, const std::string& text) {
    try {
        read_text(dir, text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

const char* kWhite = "void plastic white\n0\n0\n5 .5 .5 .5 0 0\n";

TEST(RadianceShapes, ChordsKeepTheSagittaWithinTheTolerance) {
    for (double tol : {0.1, 0.01, 0.002, 1e-4}) {
        const int n = radiance::circle_segments(tol);
        EXPECT_LE(1.0 - std::cos(kPi / n), tol);
        EXPECT_GT(1.0 - std::cos(kPi / (n - 1)), tol);  // and no more chords than needed
    }
}

TEST(RadianceReader, ConvexPolygonFacesByTheRightHandRule) {
    ScratchDir dir("rad_convex");
    const RadianceModel m = read_text(dir, std::string(kWhite) +
                                               "white polygon up\n0\n0\n12 0 0 0  2 0 0  2 1 0  0 1 0\n"
                                               "white polygon down\n0\n0\n12 0 0 1  0 1 1  2 1 1  2 0 1\n");
    ASSERT_EQ(m.surfaces.size(), 2u);
    for (int s = 0; s < 2; ++s) {
        EXPECT_NEAR(surface_area(m, m.surfaces[s]), 2.0, 1e-12);
        for (std::size_t t = 0; t < m.surfaces[s].triangle_count; ++t)
            EXPECT_GT(area_vector(m, m.surfaces[s].first_triangle + t).z * (s == 0 ? 1.0 : -1.0), 0.0);
    }
    EXPECT_EQ(m.modifiers[m.triangle_modifier[0]].name, "white");
}

TEST(RadianceReader, ConcavePolygonsAndSeamedHolesKeepTheirArea) {
    ScratchDir dir("rad_concave");
    // An L (area 3), a comb with three teeth (area 8), and a 4 x 3 wall with a 2 x 1 window
    // joined to the outline by a seam, as genprism and Radiance's own models write it.
    const RadianceModel m = read_text(
        dir,
        std::string(kWhite) + "white polygon L\n0\n0\n18 0 0 0 2 0 0 2 1 0 1 1 0 1 2 0 0 2 0\n" +
            "white polygon comb\n0\n0\n36 0 0 0 5 0 0 5 2 0 4 2 0 4 1 0 3 1 0 3 2 0 2 2 0 2 1 0 1 1 0 1 2 0 0 2 0\n" +
            "white polygon wall\n0\n0\n30 4 0 0 4 3 0 0 3 0 0 0 0 3 0 0 3 1 0 1 1 0 1 2 0 3 2 0 3 0 0\n");
    ASSERT_EQ(m.surfaces.size(), 3u);
    const double want[] = {3.0, 8.0, 10.0};
    for (int s = 0; s < 3; ++s) {
        EXPECT_NEAR(surface_area(m, m.surfaces[s]), want[s], 1e-12) << m.surfaces[s].name;
        for (std::size_t t = 0; t < m.surfaces[s].triangle_count; ++t)
            EXPECT_GE(area_vector(m, m.surfaces[s].first_triangle + t).z, 0.0) << m.surfaces[s].name;
    }
    EXPECT_TRUE(m.warnings.empty());
}

TEST(RadianceReader, RingIsAnAnnulusFacingItsNormalWithinTheTolerance) {
    ScratchDir dir("rad_ring");
    RadianceOptions o;
    o.chord_tolerance = 0.01;
    const RadianceModel m = read_text(dir,
                                      std::string(kWhite) + "white ring r\n0\n0\n8 1 2 3  0 1 1  0.5 2\n" +
                                          "white ring disc\n0\n0\n8 0 0 0  0 0 -1  1 0\n",
                                      o);
    const double exact = kPi * (4.0 - 0.25);
    const double a = surface_area(m, m.surfaces[0]);
    EXPECT_LE(a, exact);
    EXPECT_GE(a, exact * (1 - o.chord_tolerance) * (1 - o.chord_tolerance));
    const Vec3 n = glm::normalize(Vec3(0, 1, 1));
    for (std::size_t t = 0; t < m.surfaces[0].triangle_count; ++t)
        EXPECT_NEAR(glm::dot(glm::normalize(area_vector(m, t)), n), 1.0, 1e-9);
    EXPECT_GE(surface_area(m, m.surfaces[1]), kPi * (1 - o.chord_tolerance) * (1 - o.chord_tolerance));
    for (std::size_t t = 0; t < m.surfaces[1].triangle_count; ++t)
        EXPECT_LT(area_vector(m, m.surfaces[1].first_triangle + t).z, 0.0);
}

TEST(RadianceReader, SphereLiesWithinTheChordToleranceAndBubbleFacesIn) {
    for (double tol : {0.05, 0.002, 0.0005}) {
        ScratchDir dir("rad_sphere");
        RadianceOptions o;
        o.chord_tolerance = tol;
        const Vec3 c(1, -2, 0.5);
        const double r = 0.7;
        const RadianceModel m =
            read_text(dir,
                      std::string(kWhite) +
                          "white sphere s\n0\n0\n4 1 -2 0.5 0.7\nwhite bubble b\n0\n0\n4 1 -2 0.5 0.7\n",
                      o);
        const double exact = 4 * kPi * r * r;
        for (int s = 0; s < 2; ++s) {
            const RadianceSurface& sf = m.surfaces[s];
            const double a = surface_area(m, sf);
            EXPECT_LE(a, exact);
            EXPECT_GE(a, exact * (1 - tol) * (1 - tol)) << tol;
            for (std::size_t t = sf.first_triangle; t < sf.first_triangle + sf.triangle_count; ++t) {
                const Vec3 n = glm::normalize(area_vector(m, t));
                const Vec3 v = m.mesh.vertices[m.mesh.triangles[t].x];
                EXPECT_NEAR(glm::length(v - c), r, 1e-12);
                const double plane = glm::dot(v - c, n);  // the triangle's plane from the centre
                EXPECT_GE(std::abs(plane), r * (1 - tol)) << tol;
                EXPECT_EQ(plane > 0.0, s == 0);  // sphere out, bubble in
            }
        }
    }
}

TEST(RadianceReader, CylindersAndConesMatchTheirLateralAreaAndFaceTheirSide) {
    ScratchDir dir("rad_cone");
    const double tol = 0.002;
    const RadianceModel m = read_text(dir, std::string(kWhite) + "white cylinder c\n0\n0\n7 0 0 0 0 0 2 0.5\n"
                                                                 "white tube t\n0\n0\n7 0 0 0 0 0 2 0.5\n"
                                                                 "white cone k\n0\n0\n8 0 0 0 3 0 0 1 0.25\n"
                                                                 "white cup u\n0\n0\n8 0 0 0 0 0 -1 0 2\n");
    const double slant_k = std::sqrt(9.0 + 0.75 * 0.75), slant_u = std::sqrt(1.0 + 4.0);
    const double exact[] = {2 * kPi * 0.5 * 2, 2 * kPi * 0.5 * 2, kPi * 1.25 * slant_k, kPi * 2 * slant_u};
    const Vec3 axis_point[] = {Vec3(0.0), Vec3(0.0), Vec3(0.0), Vec3(0.0)};
    for (int s = 0; s < 4; ++s) {
        const RadianceSurface& sf = m.surfaces[s];
        const double a = surface_area(m, sf);
        EXPECT_LE(a, exact[s] * (1 + 1e-12)) << sf.name;
        EXPECT_GE(a, exact[s] * (1 - tol) * (1 - tol)) << sf.name;
        const bool out = sf.type == "cylinder" || sf.type == "cone";
        for (std::size_t t = sf.first_triangle; t < sf.first_triangle + sf.triangle_count; ++t) {
            const glm::uvec3 k = m.mesh.triangles[t];
            const Vec3 centroid = (m.mesh.vertices[k.x] + m.mesh.vertices[k.y] + m.mesh.vertices[k.z]) / 3.0;
            // Away from the axis (the axes are along x or z through the origin).
            const Vec3 radial = s == 2 ? Vec3(0, centroid.y, centroid.z) : Vec3(centroid.x, centroid.y, 0);
            EXPECT_EQ(glm::dot(area_vector(m, t), radial - axis_point[s]) > 0.0, out) << sf.name;
        }
    }
}

TEST(RadianceReader, NegativeRadiiTurnSurfacesInsideOutWithAWarning) {
    ScratchDir dir("rad_negative");
    const RadianceModel m = read_text(dir, std::string(kWhite) + "white sphere s\n0\n0\n4 0 0 0 -1\n" +
                                               "white cylinder c\n0\n0\n7 0 0 0 0 0 1 -1\n");
    EXPECT_EQ(m.surfaces[0].type, "bubble");
    EXPECT_EQ(m.surfaces[1].type, "tube");
    EXPECT_EQ(m.warnings.size(), 2u);
}

TEST(RadianceReader, MaterialsAreKeptAsRecordsAndAnisotropicOnesReadIsotropic) {
    ScratchDir dir("rad_materials");
    const RadianceModel m = read_text(dir, "void metal shiny\n0\n0\n5 .8 .7 .6 .9 .05\n"
                                           "void plastic2 brushed\n4 1 0 0 .\n0\n6 .5 .5 .5 .04 .01 .04\n"
                                           "void glass pane\n0\n0\n4 .9 .9 .9 1.52\n"
                                           "void alias shiny2 shiny\n"
                                           "void texfunc bumps\n2 x y\n0\n0\n"
                                           "bumps plastic bumpy\n0\n0\n5 .2 .2 .2 0 0\n"
                                           "bumpy polygon p\n0\n0\n9 0 0 0 1 0 0 0 1 0\n"
                                           "shiny2 polygon q\n0\n0\n9 0 0 0 1 0 0 0 1 0\n");
    ASSERT_EQ(m.modifiers.size(), 6u);
    EXPECT_EQ(m.modifiers[0].type, "metal");
    EXPECT_EQ(m.modifiers[0].reals, (std::vector<double>{.8, .7, .6, .9, .05}));
    EXPECT_EQ(m.modifiers[1].type, "plastic");
    EXPECT_EQ(m.modifiers[1].read_as, "plastic2");
    ASSERT_EQ(m.modifiers[1].reals.size(), 5u);
    EXPECT_DOUBLE_EQ(m.modifiers[1].reals[4], 0.02);  // sqrt(0.01 * 0.04)
    EXPECT_EQ(m.modifiers[3].name, "shiny2");
    EXPECT_EQ(m.modifiers[3].type, "metal");
    EXPECT_EQ(m.modifiers[3].reals, m.modifiers[0].reals);
    EXPECT_EQ(m.modifiers[m.surfaces[0].modifier].name, "bumpy");
    EXPECT_EQ(m.modifiers[m.surfaces[1].modifier].name, "shiny2");
    EXPECT_EQ(m.warnings.size(), 2u);  // plastic2, texfunc
}

TEST(RadianceReader, DistantSourcesAreKeptWithTheirDirectionAndAngle) {
    ScratchDir dir("rad_source");
    write(dir.path() / "sun.rad", "void light solar\n0\n0\n3 1e6 1e6 1e6\nsolar source sun\n0\n0\n4 0 0 2 0.533\n");
    const RadianceModel m = read_text(dir, "!xform -ry 90 sun.rad\n");
    ASSERT_EQ(m.sources.size(), 1u);
    EXPECT_NEAR(m.sources[0].direction.x, 1.0, 1e-12);  // +z turned 90 degrees about y is +x
    EXPECT_NEAR(glm::length(m.sources[0].direction), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(m.sources[0].angle_deg, 0.533);
    EXPECT_TRUE(m.mesh.triangles.empty());
}

// One right triangle (0,0,0) (1,0,0) (0,1,0) facing +z, in tri.rad.
const char* kTri = "void plastic grey\n0\n0\n5 .2 .2 .2 0 0\ngrey polygon t\n0\n0\n9 0 0 0 1 0 0 0 1 0\n";

TEST(RadianceXform, TransformsApplyInTheOrderWritten) {
    ScratchDir dir("rad_xform_order");
    write(dir.path() / "tri.rad", kTri);
    // Rotate then move: (1,0,0) -> (0,1,0) -> (5,1,0). Move then rotate: (1,0,0) -> (6,0,0) -> (0,6,0).
    const RadianceModel m = read_text(dir, "!xform -rz 90 -t 5 0 0 tri.rad\n!xform -t 5 0 0 -rz 90 tri.rad\n");
    ASSERT_EQ(m.surfaces.size(), 2u);
    const auto v = [&](int s, int i) { return m.mesh.vertices[m.mesh.triangles[m.surfaces[s].first_triangle][i]]; };
    bool found_a = false, found_b = false;
    for (int i = 0; i < 3; ++i) {
        found_a |= glm::length(v(0, i) - Vec3(5, 1, 0)) < 1e-12;
        found_b |= glm::length(v(1, i) - Vec3(0, 6, 0)) < 1e-12;
    }
    EXPECT_TRUE(found_a);
    EXPECT_TRUE(found_b);
}

TEST(RadianceXform, RotationsScaleMirrorAndInvertKeepRadiancesSides) {
    ScratchDir dir("rad_xform_sides");
    write(dir.path() / "tri.rad", kTri);
    const RadianceModel m = read_text(dir,
                                      "!xform -rx 90 tri.rad\n"  // +z -> -y
                                      "!xform -ry 90 tri.rad\n"  // +z -> +x
                                      "!xform -s 3 tri.rad\n"    // area x 9
                                      "!xform -mz tri.rad\n"     // mirrored: faces -z
                                      "!xform -mx tri.rad\n"     // mirror in x: still +z
                                      "!xform -I tri.rad\n");    // turned: -z
    const Vec3 want[] = {Vec3(0, -1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, 0, -1)};
    ASSERT_EQ(m.surfaces.size(), 6u);
    for (int s = 0; s < 6; ++s) {
        const Vec3 n = area_vector(m, m.surfaces[s].first_triangle);
        EXPECT_NEAR(glm::dot(glm::normalize(n), want[s]), 1.0, 1e-12) << s;
    }
    EXPECT_NEAR(surface_area(m, m.surfaces[2]), 4.5, 1e-12);
}

TEST(RadianceXform, ArraysIterationsPrefixesAndNestingCompose) {
    ScratchDir dir("rad_xform_array");
    write(dir.path() / "parts" / "tri.rad", kTri);
    write(dir.path() / "parts" / "row.rad", "!xform -n r -a 3 -t 2 0 0 tri.rad\n");  // relative to parts/
    const RadianceModel m = read_text(dir, "!xform -a 2 -t 0 10 0 -a 3 -t 0 0 1 parts/tri.rad\n"
                                           "!xform -t 0 0 7 -i 2 -t 1 0 0 parts/tri.rad\n"
                                           "!xform -n outer -t 100 0 0 parts/row.rad\n");
    ASSERT_EQ(m.surfaces.size(), 6u + 1u + 3u);
    EXPECT_EQ(m.surfaces[0].name, "a0.0.t");
    EXPECT_EQ(m.surfaces[5].name, "a1.2.t");
    const auto first = [&](int s) { return m.mesh.vertices[m.mesh.triangles[m.surfaces[s].first_triangle].x]; };
    // Copy (1, 2): one step of -t 0 10 0 and two of -t 0 0 1; the first vertex is (0,0,0) moved.
    EXPECT_NEAR(glm::length(first(5) - Vec3(0, 10, 2)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(first(6) - Vec3(2, 0, 7)), 0.0, 1e-12);  // -i 2 repeats the move twice
    EXPECT_EQ(m.surfaces[9].name, "outer.r.2.t");
    EXPECT_NEAR(glm::length(first(9) - Vec3(104, 0, 0)), 0.0, 1e-12);  // inner then outer
}

TEST(RadianceXform, ALongArrayStepsEachCopyOnceFromTheLast) {
    // -a 200000 -rz 0.001: copy k is turned by k / 1000 degrees. Each copy's matrix is one
    // product from the one before (built anew per copy, this array took 2e10 products).
    const radiance::XformCommand x = radiance::parse_xform({"-a", "200000", "-rz", "0.001", "part.rad"}, "t.rad:1");
    ASSERT_EQ(x.copies.size(), 200000u);
    EXPECT_EQ(x.copies.back().name_prefix, "a199999");
    const double a = 199.999 * kPi / 180.0;
    const glm::dvec4 moved = x.copies.back().matrix * glm::dvec4(1, 0, 0, 1);
    EXPECT_NEAR(moved.x, std::cos(a), 1e-9);
    EXPECT_NEAR(moved.y, std::sin(a), 1e-9);
    EXPECT_NEAR(moved.z, 0.0, 1e-15);
}

TEST(RadianceXform, NewModifierReplacesTheSurfacesModifier) {
    ScratchDir dir("rad_xform_m");
    write(dir.path() / "part.rad", "undefined_here polygon t\n0\n0\n9 0 0 0 1 0 0 0 1 0\n");
    const RadianceModel m = read_text(dir, std::string(kWhite) + "!xform -m white part.rad\n");
    ASSERT_EQ(m.surfaces.size(), 1u);
    EXPECT_EQ(m.modifiers[m.surfaces[0].modifier].name, "white");
}

TEST(RadianceReader, ScaleConvertsModelUnitsToMetres) {
    ScratchDir dir("rad_scale");
    RadianceOptions o;
    o.scale = 0.3048;
    const RadianceModel m =
        read_text(dir, std::string(kWhite) + "white polygon f\n0\n0\n12 0 0 0 10 0 0 10 10 0 0 10 0\n", o);
    EXPECT_NEAR(total_area(m), 100 * 0.3048 * 0.3048, 1e-12);
}

TEST(RadianceReader, SkyGeneratorsAreKeptAndDefineTheSkyPattern) {
    ScratchDir dir("rad_sky");
    const RadianceModel m = read_text(dir,
                                      "!gensky 3 21 12 +s -a 37.8 -o 122\n"
                                      "skyfunc glow sky_mat\n0\n0\n4 1 1 1 0\nsky_mat source sky\n0\n0\n4 0 0 1 180\n");
    ASSERT_EQ(m.sky_commands.size(), 1u);
    EXPECT_EQ(m.sky_commands[0].program, "gensky");
    EXPECT_EQ(m.sky_commands[0].arguments,
              (std::vector<std::string>{"3", "21", "12", "+s", "-a", "37.8", "-o", "122"}));
    EXPECT_EQ(m.sky_commands[0].at.line, 1);
    EXPECT_EQ(m.modifiers[m.modifiers[m.sources[0].modifier].modifier].sky_command, 0);
}

// Each bad input is refused with the file, the line and what is wrong.
TEST(RadianceReader, MalformedInputNamesFileLineAndProblem) {
    ScratchDir dir("rad_errors");
    const std::string head = kWhite;  // 4 lines
    const struct {
        std::string text, line, words;
    } cases[] = {
        {head + "white polygon p\n0\n0\n9 0 0 0 1 0 x 0 1 0\n", ":8:", "'x' is not a number"},
        {head + "white polygon p\n0\n0\n8 0 0 0 1 0 0 0 1\n", ":5:", "3 real arguments per vertex"},
        {head + "white sphere s\n0\n1 7\n4 0 0 0 1\n", ":7:", "no integer arguments"},
        {head + "white sphere s\n0\n0\n4 0 0 0\n", ":8:", "ends inside 's'"},
        {head + "\n\nblack sphere s\n0\n0\n4 0 0 0 1\n", ":7:", "modifier 'black' is not defined"},
        {head + "void alias w2 nothing\n", ":5:", "modifier 'nothing' is not defined"},
        {head + "void plastic red\n0\n0\n3 1 0 0\n", ":5:", "takes 5 real arguments, not 3"},
        {head + "void mist fog\n0\n0\n0\n", ":5:", "'mist' is not supported"},
        {head + "void antimatter hole\n1 white\n0\n0\n", ":5:", "'antimatter' is not supported"},
        {head + "void colorpict pic\n5 r g b p.hdr p.cal\n0\n0\n", ":5:", "'colorpict' is not supported"},
        {head + "white mesh m\n1 m.rtm\n0\n0\n", ":5:", "'mesh' is not supported"},
        {head + "white instance i\n1 m.oct\n0\n0\n", ":5:", "'instance' is not supported"},
        {head + "void frobnicate f\n0\n0\n0\n", ":5:", "unknown type 'frobnicate'"},
        {head + "white ring r\n0\n0\n8 0 0 0 0 0 1 1 1\n", ":5:", "radii"},
        {head + "!genbox white box 1 1 1\n", ":5:", "would run a program"},
        {head + "!xform -t 0 0 1 tri.rad | xform -s 2\n", ":5:", "uses the shell"},
        {head + "\n!xform -t 0 0 1 missing.rad\n", ":6:", "'missing.rad' does not exist"},
        {head + "!xform " + std::string(300, 'n') + ".rad\n", ":5:", "does not exist"},  // longer than NAME_MAX
        {head + "!xform -t 0 1 tri.rad\n", ":5:", "-t takes a number"},
        {head + "!xform -q tri.rad\n", ":5:", "'-q' is not read"},
        {head + "!xform -t 0 0 1\n", ":5:", "names no file"},
        {head + "void plastic void\n0\n0\n5 0 0 0 0 0\n", ":5:", "cannot be named 'void'"},
        {head + "white polygon p\n0\n0\n-3 0\n", ":8:", "must be a whole number"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of(dir, c.text);
        EXPECT_NE(e.find("scene.rad" + c.line), std::string::npos) << c.text << "\n-> " << e;
        EXPECT_NE(e.find(c.words), std::string::npos) << c.text << "\n-> " << e;
    }
}

TEST(RadianceReader, AFileIncludingItselfIsRefusedNotFollowedForEver) {
    ScratchDir dir("rad_loop");
    const std::string e = error_of(dir, "!xform -t 0 0 1 scene.rad\n");
    EXPECT_NE(e.find("nested more than 32 deep"), std::string::npos) << e;
}

TEST(RadianceReader, AnErrorInAnIncludedFileNamesThatFile) {
    ScratchDir dir("rad_included_error");
    write(dir.path() / "sub" / "bad.rad", "\n\nvoid plastic p\n0\n0\n2 1 1\n");
    const std::string e = error_of(dir, "!xform sub/bad.rad\n");
    EXPECT_NE(e.find("bad.rad:3:"), std::string::npos) << e;
}

// Real scenes (SOURCES.md). Counts are those of the files; areas come from their geometry.
TEST(RadianceRealScenes, CornellBoxLoads) {
    const RadianceModel m = read_radiance(kData / "cornell.rad");
    EXPECT_EQ(m.modifiers.size(), 6u);
    ASSERT_EQ(m.surfaces.size(), 8u);  // the light, the sphere, six walls
    EXPECT_NEAR(surface_area(m, m.surfaces[0]), 0.04, 1e-12);
    EXPECT_EQ(m.modifiers[m.surfaces[0].modifier].type, "light");
    EXPECT_EQ(m.surfaces[1].type, "sphere");
    double walls = 0.0;
    for (int s = 2; s < 8; ++s) walls += surface_area(m, m.surfaces[s]);
    EXPECT_NEAR(walls, 6.0, 1e-12);
    // genbox -i: the box faces inward, so every wall's normal points to the centre.
    for (int s = 2; s < 8; ++s) {
        const std::size_t t = m.surfaces[s].first_triangle;
        EXPECT_LT(glm::dot(area_vector(m, t), m.mesh.vertices[m.mesh.triangles[t].x]), 0.0) << m.surfaces[s].name;
    }
    EXPECT_TRUE(m.warnings.empty());
}

TEST(RadianceRealScenes, CornerAndDioramaPolygonsTriangulateToTheirArea) {
    const RadianceModel corner = read_radiance(kData / "corner.rad");
    EXPECT_EQ(corner.surfaces.size(), 4u);
    EXPECT_NEAR(total_area(corner), 4.0, 1e-12);
    ScratchDir dir("rad_diorama");
    fs::copy(kData / "basic.mat", dir.path() / "basic.mat");
    fs::copy(kData / "diorama_walls.rad", dir.path() / "diorama_walls.rad");
    const RadianceModel m = read_text(dir, "!xform basic.mat diorama_walls.rad\n");
    EXPECT_EQ(m.modifiers.size(), 4u);
    EXPECT_EQ(m.surfaces.size(), 10u);
    for (const RadianceSurface& s : m.surfaces) {  // the triangles cover each polygon once
        const double a = surface_area(m, s);
        EXPECT_GT(a, 0.0);
        // Sum of the signed triangle areas along the polygon's normal equals the total: no
        // triangle folded over.
        Vec3 sum(0.0);
        for (std::size_t t = s.first_triangle; t < s.first_triangle + s.triangle_count; ++t) sum += area_vector(m, t);
        EXPECT_NEAR(0.5 * glm::length(sum), a, 1e-9 * a) << s.name;
    }
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
}

TEST(RadianceRealScenes, DisksArrayNineXformedSaucersOfConesWithNewModifiers) {
    const RadianceModel m = read_radiance(kData / "disks_scene.rad");
    EXPECT_EQ(m.surfaces.size(), 9u * 55u);
    EXPECT_EQ(m.surfaces.front().name, "disk1.seg.1");
    EXPECT_EQ(m.modifiers[m.surfaces.front().modifier].name, "mat1");
    EXPECT_EQ(m.modifiers[m.surfaces.back().modifier].name, "mat9");
    // Every saucer is the same shape moved: equal areas.
    double first = 0.0;
    for (int d = 0; d < 9; ++d) {
        double a = 0.0;
        for (int s = 0; s < 55; ++s) a += surface_area(m, m.surfaces[d * 55 + s]);
        if (d == 0) first = a;
        EXPECT_NEAR(a, first, 1e-9 * first);
    }
    EXPECT_GT(first, 0.5);  // a saucer 1.3 m across
    EXPECT_LT(first, 2.0 * kPi * 0.9 * 0.9);
}

TEST(RadianceRealScenes, GlowSpheresAndSkyReceiversLoad) {
    const RadianceModel bulbs = read_radiance(kData / "glowbulb.rad");
    EXPECT_EQ(bulbs.surfaces.size(), 2u);
    EXPECT_EQ(bulbs.modifiers[0].type, "glow");
    const RadianceModel sky = read_radiance(kData / "dummysky.rad");
    ASSERT_EQ(sky.sources.size(), 2u);
    EXPECT_DOUBLE_EQ(sky.sources[0].direction.z, -1.0);
    EXPECT_DOUBLE_EQ(sky.sources[1].angle_deg, 180.0);
}

TEST(RadianceRealScenes, GeneratorCommandsInARealModelAreRefusedAtTheirLine) {
    try {
        read_radiance(kData / "plainoff.rad");
        FAIL() << "plainoff.rad runs genprism";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("plainoff.rad:117: the command '!genprism"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace luxtrace
