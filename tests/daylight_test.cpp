// Daylight end to end (docs/VALIDATION.md, "Daylight"): the real luxtrace binary runs sky
// and sun lights and every detector is judged by the run's own error estimate.
//  - Every sky (CIE types 1-16 and uniform, the sun at 30 and at 60 degrees) gives an
//    unobstructed horizontal plane its diffuse_horizontal_lx (or L_z times the quadrature
//    of sky_model.hpp) and vertical planes facing the four points of the compass what
//    the quadrature says.
//  - Energy: a closed black box's outer faces receive exactly what sky, sun and ground
//    glow give such faces.
//  - A sun patch through a window falls where geometry puts it at three times of a day,
//    with the sun's illuminance inside it, nothing outside, and the window's flux in all;
//    through a glazed window the patch is the pane's T(theta) times that, and it is
//    direct light in the surface map (going straight through a pane turns nothing).
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/light/site.hpp"
#include "luxtrace/light/sky_model.hpp"
#include "luxtrace/light/sun_position.hpp"
#include "luxtrace/material/glazing.hpp"

#include "test_support.hpp"
#include "z_pool.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

constexpr double kZMax = 5.0;

double deg(double d) { return d * kPi / 180.0; }

struct Reading {
    double value = 0.0, sigma = 0.0;  // lx, absolute
};

// The whole-grid mean of a one-band detector and its standard error (eq. 8).
Reading grid_mean(const ResultReader& r, const std::string& name) {
    const std::string g = "/detectors/" + name;
    const double v = r.attr_f64(g, "mean_value");
    return {v, v * r.attr_f64(g, "mean_sigma_rel")};
}

// Runs a scene text; the result file's path.
fs::path run_scene(const test_support::ScratchDir& dir, const std::string& name, const std::string& text) {
    test_support::CommandOutcome o;
    const fs::path out = test_support::run_scene_text(dir, name, text, &o);
    EXPECT_EQ(o.code, 0) << o.out;
    return out;
}

using test_support::kBlackSpeck;
using test_support::ZPool;

// An illuminance detector's text: by default a one-cell 1 m square at the origin.
std::string unit_detector(const std::string& name, const std::string& normal, const std::string& up,
                          const std::string& center = "[0, 0, 0]", const std::string& size = "[1, 1]",
                          const std::string& cells = "[1, 1]") {
    return "[[detector]]\nname = \"" + name + "\"\ntype = \"illuminance\"\ncenter = " + center +
           "\nnormal = " + normal + "\nup = " + up + "\nsize = " + size + "\ncells = " + cells + "\n";
}

TEST(DaylightSky, EverySkyLightsUnobstructedPlanesAsQuadratureSays) {
    test_support::ScratchDir dir("daylight_skies");
    struct Case {
        std::string sky;  // scene keys
        SkyModel model;
        bool by_zenith;
    };
    std::vector<Case> cases{{"sky = \"uniform\"\n", SkyModel::uniform(), false},
                            {"sky = \"cie\"\ncie_type = 16\n", SkyModel::cie(16, 0.0, 0.0), true}};
    for (int type = 1; type <= 15; ++type)
        for (const auto& [altitude, azimuth] : {std::pair{30.0, 180.0}, std::pair{60.0, 250.0}}) {
            std::ostringstream keys;
            keys << "sky = \"cie\"\ncie_type = " << type << "\nsun_altitude_deg = " << altitude
                 << "\nsun_azimuth_deg = " << azimuth << "\n";
            cases.push_back({keys.str(), SkyModel::cie(type, deg(90.0 - altitude), deg(azimuth)), altitude == 60.0});
        }
    const std::array<std::pair<const char*, double>, 4> facades{
        {{"north", 0.0}, {"east", 90.0}, {"south", 180.0}, {"west", 270.0}}};
    ZPool pool("daylight");
    int run = 0;
    for (const Case& c : cases) {
        // Normalised by the horizontal illuminance or by the zenith luminance, alternately.
        const double zenith_cd_m2 = 3000.0, horizontal_lx = 12000.0;
        std::string text = std::string(kBlackSpeck) + "\n[[light]]\ntype = \"sky\"\n" + c.sky +
                           (c.by_zenith ? "zenith_luminance_cd_m2 = 3000\n" : "diffuse_horizontal_lx = 12000\n") +
                           "\n" + unit_detector("up", "[0, 0, 1]", "[0, 1, 0]");
        for (const auto& [name, facing] : facades) {
            const Vec3 n = sky_direction(0.5 * kPi, deg(facing));
            std::ostringstream normal;
            normal << "[" << n.x << ", " << n.y << ", 0]";
            text += "\n" + unit_detector(name, normal.str(), "[0, 0, 1]");
        }
        text += "\n[run]\nphotons = 400000\nseed = " + std::to_string(101 + run) + "\n";
        const fs::path out = run_scene(dir, "sky" + std::to_string(run++), text);
        const ResultReader r(out);
        const double lz = c.by_zenith ? zenith_cd_m2
                                      : horizontal_lx / c.model.horizontal_illuminance_per_zenith_luminance_sr();
        const std::string what = c.sky.substr(0, c.sky.find('\n', c.sky.find("type") + 1)) + " sun " +
                                 std::to_string(c.model.sun_zenith_rad());
        pool.add(what + " horizontal", grid_mean(r, "up"),
                 lz * c.model.horizontal_illuminance_per_zenith_luminance_sr());
        for (const auto& [name, facing] : facades)
            pool.add(what + " " + name, grid_mean(r, name),
                     lz * c.model.vertical_illuminance_per_zenith_luminance_sr(deg(facing)));
    }
    pool.check("unobstructed planes under every sky");
}

