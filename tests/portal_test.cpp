// Portals (light/portal.hpp, src/scene/portal_loader.cpp; docs/DAYLIGHT.md "Portals"):
//  - a portal's flux is the sky's illuminance on the opening's plane times its area
//    (vertical: the quadrature of sky_model.hpp; horizontal: E_dh; ground glow: half or
//    all of pi L_g), and the sun's is E_n A cos(theta_sun);
//  - the sky's E_h,ext is counted once however many portals split it;
//  - bad [[portal]] input is an InputError naming the file, line and key (exit 2);
//  - end to end, the same room with and without portals gives the same interior detector
//    values within the runs' errors: open sky (CIE 16), an exterior black obstruction
//    (CIE 12 with its sun), and the sun with its ground glow.
#include "luxtrace/light/portal.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/light/sky_model.hpp"

#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

namespace luxtrace {
namespace {

using namespace test_support;

double deg(double d) { return d * kPi / 180.0; }

const Frame kHorizon{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};

// The illuminance on a plane of outward normal `n` by a midpoint rule on a fine grid of
// the plane's own hemisphere (an independent check for tilted planes).
double midpoint_illuminance(const SkyLuminance& lum, const Vec3& n) {
    const Frame f = Frame::around(n);
    const int nz = 900, na = 1800;
    double sum = 0.0;
    for (int i = 0; i < nz; ++i) {
        const double mu0 = 1.0 - double(i) / nz, mu1 = 1.0 - double(i + 1) / nz, mu = 0.5 * (mu0 + mu1);
        const double s = std::sqrt(1.0 - mu * mu);
        for (int j = 0; j < na; ++j) {
            const double a = (j + 0.5) * 2.0 * kPi / na;
            sum += lum(f.to_world(Vec3(s * std::cos(a), s * std::sin(a), mu))) * mu;
        }
    }
    return sum * (1.0 / nz) * (2.0 * kPi / na);
}

TEST(PortalSky, FluxIsTheSkysIlluminanceOnTheOpeningsPlane) {
    for (const SkyModel& sky : {SkyModel::cie(16, 0.0, 0.0), SkyModel::cie(12, deg(50.0), deg(200.0)),
                                SkyModel::cie(3, deg(30.0), deg(100.0))}) {
        const double lz = 3000.0;
        const SkyLuminance lum{sky, lz, 0.0};
        // Horizontal (roof) opening: E_dh.
        const Vec3 up(0, 0, 1);
        const PortalSky roof(lum, kHorizon, Portal::frame_for(up, kHorizon));
        EXPECT_NEAR(roof.illuminance_lx(), lz * sky.horizontal_illuminance_per_zenith_luminance_sr(),
                    1e-7 * roof.illuminance_lx());
        // Facades facing the four points of the compass and one in between.
        for (const double facing : {0.0, 90.0, 180.0, 235.0, 270.0}) {
            const Vec3 out(std::sin(deg(facing)), std::cos(deg(facing)), 0.0);
            const PortalSky facade(lum, kHorizon, Portal::frame_for(out, kHorizon));
            EXPECT_NEAR(facade.illuminance_lx(), lz * sky.vertical_illuminance_per_zenith_luminance_sr(deg(facing)),
                        1e-7 * facade.illuminance_lx())
                << "type " << sky.cie_type() << ", facing " << facing;
        }
    }
}

TEST(PortalSky, TiltedOpeningsAndGroundGlow) {
    // A plane tilted 45 degrees sees sky and ground: against a fine midpoint rule.
    const SkyLuminance lum{SkyModel::cie(12, deg(40.0), deg(180.0)), 2000.0, 800.0};
    for (const Vec3& n : {glm::normalize(Vec3(0, -1, 1)), glm::normalize(Vec3(1, 0.3, -0.5))}) {
        const PortalSky tilted(lum, kHorizon, Portal::frame_for(n, kHorizon));
        EXPECT_NEAR(tilted.illuminance_lx(), midpoint_illuminance(lum, n), 2e-5 * tilted.illuminance_lx());
    }
    // Ground glow alone: a facade sees half the ground, pi L_g / 2; a floor opening all of it.
    const SkyLuminance ground{std::nullopt, 0.0, 1000.0};
    EXPECT_NEAR(PortalSky(ground, kHorizon, Portal::frame_for(Vec3(1, 0, 0), kHorizon)).illuminance_lx(),
                1000.0 * kPi / 2.0, 1e-9 * 1000.0);
    EXPECT_NEAR(PortalSky(ground, kHorizon, Portal::frame_for(Vec3(0, 0, -1), kHorizon)).illuminance_lx(), 1000.0 * kPi,
                1e-9 * 1000.0);
    EXPECT_EQ(PortalSky(ground, kHorizon, Portal::frame_for(Vec3(0, 0, 1), kHorizon)).illuminance_lx(), 0.0);
}

TEST(PortalSky, DirectionsLeaveThroughTheOpeningWithDensityLCos) {
    // The mean of w.n over the sampled directions is (integral of L cos^2) / (integral of
    // L cos): for the uniform sky on a roof opening, (2 pi / 3) / pi = 2 / 3.
    const PortalSky roof(SkyLuminance{SkyModel::uniform(), 1.0, 0.0}, kHorizon,
                         Portal::frame_for(Vec3(0, 0, 1), kHorizon));
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < n; ++k) {
        const Vec3 w = roof.sample((k + 0.5) / n, std::fmod(k * 0.6180339887498949, 1.0));
        ASSERT_GE(w.z, 0.0);
        sum += w.z;
        sum2 += w.z * w.z;
    }
    const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 2.0 / 3.0, 5.0 * sigma);
}

