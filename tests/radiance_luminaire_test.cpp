// ies2rad's luminaires read back (issue 25 §1): on real ies2rad outputs from Radiance's own
// repository (tests/data/radiance/SOURCES.md) the intensities are the .dat's values times
// 179, the light's colour, the multiplier and the emitter's area, turned into the scene by
// the pattern's transform; on a real IES file written out in ies2rad's layout the luminaire
// read back is the IES file's, in flux, in distribution and in orientation.
#include "luxtrace/scene/radiance_luminaire.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/ies.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;
using test_support::ScratchDir;

const fs::path kData = fs::path(LUXTRACE_TEST_DATA_DIR);
constexpr double kDeg = kPi / 180.0;

void write(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
}

// The numbers of a Radiance data file, comments skipped (a second, plain reading).
std::vector<double> numbers_of(const fs::path& p) {
    std::ifstream in(p);
    std::vector<double> v;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line.substr(0, line.find('#')));
        double x = 0.0;
        while (s >> x) v.push_back(x);
    }
    return v;
}

std::string expect_input_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

// Scene direction of (C, gamma) in a luminaire frame.
Vec3 scene_direction(const Frame& f, double c_deg, double g_deg) {
    return f.to_world(photometric_direction(PhotometricType::C, c_deg, g_deg));
}

TEST(RadianceLuminaire, ModifiersKeepTheXformInForceWhereTheyAreDefined) {
    ScratchDir dir("radlum_xform");
    write(dir.path() / "top.rad", "void plastic p\n0\n0\n5 .5 .5 .5 0 0\n!xform -rz 90 -t 1 2 3 inner.rad\n");
    write(dir.path() / "inner.rad", "void plastic q\n0\n0\n5 .5 .5 .5 0 0\n");
    const RadianceModel m = read_radiance(dir.path() / "top.rad");
    ASSERT_EQ(m.modifiers.size(), 2u);
    EXPECT_EQ(m.modifiers[0].transform, glm::dmat4(1.0));
    const glm::dmat4& t = m.modifiers[1].transform;
    const Vec3 x(t * glm::dvec4(1, 0, 0, 1));  // the point (1, 0, 0): turned to (0, 1, 0), then moved
    EXPECT_NEAR(glm::length(x - Vec3(1, 3, 3)), 0.0, 1e-12);
}