TEST(DaylightSun, BelowTheHorizonTheRunSaysSoAndTheSunEmitsNothing) {
    // Munich, 21 December at 20:00: the run warns, the sun carries no flux, the sky runs.
    test_support::ScratchDir dir("daylight_night");
    const fs::path scene = dir.path() / "night.toml", out = dir.path() / "night.h5";
    std::ofstream(scene) << "[site]\nlatitude_deg = 48.14\nlongitude_deg = 11.58\nutc_offset_h = 1\n"
                            "time = \"2026-12-21T20:00\"\n\n"
                         << kBlackSpeck
                         << "\n[[light]]\ntype = \"sun\"\ndirect_normal_lx = 50000\n\n[[light]]\ntype = \"sky\"\n"
                            "sky = \"uniform\"\ndiffuse_horizontal_lx = 100\n\n"
                         << unit_detector("up", "[0, 0, 1]", "[0, 1, 0]") << "\n[run]\nphotons = 20000\n";
    const auto o = test_support::run_luxtrace("run \"" + scene.string() + "\" --output \"" + out.string() + "\"");
    ASSERT_EQ(o.code, 0) << o.out;
    EXPECT_NE(o.out.find("luxtrace: warning: light 1 (sun): the sun is below the horizon at 2026-12-21T20:00"),
              std::string::npos)
        << o.out;
    const ResultReader r(out);
    EXPECT_EQ(r.f64("/daylight/direct_normal_lx").at(0), 0.0);
    const Reading up = grid_mean(r, "up");
    EXPECT_LT(std::abs(up.value - 100.0), kZMax * up.sigma) << up.value << " +- " << up.sigma;
}

TEST(DaylightEnergy, ClosedBoxFacesReceiveWhatSkySunAndGroundGive) {
    // A black 1 m cube under the traditional overcast sky (10 klx), a sun of 60 klx
    // normal at altitude 35 degrees, azimuth 200, and a ground of reflectance 0.2:
    // its top gets E_dh + E_n sin h, its bottom the ground glow's pi L_g = rho E_h,global,
    // a vertical face the sky's share (quadrature), the sun's E_n cos h cos(a - a_s) when
    // it faces the sun, and half the ground's pi L_g. Detectors 1 mm off each face.
    test_support::ScratchDir dir("daylight_box");
    const double e_dh = 10000.0, e_n = 60000.0, h = 35.0, a_s = 200.0, rho = 0.2;
    std::ostringstream s;
    s << "[[material]]\nname = \"black\"\ntype = \"black\"\n\n[[shape]]\ntype = \"box\"\ncenter = [0, 0, 0]\n"
         "size = [1, 1, 1]\nmaterial = \"black\"\n\n"
      << "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = " << e_dh
      << "\nground_reflectance = " << rho << "\n\n[[light]]\ntype = \"sun\"\ndirect_normal_lx = " << e_n
      << "\nsun_altitude_deg = " << h << "\nsun_azimuth_deg = " << a_s << "\n\n";
    const double e_global = e_dh + e_n * std::sin(deg(h));
    const SkyModel overcast = SkyModel::cie(16, 0.0, 0.0);
    const double lz = e_dh / overcast.horizontal_illuminance_per_zenith_luminance_sr();
    struct Face {
        std::string name;
        Vec3 normal;
        double expected;
    };
    std::vector<Face> faces{{"top", {0, 0, 1}, e_global}, {"bottom", {0, 0, -1}, rho * e_global}};
    for (const double facing : {0.0, 90.0, 180.0, 270.0}) {
        const Vec3 n = sky_direction(0.5 * kPi, deg(facing));
        const double sun = e_n * std::cos(deg(h)) * std::max(0.0, std::cos(deg(facing - a_s)));
        faces.push_back(
            {"facing" + std::to_string(int(facing)), n,
             lz * overcast.vertical_illuminance_per_zenith_luminance_sr(deg(facing)) + sun + 0.5 * rho * e_global});
    }
    for (const Face& f : faces) {
        const Vec3 c = 0.501 * f.normal;
        s << "[[detector]]\nname = \"" << f.name << "\"\ntype = \"illuminance\"\ncenter = [" << c.x << ", " << c.y
          << ", " << c.z << "]\nnormal = [" << f.normal.x << ", " << f.normal.y << ", " << f.normal.z
          << "]\nup = " << (std::abs(f.normal.z) > 0.5 ? "[0, 1, 0]" : "[0, 0, 1]")
          << "\nsize = [1, 1]\ncells = [1, 1]\n\n";
    }
    s << "[run]\nphotons = 3000000\nseed = 7\n";
    const ResultReader r(run_scene(dir, "box", s.str()));
    ZPool pool("daylight");
    for (const Face& f : faces) pool.add(f.name, grid_mean(r, f.name), f.expected);
    pool.check("closed box faces");
}