const std::string kWindowRoom =
    "[[material]]\nname = \"m\"\nreflectance = 0.5\n"
    "[[material]]\nname = \"open\"\ntype = \"glass\"\nior = 1\n"
    "[[shape]]\ntype = \"rectangle\"\nsize = [4, 4]\nmaterial = \"m\"\n"
    "[[shape]]\nname = \"window\"\ntype = \"rectangle\"\ncenter = [0, -2, 1]\nnormal = [0, 1, 0]\nup = [0, 0, 1]\n"
    "size = [2, 1]\nmaterial = \"open\"\n";
const std::string kOvercast =
    "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = 10000\nground_reflectance = "
    "0.2\n";
const std::string kSunSouth =
    "[[light]]\ntype = \"sun\"\ndirect_normal_lx = 60000\nsun_altitude_deg = 30\nsun_azimuth_deg = 160\n";

TEST_F(Loader, PortalsSplitEverySunAndSkyLightAndKeepTheSkysEhOnce) {
    const std::string roof = "[[shape]]\nname = \"roof\"\ntype = \"rectangle\"\ncenter = [0, 0, 2]\nnormal = [0, 0, "
                             "-1]\nsize = [1, 1]\nmaterial = \"open\"\n";
    const Scene plain = load(kWindowRoom + roof + kOvercast + kSunSouth + kLamp);
    const Scene s = load(kWindowRoom + roof + kOvercast + kSunSouth + kLamp +
                         "[[portal]]\nshape = \"window\"\n[[portal]]\nshape = \"roof\"\n");
    double eh_plain = 0.0, eh = 0.0;
    for (const Light& l : plain.lights.lights()) eh_plain += l.unobstructed_horizontal_lx;
    for (const Light& l : s.lights.lights()) eh += l.unobstructed_horizontal_lx;
    EXPECT_EQ(eh, eh_plain);
    // sky, its 2 portals; sun, 2; ground glow, 2; the lamp untouched.
    ASSERT_EQ(s.lights.lights().size(), 7u);
    const double lz = 10000.0 / (7.0 * kPi / 9.0), rho_eh_sky = 0.2 * 10000.0, en = 60000.0;
    const double sun_eh = en * std::sin(deg(30.0));
    for (const Light& l : s.lights.lights()) {
        if (l.is<PointLight>()) continue;  // the lamp: no portal
        const PortalLight* through = l.as<PortalLight>();
        ASSERT_NE(through, nullptr) << l.label;
        const Portal& portal = *through->portal;
        const bool window = portal.name == "window";
        const double area = window ? 2.0 : 1.0;
        EXPECT_NEAR(portal.surface.area_m2, area, 1e-12);
        // The window faces south (outward -y), the roof opening up.
        expect_vec(portal.outward, window ? Vec3(0, -1, 0) : Vec3(0, 0, 1), 1e-12);
        double e = 0.0;  // the plane's illuminance from this light
        const SkyLight* sky = std::get_if<SkyLight>(&through->source);
        if (std::holds_alternative<SunLight>(through->source)) {
            const Vec3 to_sun(std::cos(deg(30.0)) * std::sin(deg(160.0)), std::cos(deg(30.0)) * std::cos(deg(160.0)),
                              std::sin(deg(30.0)));
            e = en * std::max(0.0, glm::dot(to_sun, portal.outward));
        } else if (sky->description.rfind("ground glow", 0) == 0) {
            e = window ? 0.2 * sun_eh / 2.0 : 0.0;  // half the ground; a roof sees none
        } else {
            e = window ? lz * (kPi / 6.0 + 4.0 / 9.0) + rho_eh_sky / 2.0 : 10000.0;
        }
        EXPECT_NEAR(l.flux_lm, e * area, 1e-6 * std::max(1.0, e * area)) << l.label;
    }
}