// Radiance's test/renders/rect_fixture: a Wellmade 2-lamp fixture (ies2rad, flatcorr over
// src_phi4 src_theta), its brightness scaled to 20 and the pattern given `-s 0.0254 -rz 90
// -t -4 2.5 2.999` to follow the polygon, which xform moved there.
TEST(RadianceLuminaireReal, RectFixtureIsTheDatTurnedByItsTransform) {
    const RadianceModel m = read_radiance(kData / "radiance" / "rect_fixture.rad");
    const std::vector<std::size_t> lums = radiance_luminaire_modifiers(m);
    ASSERT_EQ(lums.size(), 1u);
    const RadianceLuminaire l = radiance_luminaire(m, lums[0]);
    EXPECT_EQ(l.name, "lum_dist");
    EXPECT_EQ(l.surfaces.size(), 1u);
    EXPECT_NEAR(glm::length(l.position_m - Vec3(-4.0, 2.5, 2.999)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(l.frame.n - Vec3(0, 0, -1)), 0.0, 1e-12);  // nadir down
    EXPECT_NEAR(glm::length(l.frame.t - Vec3(0, 1, 0)), 0.0, 1e-12);   // C0 turned by -rz 90
    EXPECT_NEAR(glm::length(l.frame.b - Vec3(-1, 0, 0)), 0.0, 1e-12);

    // The .dat: 2 dimensions, C 0..90 (3), gamma 0..90 (11), then C-major values.
    const std::vector<double> dat = numbers_of(kData / "radiance" / "rect_fixture.dat");
    ASSERT_EQ(dat.size(), 1u + 6u + 33u);
    const double area = (4.57784968833 - 3.42215031167) * (2.77304985272 - 2.22695014727);  // the polygon
    const double k = 179.0 * 20.0 * area;  // 179 lm/W x the light's grey 20 x the flat emitter's area
    const Photometry& p = l.photometry;
    ASSERT_EQ(p.horizontal_deg, (std::vector<double>{0, 45, 90}));
    ASSERT_EQ(p.vertical_deg.size(), 11u);
    for (std::size_t h = 0; h < 3; ++h)
        for (std::size_t v = 0; v < 11; ++v) EXPECT_NEAR(p.candela_cd[h][v], k * dat[7 + 11 * h + v], 1e-9 * k);
    // In the scene: the C0 plane runs along +y, C90 along x (both signs: src_phi4).
    for (const std::size_t i : {2, 4, 6}) {  // gamma 18, 36, 54
        const double g = 9.0 * static_cast<double>(i);
        const double c0 = k * dat[7 + i], c90 = k * dat[7 + 22 + i];
        for (const Vec3& d :
             {Vec3(0, std::sin(g * kDeg), -std::cos(g * kDeg)), Vec3(0, -std::sin(g * kDeg), -std::cos(g * kDeg))})
            EXPECT_NEAR(p.intensity_cd(l.frame.to_local(d)), c0, 1e-9 * k);
        for (const Vec3& d :
             {Vec3(std::sin(g * kDeg), 0, -std::cos(g * kDeg)), Vec3(-std::sin(g * kDeg), 0, -std::cos(g * kDeg))})
            EXPECT_NEAR(p.intensity_cd(l.frame.to_local(d)), c90, 1e-9 * k);
    }
    // Its flux is the .dat's own integral: the table the test read, as a photometry.
    Photometry raw;
    raw.vertical_deg = p.vertical_deg;
    raw.horizontal_deg = p.horizontal_deg;
    raw.candela_cd.assign(3, {});
    for (std::size_t h = 0; h < 3; ++h) raw.candela_cd[h].assign(dat.begin() + 7 + 11 * h, dat.begin() + 18 + 11 * h);
    EXPECT_NEAR(p.flux_lm(), k * raw.flux_lm(), 1e-9 * p.flux_lm());
    EXPECT_EQ(p.opening.shape, LuminousOpening::Shape::rectangle);
    EXPECT_NEAR(p.opening.length_m, 2.77304985272 - 2.22695014727, 1e-9);  // along C0 (scene y)
    EXPECT_NEAR(p.opening.width_m, 4.57784968833 - 3.42215031167, 1e-9);
}

// Radiance's lib/source/zumtobel/SID-C2: an up-and-down light in inches, an illum of grey
// 2.95 = 1 / (its face's area in m^2) over a .dat of candelas (multiplier .0055866 = 1/179)
// with gamma first and C (90 down to 0) second: read back, the candelas come out as written.
TEST(RadianceLuminaireReal, ZumtobelUpDownLightGivesItsCandelasBack) {
    RadianceOptions o;
    o.scale = 0.0254;
    const fs::path lib = kData / "radiance" / "lib";
    const RadianceModel m = read_radiance(lib / "source" / "zumtobel" / "SID-C2.rad", o);
    const std::vector<std::size_t> lums = radiance_luminaire_modifiers(m);
    ASSERT_EQ(lums.size(), 1u);
    EXPECT_THROW(radiance_luminaire(m, lums[0]), InputError);  // "source/zumtobel/SID-C2.dat" is a library path
    const RadianceLuminaire l = radiance_luminaire(m, lums[0], {{lib}});
    EXPECT_EQ(l.surfaces.size(), 2u);  // the upper and the lower face
    EXPECT_NEAR(glm::length(l.position_m - Vec3(0, 0, -24.0 * 0.0254)), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(l.frame.t - Vec3(1, 0, 0)), 0.0, 1e-12);
    const double face_m2 = 10.625 * 49.4375 * 0.0254 * 0.0254;
    const double k = 179.0 * 2.95 * 0.0055866 * face_m2;  // within 0.1 % of 1
    EXPECT_NEAR(k, 1.0, 1e-3);
    const std::vector<double> dat = numbers_of(lib / "source" / "zumtobel" / "SID-C2.dat");
    ASSERT_EQ(dat.size(), 1u + 6u + 37u * 5u);
    const Photometry& p = l.photometry;
    ASSERT_EQ(p.horizontal_deg, (std::vector<double>{0, 22.5, 45, 67.5, 90}));
    ASSERT_EQ(p.vertical_deg.size(), 37u);
    for (std::size_t v = 0; v < 37; ++v)
        for (std::size_t h = 0; h < 5; ++h)  // the file's C runs 90, 67.5, ... 0
            EXPECT_NEAR(p.candela_cd[h][v], k * dat[7 + 5 * v + (4 - h)], 1e-9 * dat[7]) << v << " " << h;
    // At gamma 5: 896 cd toward C0 (scene x), 873 toward C90 (y). (At 90 degrees, where
    // both faces are edge-on, the two sides' limits are averaged: the faces' equal areas.)
    EXPECT_NEAR(p.intensity_cd(l.frame.to_local(scene_direction(l.frame, 0, 5))), 896 * k, 1e-9);
    EXPECT_NEAR(p.intensity_cd(l.frame.to_local(Vec3(0, std::sin(5 * kDeg), -std::cos(5 * kDeg)))), 873 * k, 1e-9);
    EXPECT_NEAR(p.candela_cd[0][0], 881 * k, 1e-9);
    EXPECT_GT(p.candela_cd[0][36], 0.0);  // the upper face lights the ceiling
}

// A real IES file (tests/data/real/ASA_15M_R2.ies) written out as ies2rad writes it: the
// .dat of cd / 179 ("%g"), a flatcorr brightdata of multiplier / area, a white light and
// the lower face; or the box with boxcorr. Placed by an xform, it reads back as the IES
// file's photometry, in the scene direction the xform turned it to.
std::string write_ies2rad(const Photometry& ies, const fs::path& dir, bool box) {
    std::ostringstream dat;
    dat << "2\n0 0 " << ies.horizontal_deg.size();
    for (std::size_t j = 0; j < ies.horizontal_deg.size(); ++j)
        dat << (j % 4 == 0 ? "\n" : "") << "\t" << ies.horizontal_deg[j];
    dat << "\n0 0 " << ies.vertical_deg.size();
    for (std::size_t j = 0; j < ies.vertical_deg.size(); ++j)
        dat << (j % 4 == 0 ? "\n" : "") << "\t" << ies.vertical_deg[j];
    dat << "\n";
    int n = 0;
    char buf[64];
    for (const auto& plane : ies.candela_cd)
        for (const double cd : plane) {
            std::snprintf(buf, sizeof buf, "\t%g", cd / 179.0);
            dat << (n++ % 4 == 0 ? "\n" : "") << buf;
        }
    write(dir / "asa.dat", dat.str() + "\n");
    const double l = ies.opening.length_m, w = ies.opening.width_m, h = box ? 0.1 : 0.0;
    std::ostringstream rad;
    rad << "# written by the test in ies2rad's layout\n\nvoid brightdata asa_dist\n";
    if (box) rad << "5 boxcorr asa.dat source.cal src_phi2 src_theta\n0\n4 1 " << l << " " << w << " " << h << "\n";
    else rad << "5 flatcorr asa.dat source.cal src_phi2 src_theta\n0\n1 " << 1.0 / (l * w) << "\n";
    rad << "\nasa_dist light asa_light\n0\n0\n3 1 1 1\n";
    auto rect = [&](const char* name, std::array<int, 4> idx) {
        rad << "\nasa_light polygon " << name << "\n0\n0\n12\n";
        for (const int q : idx)
            rad << "\t" << ((q & 1) ? .5 : -.5) * l << "\t" << ((q >> 1 & 1) ? .5 : -.5) * w << "\t"
                << ((q >> 2) ? .5 : -.5) * h << "\n";
    };
    rect("asa.d", {0, 2, 3, 1});
    if (box) {
        rect("asa.u", {4, 5, 7, 6});
        rect("asa.1", {0, 1, 5, 4});
        rect("asa.2", {1, 3, 7, 5});
        rect("asa.3", {3, 2, 6, 7});
        rect("asa.4", {2, 0, 4, 6});
    }
    write(dir / "asa.rad", rad.str());
    write(dir / "scene.rad", "!xform -rz 30 -t 1 2 3 asa.rad\n");
    return (dir / "scene.rad").string();
}

TEST(RadianceLuminaire, RealIesFileWrittenAsIes2radReadsBackAsTheIesFile) {
    const Photometry ies = load_ies(kData / "real" / "ASA_15M_R2.ies");
    ASSERT_EQ(ies.opening.shape, LuminousOpening::Shape::rectangle);
    for (const bool box : {false, true}) {
        SCOPED_TRACE(box ? "boxcorr" : "flatcorr");
        ScratchDir dir(box ? "radlum_box" : "radlum_flat");
        const RadianceModel m = read_radiance(write_ies2rad(ies, dir.path(), box));
        const std::vector<std::size_t> lums = radiance_luminaire_modifiers(m);
        ASSERT_EQ(lums.size(), 1u);
        const RadianceLuminaire l = radiance_luminaire(m, lums[0]);
        EXPECT_NEAR(glm::length(l.position_m - Vec3(1, 2, 3)), 0.0, 1e-9);
        EXPECT_NEAR(glm::length(l.frame.t - Vec3(std::cos(30 * kDeg), std::sin(30 * kDeg), 0)), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(l.frame.n - Vec3(0, 0, -1)), 0.0, 1e-12);
        // The flux and the intensity toward every direction within %g's 6 digits (a box's
        // sides triangulated exactly: its projected area is the boxcorr's).
        EXPECT_NEAR(l.photometry.flux_lm(), ies.flux_lm(), 2e-5 * ies.flux_lm());
        const double peak = *std::max_element(ies.candela_cd[0].begin(), ies.candela_cd[0].end());
        for (double c = 0.0; c < 360.0; c += 17.0)
            for (double g = 1.0; g < 90.0; g += 7.0) {
                const Vec3 d = scene_direction(l.frame, c, g);
                const Vec3 in_ies = photometric_direction(PhotometricType::C, c, g);  // the IES file's frame
                EXPECT_NEAR(l.photometry.intensity_cd(l.frame.to_local(d)), ies.intensity_cd(in_ies), 1e-5 * peak);
            }
        EXPECT_EQ(l.photometry.opening.shape, box ? LuminousOpening::Shape::box : LuminousOpening::Shape::rectangle);
        // The scene naming the IES file instead: its photometry, at the same place.
        const RadianceLuminaire named = radiance_luminaire_named(m, lums[0], ies);
        EXPECT_EQ(named.photometry.candela_cd, ies.candela_cd);
        EXPECT_EQ(named.position_m, l.position_m);
        EXPECT_EQ(named.frame.t, l.frame.t);
    }
}

TEST(RadianceLuminaire, ErrorsNameTheFileTheLineAndWhatIsWrong) {
    ScratchDir dir("radlum_errors");
    const std::string light = "\nd light l\n0\n0\n3 1 1 1\nl polygon p\n0\n0\n12 0 0 0 0 1 0 1 1 0 1 0 0\n";
    auto first_luminaire = [&](const std::string& rad, const std::string& dat) {
        write(dir.path() / "l.rad", rad + light);
        if (!dat.empty()) write(dir.path() / "l.dat", dat);
        const RadianceModel m = read_radiance(dir.path() / "l.rad");
        return radiance_luminaire(m, 0);
    };
    const std::string good = "void brightdata d\n4 flatcorr l.dat source.cal src_theta\n0\n0\n";
    std::string e = expect_input_error(
        [&] { first_luminaire("void brightdata d\n4 flatcorr gone.dat source.cal src_theta\n0\n0\n", ""); });
    EXPECT_NE(e.find("l.rad:1"), std::string::npos) << e;
    EXPECT_NE(e.find("'gone.dat' not found"), std::string::npos) << e;
    e = expect_input_error([&] { first_luminaire(good, "1\n0 90 3\n1 2 x\n"); });
    EXPECT_NE(e.find("l.dat:3"), std::string::npos) << e;
    EXPECT_NE(e.find("'x' is not a number"), std::string::npos) << e;
    e = expect_input_error([&] { first_luminaire(good, "1\n0 90 3\n1 2\n"); });
    EXPECT_NE(e.find("l.dat:3: the file ends"), std::string::npos) << e;
    e = expect_input_error([&] { first_luminaire(good, "1\n0 90 3\n1 2 3 4\n"); });
    EXPECT_NE(e.find("more values"), std::string::npos) << e;
    e = expect_input_error([&] { first_luminaire(good, "3\n"); });
    EXPECT_NE(e.find("l.dat:1: the number of dimensions"), std::string::npos) << e;
    e = expect_input_error([&] { first_luminaire(good, "2\n0 90 2\n0 90 2\n1 1 1 1\n"); });
    EXPECT_NE(e.find("2 dimensions for the 1 coordinates"), std::string::npos) << e;
    e = expect_input_error(
        [&] { first_luminaire("void brightdata d\n4 mycorr l.dat source.cal src_theta\n0\n0\n", "1\n0 90 2\n1 1\n"); });
    EXPECT_NE(e.find("l.rad:1: brightdata 'd': function 'mycorr' is not one of ies2rad's"), std::string::npos) << e;
    e = expect_input_error([&] {
        first_luminaire("void brightdata d\n5 flatcorr l.dat source.cal srcB_horiz srcB_vert\n0\n0\n",
                        "1\n0 90 2\n1 1\n");
    });
    EXPECT_NE(e.find("type B"), std::string::npos) << e;
    e = expect_input_error(
        [&] { first_luminaire("void brightdata d\n4 flatcorr l.dat my.cal src_theta\n0\n0\n", "1\n0 90 2\n1 1\n"); });
    EXPECT_NE(e.find("'my.cal' is not source.cal"), std::string::npos) << e;
    e = expect_input_error([&] {
        first_luminaire("void brightdata d\n4 boxcorr l.dat source.cal src_theta\n0\n1 1\n", "1\n0 90 2\n1 1\n");
    });
    EXPECT_NE(e.find("boxcorr takes 4 real arguments"), std::string::npos) << e;
    // A brightdata that lights nothing.
    write(dir.path() / "n.rad", good);
    const RadianceModel m = read_radiance(dir.path() / "n.rad");
    e = expect_input_error([&] { radiance_luminaire(m, 0); });
    EXPECT_NE(e.find("n.rad:1: brightdata 'd' lights no surface"), std::string::npos) << e;
}

}  // namespace
}  // namespace luxtrace