// A black room 3 m x 2 m x 2 m with a 0.6 m x 0.6 m opening in its south wall (y = -1,
// x in [-0.3, 0.3], z in [0.9, 1.5]), glazed by `pane` (scene text) if given, and a
// floor detector of 5 cm cells. The floor is the first shape: triangles 0 and 1.
// A black rectangle's [[shape]] text: centre, normal, size (and `up` for the floor and
// ceiling, whose default up would turn them).
std::string black_rectangle(const std::string& center, const std::string& normal, const std::string& size,
                            const std::string& up = "") {
    return "[[shape]]\ntype = \"rectangle\"\ncenter = " + center + "\nnormal = " + normal + "\nsize = " + size +
           (up.empty() ? "" : "\nup = " + up) + "\nmaterial = \"black\"\n\n";
}

std::string sun_patch_scene(const std::string& time, const std::string& pane = "") {
    return "[site]\nlatitude_deg = 45.0\nlongitude_deg = 9.0\nutc_offset_h = 1\ntime = \"" + time +
           "\"\n\n[[material]]\nname = \"black\"\ntype = \"black\"\n\n" +
           black_rectangle("[0, 0, 0]", "[0, 0, 1]", "[3, 2]", "[0, 1, 0]") +   // floor: triangles 0, 1
           black_rectangle("[0, 0, 2]", "[0, 0, -1]", "[3, 2]", "[0, 1, 0]") +  // ceiling
           black_rectangle("[0, 1, 1]", "[0, -1, 0]", "[3, 2]") +               // north wall
           black_rectangle("[1.5, 0, 1]", "[-1, 0, 0]", "[2, 2]") +             // east wall
           black_rectangle("[-1.5, 0, 1]", "[1, 0, 0]", "[2, 2]") +             // west wall
           black_rectangle("[0, -1, 0.45]", "[0, 1, 0]", "[3, 0.9]") +          // south wall: below,
           black_rectangle("[0, -1, 1.75]", "[0, 1, 0]", "[3, 0.5]") +          // above,
           black_rectangle("[-0.9, -1, 1.2]", "[0, 1, 0]", "[1.2, 0.6]") +      // west and east of the window
           black_rectangle("[0.9, -1, 1.2]", "[0, 1, 0]", "[1.2, 0.6]") + R"([[light]]
type = "sun"
direct_normal_lx = 80000
)" + pane + "\n" +
           unit_detector("floor", "[0, 0, 1]", "[0, 1, 0]", "[0, 0, 0.001]", "[3, 2]", "[60, 40]") +
           "\n[run]\nphotons = 3000000\nseed = 11\n";
}

// The sun over the patch room's site (45 N, 9 E, CET) at local standard `time`.
SunPosition patch_sun(const char* time) {
    SunSite site;
    site.latitude_deg = 45.0;
    site.longitude_deg = 9.0;
    LocalStandardTime when = *parse_local_time(time);
    when.utc_offset_h = 1.0;
    return sun_position(when, site);
}