TEST_F(Loader, PortalFlipTurnsTheOpeningRound) {
    const Scene s = load(kWindowRoom + kOvercast + "[[portal]]\nshape = \"window\"\nflip = true\n");
    expect_vec(s.lights.lights().at(0).as<PortalLight>()->portal->outward, Vec3(0, 1, 0), 1e-12);
}

TEST_F(Loader, BadPortalsNameFileLineAndKey) {
    const std::string base = kWindowRoom + kOvercast;
    expect_bad(base + "[[portal]]\nshape = \"door\"\n", "shape = \"door\"", {"key 'shape'", "'door'"});
    expect_bad(base + "[[portal]]\nflip = true\n", "", {"[[portal]]", "needs 'shape'"});
    expect_bad(base + "[[portal]]\nshape = \"window\"\n[[portal]]\nshape  = \"window\"\n", "shape  = \"window\"",
               {"already a portal"});
    expect_bad(base + "[[portal]]\nshape = \"window\"\nopen = true\n", "open = true", {"open"});
    expect_bad(base + "[[shape]]\nname = \"crate\"\ntype = \"box\"\nsize = [1, 1, 1]\nmaterial = \"m\"\n"
                      "[[portal]]\nshape = \"crate\"\n",
               "shape = \"crate\"", {"key 'shape'", "not planar"});
    expect_bad(kWindowRoom + kLamp + "[[portal]]\nshape = \"window\"\n", "", {"[[portal]]", "'sun' or 'sky'"});
}

// ---- end to end -------------------------------------------------------------------

// A closed room 4 m x 4 m x 3 m (z from 0) with one 2 m x 1.2 m open window in its
// south wall (y = -2), a desk-height detector; `outside` adds exterior geometry.
std::string room(const std::string& lights, const std::string& outside, bool portal) {
    std::string s = "[[material]]\nname = \"wall\"\nreflectance = 0.5\n"
                    "[[material]]\nname = \"open\"\ntype = \"glass\"\nior = 1\n"
                    "[[material]]\nname = \"black\"\ntype = \"black\"\n";
    auto rect = [&](const std::string& c, const std::string& n, const std::string& up, const std::string& size,
                    const std::string& mat, const std::string& name = "") {
        s += "[[shape]]\n" + (name.empty() ? "" : "name = \"" + name + "\"\n") + "type = \"rectangle\"\ncenter = " + c +
             "\nnormal = " + n + "\nup = " + up + "\nsize = " + size + "\nmaterial = \"" + mat + "\"\n";
    };
    rect("[0, 0, 0]", "[0, 0, 1]", "[0, 1, 0]", "[4, 4]", "wall");
    rect("[0, 0, 3]", "[0, 0, -1]", "[0, 1, 0]", "[4, 4]", "wall");
    rect("[-2, 0, 1.5]", "[1, 0, 0]", "[0, 0, 1]", "[4, 3]", "wall");
    rect("[2, 0, 1.5]", "[-1, 0, 0]", "[0, 0, 1]", "[4, 3]", "wall");
    rect("[0, 2, 1.5]", "[0, -1, 0]", "[0, 0, 1]", "[4, 3]", "wall");
    rect("[0, -2, 0.5]", "[0, 1, 0]", "[0, 0, 1]", "[4, 1]", "wall");    // below the sill
    rect("[0, -2, 2.6]", "[0, 1, 0]", "[0, 0, 1]", "[4, 0.8]", "wall");  // above the head
    rect("[-1.5, -2, 1.6]", "[0, 1, 0]", "[0, 0, 1]", "[1, 1.2]", "wall");
    rect("[1.5, -2, 1.6]", "[0, 1, 0]", "[0, 0, 1]", "[1, 1.2]", "wall");
    rect("[0, -2, 1.6]", "[0, 1, 0]", "[0, 0, 1]", "[2, 1.2]", "open", "window");
    s += outside + lights;
    s += "[[detector]]\nname = \"desk\"\ntype = \"illuminance\"\ncenter = [0, 0, 0.8]\nnormal = [0, 0, 1]\n"
         "up = [0, 1, 0]\nsize = [3.6, 3.6]\ncells = [3, 3]\n";
    if (portal) s += "[[portal]]\nshape = \"window\"\n";
    return s;
}

struct Cells {
    std::vector<double> value, sigma;
};

Cells run_room(const ScratchDir& dir, const std::string& name, const std::string& text, long photons) {
    const fs::path scene = dir.path() / (name + ".toml"), out = dir.path() / (name + ".h5");
    std::ofstream(scene) << text;
    const auto o = run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                "\" --quiet --threads 2 --photons " + std::to_string(photons));
    EXPECT_EQ(o.code, 0) << o.out;
    const ResultReader r(out);
    Cells c{r.f64("/detectors/desk/value"), r.f64("/detectors/desk/sigma_rel")};
    for (std::size_t i = 0; i < c.value.size(); ++i) c.sigma[i] *= c.value[i];
    return c;
}