// The patch a run of sun_patch_scene(time, pane) leaves on the floor detector against
// geometry: cells wholly inside it read `transmittance` x E_n sin h, cells wholly outside
// nothing, and the floor receives the window's flux. Returns the result file.
fs::path check_sun_patch(const test_support::ScratchDir& dir, const std::string& name, const char* time,
                         const std::string& pane, double transmittance) {
    constexpr double kEn = 80000.0, kCell = 0.05;
    constexpr double kMargin = 0.03;  // the penumbra: about 2.5 m x tan(0.27 deg) = 1.2 cm, and rounding
    const SunPosition sun = patch_sun(time);
    const Vec3 d = -sky_direction_deg(sun.altitude_deg, sun.azimuth_deg);  // travel (north = +y)
    const fs::path out = run_scene(dir, name, sun_patch_scene(time, pane));
    const ResultReader r(out);
    const std::vector<double> value = r.f64("/detectors/floor/value"), sigma_rel = r.f64("/detectors/floor/sigma_rel");
    // Where a floor point's ray back to the sun crosses the wall plane y = -1, in window
    // coordinates; inside the window shrunk (or grown) by `margin`?
    auto through_window = [&](double x, double y, double margin) {
        const double s = (y + 1.0) / d.y;  // back along -d to y = -1
        const double wx = x - s * d.x, wz = 0.001 - s * d.z;
        return wx > -0.3 + margin && wx < 0.3 - margin && wz > 0.9 + margin && wz < 1.5 - margin;
    };
    ZPool inside("daylight");
    double flux = 0.0, flux_var = 0.0;
    int lit = 0, dark = 0;
    for (int j = 0; j < 40; ++j)
        for (int i = 0; i < 60; ++i) {
            const std::size_t c = static_cast<std::size_t>(j * 60 + i);
            const double x0 = -1.5 + i * kCell, y0 = -1.0 + j * kCell;
            bool all_in = true, all_out = true;
            for (const double x : {x0, x0 + kCell})
                for (const double y : {y0, y0 + kCell}) {
                    all_in = all_in && through_window(x, y, kMargin);
                    all_out = all_out && !through_window(x, y, -kMargin);
                }
            flux += value[c] * kCell * kCell;
            if (value[c] > 0.0) flux_var += std::pow(sigma_rel[c] * value[c] * kCell * kCell, 2);
            if (all_in) {
                ++lit;
                inside.add(name + " cell " + std::to_string(c), value[c], sigma_rel[c] * value[c],
                           transmittance * kEn * std::sin(deg(sun.altitude_deg)));
            } else if (all_out) {
                ++dark;
                EXPECT_EQ(value[c], 0.0) << name << ": cell " << i << "," << j << " lies outside the patch";
            }
        }
    EXPECT_GT(lit, 40) << name;
    EXPECT_GT(dark, 1500) << name;
    inside.check(name + " inside the patch");
    // All the beam the window lets in lands on the floor (the cells' errors are nearly
    // independent: a photon registers in one cell).
    const double window_flux = transmittance * kEn * 0.36 * std::max(0.0, d.y);
    const double z = (flux - window_flux) / std::sqrt(flux_var);
    EXPECT_LT(std::abs(z), kZMax) << name << ": floor flux " << flux << " lm, window " << window_flux << " lm";
    std::cout << "[daylight] " << name << " " << time << ": sun altitude " << sun.altitude_deg << ", azimuth "
              << sun.azimuth_deg << "; " << lit << " cells inside, " << dark << " outside; floor flux " << flux
              << " lm vs " << window_flux << " (z " << z << ")\n";
    return out;
}

TEST(DaylightSun, PatchThroughAWindowFallsWhereGeometryPutsIt) {
    test_support::ScratchDir dir("daylight_patch");
    int t = 0;
    for (const char* time : {"2026-03-21T11:00", "2026-03-21T12:30", "2026-03-21T14:00"})
        check_sun_patch(dir, "patch" + std::to_string(t++), time, "", 1.0);
}

TEST(DaylightSun, PatchThroughGlazingIsThePanesShareAndDirectLight) {
    // A 6 mm clear pane (T_n 0.88, n 1.52) in the opening: the patch is T(theta) of the
    // sun's incidence on the pane, and on the black floor every arrival is direct.
    test_support::ScratchDir dir("daylight_glazed_patch");
    const char* time = "2026-03-21T14:00";
    const SunPosition sun = patch_sun(time);
    const double cos_i = sky_direction_deg(sun.altitude_deg, sun.azimuth_deg).y * -1.0;  // pane normal: south
    const double t = pane_optics(cos_i, 1.52, pane_transmissivity(0.88, 1.52)).transmittance;
    const std::string pane = R"(
[[material]]
name = "clear6mm"
type = "glazing"
transmittance = 0.88
refractive_index = 1.52

[[shape]]
type = "rectangle"
center = [0, -1, 1.2]
normal = [0, -1, 0]
size = [0.6, 0.6]
material = "clear6mm"
)";
    const ResultReader r(check_sun_patch(dir, "glazed", time, pane, t));
    const std::vector<std::uint64_t> count = r.u64("/global/count_odd"), direct = r.u64("/global/direct_odd");
    // The floor's two triangles, their front sides: [T, 2, B] with one band.
    for (const std::size_t i : {std::size_t{0}, std::size_t{2}}) {
        EXPECT_GT(count[i], 100u);
        EXPECT_EQ(direct[i], count[i]) << "floor slot " << i;
    }
}

}  // namespace
}  // namespace luxtrace