TEST(PortalRun, TheSameRoomReadsTheSameWithAndWithoutPortals) {
    ScratchDir dir("portal_run");
    // A black wall 3 m in front of the window, 2 m high: it hides the lower sky.
    const std::string wall = "[[shape]]\ntype = \"rectangle\"\ncenter = [0, -5, 1]\nnormal = [0, 1, 0]\n"
                             "up = [0, 0, 1]\nsize = [10, 2]\nmaterial = \"black\"\n";
    struct Case {
        std::string name, lights, outside;
    };
    const std::vector<Case>
        cases{{"overcast", kOvercast, ""},
              {"clear_obstructed",
               "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 12\nsun_altitude_deg = 35\nsun_azimuth_deg = 200\n"
               "diffuse_horizontal_lx = 12000\n",
               wall},
              {"sun", kSunSouth + "ground_reflectance = 0.2\n", ""}};
    double sum_z2 = 0.0;
    int count = 0;
    for (const Case& c : cases) {
        const Cells plain = run_room(dir, c.name, room(c.lights, c.outside, false), 4000000);
        const Cells portal = run_room(dir, c.name + "_portal", room(c.lights, c.outside, true), 500000);
        ASSERT_EQ(plain.value.size(), portal.value.size());
        for (std::size_t i = 0; i < plain.value.size(); ++i) {
            const double sigma = std::hypot(plain.sigma[i], portal.sigma[i]);
            if (!(sigma > 0.0)) {  // a cell no light reaches in either run (the sun patch's shade)
                EXPECT_EQ(plain.value[i], portal.value[i]) << c.name << " cell " << i;
                continue;
            }
            const double z = (portal.value[i] - plain.value[i]) / sigma;
            EXPECT_LT(std::abs(z), 5.0) << c.name << " cell " << i << ": " << portal.value[i] << " +- "
                                        << portal.sigma[i] << " lx through the portal, " << plain.value[i] << " +- "
                                        << plain.sigma[i] << " lx without";
            // The portal's estimate is the sharper one by far.
            EXPECT_LT(portal.sigma[i], plain.sigma[i]) << c.name << " cell " << i;
            sum_z2 += z * z;
            ++count;
        }
    }
    const double mean = sum_z2 / count, band = 5.0 * std::sqrt(2.0 / count);
    EXPECT_NEAR(mean, 1.0, band) << "mean z^2 over " << count << " cells";
    std::cout << "[portal] " << count << " cells, mean z^2 " << mean << " (allowed 1 +- " << band << ")\n";
}

TEST(PortalRun, ExteriorGeometryIsWarnedAboutAndBadInputExitsTwo) {
    ScratchDir dir("portal_warn");
    const std::string wall = "[[shape]]\ntype = \"rectangle\"\ncenter = [0, -5, 1]\nnormal = [0, 1, 0]\n"
                             "up = [0, 0, 1]\nsize = [10, 2]\nmaterial = \"black\"\n";
    const fs::path scene = dir.path() / "warn.toml", out = dir.path() / "warn.h5";
    std::ofstream(scene) << room(kOvercast, wall, true);
    const auto o = run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() +
                                "\" --threads 2 --photons 10000");
    EXPECT_EQ(o.code, 0) << o.out;
    const auto k = run_luxtrace("check \"" + scene.string() + "\"");
    EXPECT_EQ(k.out.find("lie outside its opening"), std::string::npos) << "a black obstruction is exact: " << k.out;
    EXPECT_NE(k.out.find("hit exterior geometry"), std::string::npos) << k.out;
    // A grey one: the loader warns, and the probe says how much of the sky it hides.
    std::string grey = wall;
    grey.replace(grey.find("\"black\""), 7, "\"wall\"");
    std::ofstream(scene) << room(kOvercast, grey, true);
    const auto c = run_luxtrace("check \"" + scene.string() + "\"");
    EXPECT_NE(c.out.find("portal 'window': 2 triangle(s) that are not black lie outside"), std::string::npos) << c.out;
    EXPECT_NE(c.out.find("through portal 'window': "), std::string::npos) << c.out;
    EXPECT_NE(c.out.find("hit exterior geometry"), std::string::npos) << c.out;
    const fs::path bad = dir.path() / "bad.toml";
    std::ofstream(bad) << room(kOvercast, "", false) << "[[portal]]\nshape = \"door\"\n";
    const auto b = run_luxtrace("check \"" + bad.string() + "\"");
    EXPECT_EQ(b.code, 2) << b.out;
    EXPECT_NE(b.out.find("key 'shape'"), std::string::npos) << b.out;
    EXPECT_FALSE(fs::exists(dir.path() / "bad.h5"));
}

}  // namespace
}  // namespace luxtrace
