// The renderer against analytic cases (a diffuse plane under point, IES, spot,
// directional and area lights: L = rho E / pi), the stored secondary map (zero in a room
// with black walls, added smoothly otherwise), mirrors and glass, tone mapping's
// invariants, the image files, and `luxtrace render` on bad input.
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/light/ies.hpp"
#include "luxtrace/render/camera.hpp"
#include "luxtrace/render/image_io.hpp"
#include "luxtrace/render/renderer.hpp"
#include "luxtrace/render/tone_map.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include "daylight_reference.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <cairo.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

namespace fs = std::filesystem;
using namespace luxtrace;

namespace {

const fs::path kData = fs::path(LUXTRACE_TEST_DATA_DIR) / "render";

struct Fixture {
    Scene scene;
    std::unique_ptr<EmbreeScene> embree;
    std::unique_ptr<Renderer> renderer;
    explicit Fixture(Scene s, std::vector<double> secondary = {}, std::vector<double> light_weight = {})
        : scene(std::move(s)) {
        embree = std::make_unique<EmbreeScene>(scene);
        renderer = std::make_unique<Renderer>(scene, *embree, std::move(secondary), std::move(light_weight));
    }
};

fs::path temp_dir() {
    const fs::path d = fs::temp_directory_path() / ("luxtrace_render_" + std::to_string(::getpid()) + "_" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

int run_cli(const std::string& args, std::string* output = nullptr) {
    const fs::path log = fs::temp_directory_path() / ("luxtrace_render_cli_" + std::to_string(::getpid()) + ".log");
    const int status = std::system(
        (std::string(LUXTRACE_BINARY) + " " + args + " > " + log.string() + " 2>&1").c_str());
    std::stringstream ss;
    ss << std::ifstream(log).rdbuf();
    fs::remove(log);
    if (output != nullptr) *output = ss.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `luxtrace run` on a scene; returns the result path.
fs::path simulate(const fs::path& scene, const fs::path& dir, const std::string& photons) {
    const fs::path out = dir / (scene.stem().string() + ".h5");
    std::string log;
    const int code = run_cli("run " + scene.string() + " --output " + out.string() + " --photons " + photons +
                                 " --threads 2 --quiet",
                             &log);
    EXPECT_EQ(code, 0) << log;
    return out;
}

// Ray-plane z = 0 hit; false if the ray goes up.
bool hit_floor(const Vec3& o, const Vec3& d, Vec3& p) {
    if (d.z >= 0.0) return false;
    p = o - (o.z / d.z) * d;
    return true;
}

double point_E(const Vec3& light, double flux, const Vec3& p) {  // isotropic source on z = 0
    const Vec3 v = light - p;
    const double r = glm::length(v);
    return flux / (4.0 * kPi) * v.z / (r * r * r);
}

}  // namespace

// ---- Direct light: exact, so compared tightly -------------------------------------------

TEST(RenderDirect, PointSourceRaysShowRhoEOverPi) {
    const Fixture f(load_scene(kData / "point_plane.toml"));
    const PinholeCamera cam(f.scene.cameras.at(0));
    int checked = 0;
    for (int j = 2; j < cam.height(); j += 9)
        for (int i = 3; i < cam.width(); i += 12) {
            const Vec3 d = cam.direction(i + 0.5, j + 0.5);
            Vec3 p;
            ASSERT_TRUE(hit_floor(cam.position(), d, p));
            ASSERT_LT(std::max(std::abs(p.x), std::abs(p.y)), 3.0);
            const double expected = 0.6 / kPi * point_E(Vec3(0.3, -0.2, 2), 1000.0, p);
            EXPECT_NEAR(f.renderer->trace(cam.position(), d, 1)[0], expected, 1e-5 * expected) << i << "," << j;
            ++checked;
        }
    EXPECT_GE(checked, 20);
}

TEST(RenderDirect, SkyThroughAPortalIsItsExactSkyComponent) {
    // A 4 x 4 x 3 m room, black but for its grey floor (rho 0.5), lit by the CIE overcast sky
    // through a 1 m square hole in the roof that is a [[portal]] (an ior 1 "glass" that
    // blocks nothing). Only direct sky reaches the floor, so a floor point shows
    // rho / pi x E_dh x SC, SC the exact sky component through the hole (daylight_reference),
    // whatever the stored map: the renderer samples the opening, not the whole sky.
    auto rect = [](const std::string& c, const std::string& n, const std::string& size, const std::string& m) {
        return "[[shape]]\ntype = \"rectangle\"\ncenter = " + c + "\nnormal = " + n +
               "\nup = " + (n == "[0, 0, 1]" || n == "[0, 0, -1]" ? "[0, 1, 0]" : "[0, 0, 1]") + "\nsize = " + size +
               "\nmaterial = \"" + m + "\"\n\n";
    };
    const fs::path dir = temp_dir();
    std::ofstream(dir / "hole.toml")
        << "[[material]]\nname = \"black\"\ntype = \"black\"\n\n[[material]]\nname = \"grey\"\nreflectance = 0.5\n\n"
           "[[material]]\nname = \"hole\"\ntype = \"glass\"\nior = 1\n\n"
        << rect("[2, 2, 0]", "[0, 0, 1]", "[4, 4]", "grey") << rect("[2, 0.75, 3]", "[0, 0, -1]", "[4, 1.5]", "black")
        << rect("[2, 3.25, 3]", "[0, 0, -1]", "[4, 1.5]", "black")
        << rect("[0.75, 2, 3]", "[0, 0, -1]", "[1.5, 1]", "black")
        << rect("[3.25, 2, 3]", "[0, 0, -1]", "[1.5, 1]", "black")
        << rect("[0, 2, 1.5]", "[1, 0, 0]", "[4, 3]", "black") << rect("[4, 2, 1.5]", "[-1, 0, 0]", "[4, 3]", "black")
        << rect("[2, 0, 1.5]", "[0, 1, 0]", "[4, 3]", "black") << rect("[2, 4, 1.5]", "[0, -1, 0]", "[4, 3]", "black")
        << "[[shape]]\nname = \"skylight\"\ntype = \"rectangle\"\ncenter = [2, 2, 3]\nnormal = [0, 0, -1]\n"
           "up = [0, 1, 0]\nsize = [1, 1]\nmaterial = \"hole\"\n\n[[portal]]\nshape = \"skylight\"\n\n"
           "[[light]]\ntype = \"sky\"\nsky = \"cie\"\ncie_type = 16\ndiffuse_horizontal_lx = 10000\n";
    const Fixture f(load_scene(dir / "hole.toml"));
    RenderOptions opt;
    opt.area_light_samples = 4096;
    const SkyModel overcast = SkyModel::cie(16, 0.0, 0.0);
    const daylight_reference::Polygon hole = daylight_reference::rectangle(Vec3(2, 2, 3), Vec3(0.5, 0, 0),
                                                                           Vec3(0, 0.5, 0));
    for (const auto& [x, y] : {std::pair{2.0, 2.0}, std::pair{1.0, 2.5}, std::pair{3.3, 0.6}}) {
        double mean = 0.0;
        constexpr int kSeeds = 4;
        for (int seed = 1; seed <= kSeeds; ++seed)
            mean += f.renderer->trace(Vec3(x, y, 1.0), Vec3(0, 0, -1), static_cast<std::uint64_t>(seed), opt)[0];
        mean /= kSeeds;
        const double sc = daylight_reference::sky_component(overcast, {Vec3(x, y, 0), Vec3(0, 0, 1), hole, {}, {}});
        const double expected = 0.5 / kPi * 10000.0 * sc;
        // 16384 points on the opening: about 0.1 % of noise.
        EXPECT_NEAR(mean / expected, 1.0, 0.005) << "floor point " << x << ", " << y << ": SC " << sc;
    }
    fs::remove_all(dir);
}

TEST(RenderDirect, RenderedPixelsLieWithinTheirFootprintAndSecondaryIsZero) {
    // End to end from a result: the plane alone receives only first hits, so the stored
    // secondary map is exactly zero, and each pixel (a mean of rays inside the pixel)
    // must lie between the smallest and largest rho E / pi over the pixel's footprint.
    const fs::path dir = temp_dir();
    const RenderInput in = load_render_input(simulate(kData / "point_plane.toml", dir, "20000"));
    for (double s : in.secondary_lx) ASSERT_EQ(s, 0.0);
    const Fixture f(in.scene, in.secondary_lx);
    const PinholeCamera cam(f.scene.cameras.at(0));
    RenderOptions opt;
    opt.samples = 4;
    opt.threads = 2;
    const LuminanceImage img = f.renderer->render(cam, opt);
    ASSERT_EQ(img.width, 64);
    ASSERT_EQ(img.height, 48);
    std::vector<double> spread;
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            double lo = 1e300, hi = 0.0;
            for (int a = 0; a <= 8; ++a)
                for (int b = 0; b <= 8; ++b) {
                    Vec3 p;
                    ASSERT_TRUE(hit_floor(cam.position(), cam.direction(i + a / 8.0, j + b / 8.0), p));
                    const double l = 0.6 / kPi * point_E(Vec3(0.3, -0.2, 2), 1000.0, p);
                    lo = std::min(lo, l);
                    hi = std::max(hi, l);
                }
            const double v = img.at(i, j, 0);
            EXPECT_GE(v, lo * (1 - 1e-4)) << i << "," << j;
            EXPECT_LE(v, hi * (1 + 1e-4)) << i << "," << j;
            spread.push_back((hi - lo) / hi);
        }
    std::nth_element(spread.begin(), spread.begin() + spread.size() / 2, spread.end());
    // The bound has teeth: across most pixels E varies by a few per cent, far less than a
    // wrong reflectance or a lost 1/pi would change the value.
    std::printf("median spread of rho E / pi over a pixel: %.2f %%\n", 100 * spread[spread.size() / 2]);
    EXPECT_LT(spread[spread.size() / 2], 0.05);
    fs::remove_all(dir);
}

TEST(RenderDirect, SpotAndSunExactWithShadow) {
    const std::string base = [] {
        std::stringstream s;
        s << std::ifstream(kData / "lights_plane.toml").rdbuf();
        return s.str();
    }();
    const fs::path dir = temp_dir();
    auto with_light = [&](const std::string& light) {
        std::ofstream(dir / "scene.toml") << base << light;
        return load_scene(dir / "scene.toml");
    };
    {  // Spot: I = F / (2 pi (1 - cos a)) inside the cone, nothing outside.
        const Fixture f(with_light("[[light]]\ntype = \"spot\"\nposition = [0, 0, 1.5]\n"
                                   "direction = [0.2, 0, -1]\nhalf_angle_deg = 30\nflux_lm = 500\n"));
        const Vec3 pos(0, 0, 1.5), axis = glm::normalize(Vec3(0.2, 0, -1));
        const double intensity = 500.0 / (2 * kPi * (1 - std::cos(kPi / 6)));
        int inside = 0, outside = 0;
        for (double x = -1.2; x <= 1.6; x += 0.2)
            for (double y = -0.9; y <= 0.9; y += 0.3) {
                const Vec3 p(x, y, 0), v = pos - p;
                const double r = glm::length(v);
                const bool lit = glm::dot(-v / r, axis) > std::cos(kPi / 6);
                const double e = lit ? intensity * v.z / (r * r * r) : 0.0;
                (lit ? inside : outside) += 1;
                const double l = f.renderer->trace(Vec3(x, y, 0.5), Vec3(0, 0, -1), 1)[0];
                EXPECT_NEAR(l, 0.5 / kPi * e, 1e-5 * (1 + e)) << x << "," << y;
            }
        EXPECT_GT(inside, 10);
        EXPECT_GT(outside, 10);
    }
    {  // Sun: E = E_n cos(theta) where unshadowed; the black block shadows the plane.
        const Fixture f(with_light("[[light]]\ntype = \"directional\"\ndirection = [0.5, 0, -1]\n"
                                   "illuminance_lx = 10000\n"));
        const double lit = 0.5 / kPi * 10000.0 / std::sqrt(1.25);
        EXPECT_NEAR(f.renderer->trace(Vec3(0, 0, 0.5), Vec3(0, 0, -1), 1)[0], lit, 1e-6 * lit);
        EXPECT_NEAR(f.renderer->trace(Vec3(2.5, -2, 0.5), Vec3(0, 0, -1), 1)[0], lit, 1e-6 * lit);
        // The block (x in [-2.8,-2.2], |y| < 0.3, z < 1) shades x up to -1.7 on |y| < 0.3.
        EXPECT_EQ(f.renderer->trace(Vec3(-2.0, 0, 0.5), Vec3(0, 0, -1), 1)[0], 0.0);
        EXPECT_NEAR(f.renderer->trace(Vec3(-2.0, 0.5, 0.5), Vec3(0, 0, -1), 1)[0], lit, 1e-6 * lit);
        EXPECT_NEAR(f.renderer->trace(Vec3(-1.5, 0, 0.5), Vec3(0, 0, -1), 1)[0], lit, 1e-6 * lit);
    }
    fs::remove_all(dir);
}

TEST(RenderDirect, AreaLightMatchesConfigurationFactorAndShowsMOverPi) {
    const fs::path dir = temp_dir();
    {
        std::stringstream s;
        s << std::ifstream(kData / "lights_plane.toml").rdbuf()
          << "[[light]]\ntype = \"area\"\nshape = \"panel\"\nflux_lm = 1000\n";
        std::ofstream(dir / "scene.toml") << s.str();
    }
    const Fixture f(load_scene(dir / "scene.toml"));
    const double m = 1000.0 / 0.6;  // exitance of the 1 m x 0.6 m panel
    // Point below a corner of an a x b rectangle at height h (parallel planes).
    auto corner = [](double a, double b, double h) {
        const double x = a / h, y = b / h, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
        return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
    };
    for (const Vec3 p : {Vec3(1.5, 1.5, 0), Vec3(1.7, 1.4, 0), Vec3(0.6, 0.9, 0)}) {
        // The corner formula extended oddly in each offset, summed with the signs of
        // F([x1,x2] x [y1,y2]) = G(x2,y2) - G(x1,y2) - G(x2,y1) + G(x1,y1).
        double factor = 0.0;
        for (double xe : {1.0, 2.0})
            for (double ye : {1.2, 1.8}) {
                const double dx = xe - p.x, dy = ye - p.y;
                const double sign = (xe == 2.0 ? 1 : -1) * (ye == 1.8 ? 1 : -1) * (dx > 0 ? 1 : -1) * (dy > 0 ? 1 : -1);
                factor += sign * corner(std::abs(dx), std::abs(dy), 1.0);
            }
        const double expected = 0.5 / kPi * m * factor;
        // Independent estimates (different seeds): their mean within 4 standard errors.
        RenderOptions opt;
        opt.area_light_samples = 64;
        std::vector<double> v;
        for (std::uint64_t seed = 1; seed <= 200; ++seed)
            v.push_back(f.renderer->trace(p + Vec3(0, 0, 0.3), Vec3(0, 0, -1), seed, opt)[0]);
        double mean = 0.0, var = 0.0;
        for (double x : v) mean += x / v.size();
        for (double x : v) var += (x - mean) * (x - mean) / (v.size() - 1);
        const double se = std::sqrt(var / v.size());
        std::printf("area light at (%.1f, %.1f): %.5g cd/m^2, expected %.5g, z = %.2f\n", p.x, p.y, mean, expected,
                    (mean - expected) / se);
        EXPECT_LT(std::abs(mean - expected), 4.0 * se + 1e-9 * expected)
            << p.x << "," << p.y << " expected " << expected;
        EXPECT_LT(se, 0.01 * expected);  // the test has power
    }
    // The emitter seen from its front (below) shows M / pi; from behind, its black back.
    EXPECT_NEAR(f.renderer->trace(Vec3(1.5, 1.5, 0.5), Vec3(0.1, 0, 1), 1)[0], m / kPi, 1e-6 * m);  // float vertices
    EXPECT_EQ(f.renderer->trace(Vec3(1.5, 1.5, 2.0), Vec3(0, 0.1, -1), 1)[0], 0.0);
    fs::remove_all(dir);
}

TEST(RenderDirect, IesLuminaireAgreesWithSimulatedDirectMap) {
    // The photon run emits in the luminaire frame (aim, C0 plane); the renderer evaluates
    // the intensity in the same frame. Per triangle, the simulated direct count is
    // Poisson-like around mu = E_render * A / E0: chi-square over the triangles,
    // judged through its Wilson-Hilferty normal score (|z| < 4).
    const fs::path dir = temp_dir();
    const fs::path result = simulate(kData / "ies_plane.toml", dir, "500000");
    const ResultReader r(result);
    const double e0 = r.attr_f64("/", "flux_per_photon_lm");
    const std::vector<std::uint64_t> odd = r.u64("/global/direct_odd"), even = r.u64("/global/direct_even");
    const Fixture f(load_scene(kData / "ies_plane.toml"));
    ASSERT_EQ(odd.size(), 2 * f.scene.triangle_count());  // [T, 2 sides, 1 band]
    double chi2 = 0.0;
    int dof = 0;
    for (std::size_t t = 0; t < f.scene.triangle_count(); ++t) {
        const glm::uvec3 tri = f.scene.triangles[t];
        const Vec3 a(f.scene.vertices[tri.x]), b(f.scene.vertices[tri.y]), c(f.scene.vertices[tri.z]);
        double e = 0.0;  // mean over the triangle: centroids of a 4 x 4 subdivision
        int n = 0;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; i + j < 4; ++j)
                for (int up = 0; up < (i + j < 3 ? 2 : 1); ++up) {
                    const double u = up ? (i + 2.0 / 3) / 4 : (i + 1.0 / 3) / 4;
                    const double v = up ? (j + 2.0 / 3) / 4 : (j + 1.0 / 3) / 4;
                    const Vec3 p = a + u * (b - a) + v * (c - a);
                    e += kPi / 0.5 * f.renderer->trace(p + Vec3(0, 0, 0.5), Vec3(0, 0, -1), 1)[0];
                    ++n;
                }
        ASSERT_EQ(n, 16);
        const double mu = e / n * f.scene.triangle_area_m2[t] / e0;
        if (mu < 20) continue;
        // The luminaire lights the plane's front; its back stays dark.
        EXPECT_EQ(odd[2 * t + 1] + even[2 * t + 1], 0u) << t;
        const double k = static_cast<double>(odd[2 * t] + even[2 * t]);
        chi2 += (k - mu) * (k - mu) / mu;
        ++dof;
    }
    ASSERT_GT(dof, 300);
    const double z = (std::cbrt(chi2 / dof) - (1 - 2.0 / (9 * dof))) / std::sqrt(2.0 / (9 * dof));
    std::printf("IES direct map: chi2 %.1f over %d triangles, z = %.2f\n", chi2, dof, z);
    EXPECT_LT(std::abs(z), 4.0) << "chi2 " << chi2 << " over " << dof << " triangles";
    fs::remove_all(dir);
}

// ---- The stored secondary map -----------------------------------------------------------

TEST(RenderSecondary, BlackWallsGiveZeroMapAndTheDirectImage) {
    const fs::path dir = temp_dir();
    // The black walls do receive light from the floor (arrivals that are absorbed), but
    // no surface that reflects receives anything but first hits.
    const RenderInput in = load_render_input(simulate(kData / "black_room.toml", dir, "200000"));
    int floor_triangles = 0;
    for (std::size_t t = 0; t < in.scene.triangle_count(); ++t)
        if (in.scene.materials[in.scene.triangle_material[t]].type != MaterialType::black) {
            ASSERT_EQ(in.secondary_lx[2 * t], 0.0) << t;
            ASSERT_EQ(in.secondary_lx[2 * t + 1], 0.0) << t;
            ++floor_triangles;
        }
    EXPECT_EQ(floor_triangles, 128);
    const Fixture with_map(in.scene, in.secondary_lx), direct_only(in.scene);
    const PinholeCamera cam(in.scene.cameras.at(0));
    const LuminanceImage a = with_map.renderer->render(cam), b = direct_only.renderer->render(cam);
    EXPECT_EQ(a.values, b.values);
    double sum = 0.0;
    for (float v : a.values) sum += v;
    EXPECT_GT(sum, 0.0);  // the floor is lit
    fs::remove_all(dir);
}

TEST(RenderSecondary, GreyWallsAddTheSmoothedMap) {
    const fs::path dir = temp_dir();
    const RenderInput in = load_render_input(simulate(kData / "grey_room.toml", dir, "200000"));
    const Fixture f(in.scene, in.secondary_lx);
    const Scene& s = f.scene;
    // A floor pixel: rho / pi (E_direct analytic + the smoothed map at the hit point).
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1.8, 1.8);
    for (int k = 0; k < 20; ++k) {
        const Vec3 p(u(rng), u(rng), 0.001), o = p + Vec3(0, 0, 0.4);
        const Hit h = f.embree->intersect(o, Vec3(0, 0, -1));
        ASSERT_TRUE(h.found);
        const double sec = f.renderer->secondary_at(h.triangle, 0, p)[0];  // the floor's front
        EXPECT_GT(sec, 0.0);
        const double expected = 0.7 / kPi * (point_E(Vec3(0.3, 0.2, 2.5), 2000.0, p) + sec);
        EXPECT_NEAR(f.renderer->trace(o, Vec3(0, 0, -1), 1)[0], expected, 1e-5 * expected);
    }
    // The smoothed value of a side lies within the same side's values of the triangles
    // around the hit triangle ([T][2][1]).
    for (int k = 0; k < 200; ++k) {
        const std::size_t t = rng() % s.triangle_count(), side = rng() % 2;
        const glm::uvec3 tri = s.triangles[t];
        double lo = 1e300, hi = -1e300;
        for (std::size_t o = 0; o < s.triangle_count(); ++o)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    if (s.triangles[o][i] == tri[j]) {
                        lo = std::min(lo, in.secondary_lx[2 * o + side]);
                        hi = std::max(hi, in.secondary_lx[2 * o + side]);
                    }
        const double a = std::uniform_real_distribution<double>(0, 1)(rng);
        const double b = std::uniform_real_distribution<double>(0, 1 - a)(rng);
        const Vec3 p = Vec3(s.vertices[tri.x]) + a * (Vec3(s.vertices[tri.y]) - Vec3(s.vertices[tri.x])) +
                       b * (Vec3(s.vertices[tri.z]) - Vec3(s.vertices[tri.x]));
        const double v = f.renderer->secondary_at(t, side, p)[0];
        EXPECT_GE(v, lo * (1 - 1e-12));
        EXPECT_LE(v, hi * (1 + 1e-12));
    }
    // A constant map stays constant everywhere.
    const Fixture flat(in.scene, std::vector<double>(2 * s.triangle_count(), 42.0));
    for (int k = 0; k < 50; ++k) {
        const std::size_t t = rng() % s.triangle_count();
        EXPECT_NEAR(flat.renderer->secondary_at(t, rng() % 2, Vec3(s.vertices[s.triangles[t].x]))[0], 42.0, 1e-9);
    }
    fs::remove_all(dir);
}

// ---- Specular surfaces ------------------------------------------------------------------

TEST(RenderSpecular, MirrorAndGlassScaleWhatIsBehind) {
    const Fixture f(load_scene(kData / "specular.toml"));
    // Mirror: ray from (0,0,1.5) to (-2,0,1) reflects to (2,0,0) on the plane.
    const Vec3 o(0, 0, 1.5), d = glm::normalize(Vec3(-2, 0, -0.5));
    const Vec3 m(-2, 0, 1), reflected = glm::normalize(Vec3(2, 0, -0.5));
    const double behind = f.renderer->trace(m + 1e-3 * reflected, reflected, 1)[0];
    EXPECT_GT(behind, 0.0);
    EXPECT_NEAR(f.renderer->trace(o, d, 1)[0], 0.9 * behind, 1e-5 * behind);
    // Glass slab at normal incidence; the terms the renderer drops (weight < 1e-4) are
    // (1-R)^2 R^4 / (1 - R^2), 2.6e-6 of the result.
    const double r = std::pow(0.5 / 2.5, 2);
    const double under = f.renderer->trace(Vec3(0.1, 0.1, 0.3), Vec3(0, 0, -1), 1)[0];
    EXPECT_GT(under, 0.0);
    const double through = f.renderer->trace(Vec3(0.1, 0.1, 1.5), Vec3(0, 0, -1), 1)[0];
    EXPECT_NEAR(through, (1 - r) / (1 + r) * under, 1e-5 * under);
}

// A glossy floor (Ward lobe, roughness 0.3) under a uniform sky: every view ray it reflects
// reaches the sky, so over many samples the pixel shows rho_s a(cos_i) L, the lobe's albedo
// times the sky (a mirror would show rho_s L): each sample is rho_s L or 0 (absorbed).
TEST(RenderSpecular, GlossyReflectionShowsTheLobesAlbedoOfTheSky) {
    const fs::path dir = temp_dir();
    std::ofstream(dir / "glossy.toml") << R"([[material]]
name = "satin"
type = "general"
specular_reflectance = 0.8
roughness = 0.3

[[shape]]
type = "rectangle"
size = [40, 40]
material = "satin"

[[light]]
type = "sky"
sky = "uniform"
zenith_luminance_cd_m2 = 1000
)";
    const Fixture f(load_scene(dir / "glossy.toml"));
    const Material& m = f.scene.materials[0];
    ASSERT_TRUE(m.lobe);
    const double cos_i = std::cos(70.0 * kPi / 180.0);  // grazing: the lobe loses most there
    const Vec3 d(std::sqrt(1.0 - cos_i * cos_i), 0.0, -cos_i);
    const int n = 20000;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) sum += f.renderer->trace(Vec3(0, 0, 1), d, static_cast<std::uint64_t>(k) + 1)[0];
    const double a = m.lobe->albedo(cos_i), expected = 0.8 * a * 1000.0;
    const double sigma = 800.0 * std::sqrt(a * (1.0 - a) / n);
    EXPECT_LT(a, 0.97);  // the test tells a lobe from a mirror
    EXPECT_NEAR(sum / n, expected, 4.0 * sigma + 1e-9) << "albedo " << a;
    fs::remove_all(dir);
}

TEST(RenderColour, BandsFollowReflectanceAndLightColour) {
    const Fixture f(load_scene(kData / "rgb_plane.toml"));
    const std::vector<double> l = f.renderer->trace(Vec3(0.3, 0.2, 1), Vec3(0, 0, -1), 1);
    ASSERT_EQ(l.size(), 3u);
    const double total = point_E(Vec3(0, 0, 2), 1000.0, Vec3(0.3, 0.2, 0)) / kPi;  // E / pi over all bands
    const double share[3] = {1 / 1.75, 0.5 / 1.75, 0.25 / 1.75}, rho[3] = {0.8, 0.5, 0.2};
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(l[b], rho[b] * share[b] * total, 1e-5 * l[b]);
}

// ---- Tone mapping -----------------------------------------------------------------------

TEST(ToneMap, AutoOperatorInvariants) {
    AutoToneParams p;
    p.adaptation_cd_m2 = 20.0;
    p.white_cd_m2 = 400.0;
    const AutoToneMap op(p);
    EXPECT_EQ(op(0.0), 0.0);
    EXPECT_NEAR(op(400.0), 1.0, 1e-12);  // white maps to 1
    double last = 0.0;
    for (double l = 1e-4; l < 400.0; l *= 1.05) {  // strictly increasing below white
        const double v = op(l);
        EXPECT_GT(v, last) << l;
        EXPECT_LT(v, 1.0);
        last = v;
    }
    EXPECT_EQ(op(1e9), 1.0);
    for (double bad : {std::nan(""), -5.0, std::numeric_limits<double>::infinity()}) {
        const double v = op(bad);
        EXPECT_TRUE(v >= 0.0 && v <= 1.0) << bad;
    }
}

TEST(ToneMap, TwoPassEstimates) {
    const int w = 200, h = 100;
    // Half black background, half at 50 cd/m^2: pass 2 ignores the black points.
    std::vector<double> half(w * h, 0.0);
    for (int i = 0; i < w * h / 2; ++i) half[i] = 50.0;
    const AutoToneParams a = estimate_auto_tone(half, w, h);
    EXPECT_LT(a.first_adaptation_cd_m2, 1.0);
    EXPECT_NEAR(a.adaptation_cd_m2, 50.0, 1e-9);
    // Lamps at 1e6 cd/m^2 on 0.8 % of the grid points, over walls at 10: pass 1 drops
    // them, so they set neither the white level nor the adaptation.
    std::vector<double> lamps(w * h, 10.0);
    for (int x = 0; x < 80; ++x) lamps[1 * w + x] = 1e6;
    const AutoToneParams b = estimate_auto_tone(lamps, w, h);
    EXPECT_NEAR(b.adaptation_cd_m2, 10.0, 1e-9);
    EXPECT_NEAR(b.white_cd_m2, 30.0, 1e-9);  // the floor of 3 x adaptation
    // A log-uniform ramp 1..1000 across the width: the white level is its 99th percentile.
    std::vector<double> ramp(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) ramp[y * w + x] = std::pow(1000.0, (x + 0.5) / w);
    const AutoToneParams c = estimate_auto_tone(ramp, w, h);
    EXPECT_NEAR(std::log10(c.white_cd_m2), 2.97, 0.02);
}

TEST(ToneMap, ConstantImagesAndNoNaN) {
    for (double level : {1e-3, 1.0, 30.0, 5e4}) {
        LuminanceImage img(32, 16, {"Y"});
        std::fill(img.values.begin(), img.values.end(), static_cast<float>(level));
        const DisplayImage d = tone_map_auto(img, 2.2);
        for (std::uint8_t v : d.rgb) EXPECT_EQ(v, d.rgb[0]);
        EXPECT_GT(d.rgb[0], 0);
        EXPECT_LT(d.rgb[0], 255);  // a flat picture is not pushed to white
    }
    LuminanceImage odd(4, 1, {"Y"});
    odd.values = {0.0f, std::numeric_limits<float>::quiet_NaN(), 1e30f, std::numeric_limits<float>::infinity()};
    EXPECT_NO_THROW(tone_map_auto(odd, 2.2));
    LuminanceImage black(8, 8, {"Y"});
    for (std::uint8_t v : tone_map_auto(black, 2.2).rgb) EXPECT_EQ(v, 0);
}

TEST(ToneMap, ExposureAndFalseColour) {
    EXPECT_DOUBLE_EQ(exposure_map(80.0, 80.0, 2.2), 1.0);
    EXPECT_NEAR(exposure_map(40.0, 80.0, 2.2), std::pow(0.5, 1 / 2.2), 1e-12);
    EXPECT_EQ(exposure_map(800.0, 80.0, 2.2), 1.0);
    const FalseColourScale s = FalseColourScale::log_below(200.0);
    EXPECT_DOUBLE_EQ(s.position(200.0), 1.0);
    EXPECT_DOUBLE_EQ(s.position(0.2), 0.0);
    EXPECT_NEAR(s.position(std::sqrt(200.0 * 0.2)), 0.5, 1e-12);
    for (const FalseColourScale sc : {s, FalseColourScale::log_below(1.0), FalseColourScale::log_below(3e4, 2.0),
                                      FalseColourScale{0.0, 730.0, false}, FalseColourScale{10.0, 13.0, false}}) {
        const std::vector<double> t = sc.ticks();
        EXPECT_GE(t.size(), 5u) << sc.max_cd_m2;
        EXPECT_LE(t.size(), 7u) << sc.max_cd_m2;
        for (double v : t) EXPECT_TRUE(v >= sc.min_cd_m2 * (1 - 1e-9) && v <= sc.max_cd_m2 * (1 + 1e-9)) << v;
    }
    // The colour map brightens monotonically (perceptual: luma rises along the scale).
    double last = -1.0;
    for (double t = 0.0; t <= 1.0; t += 0.05) {
        const auto c = colour_map(t);
        const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        EXPECT_GT(luma, last);
        last = luma;
    }
}

// ---- Files and the command line ---------------------------------------------------------

TEST(RenderFiles, PngAndExrReadableOfTheAskedSize) {
    const fs::path dir = temp_dir();
    const fs::path result = simulate(kData / "point_plane.toml", dir, "20000");
    std::string log;
    ASSERT_EQ(run_cli("render " + result.string() + " --view oblique --size 96x64 -o " + (dir / "v.png").string(),
                      &log),
              0)
        << log;
    cairo_surface_t* png = cairo_image_surface_create_from_png((dir / "v.png").c_str());
    ASSERT_EQ(cairo_surface_status(png), CAIRO_STATUS_SUCCESS);
    EXPECT_EQ(cairo_image_surface_get_width(png), 96);
    EXPECT_EQ(cairo_image_surface_get_height(png), 64);
    cairo_surface_destroy(png);
    // The EXR holds exactly the luminance image the library renders (same seed, row 0 on top).
    Imf::InputFile exr((dir / "v.exr").c_str());
    const Imath::Box2i win = exr.header().dataWindow();
    ASSERT_EQ(win.max.x - win.min.x + 1, 96);
    ASSERT_EQ(win.max.y - win.min.y + 1, 64);
    ASSERT_NE(exr.header().channels().findChannel("Y"), nullptr);
    std::vector<float> y(96 * 64);
    Imf::FrameBuffer fb;
    fb.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float), 96 * sizeof(float)));
    exr.setFrameBuffer(fb);
    exr.readPixels(win.min.y, win.max.y);
    const RenderInput in = load_render_input(result);
    const Fixture f(in.scene, in.secondary_lx);
    Camera c = in.scene.cameras.at(0);
    c.width = 96;
    c.height = 64;
    const LuminanceImage img = f.renderer->render(PinholeCamera(c));
    EXPECT_EQ(y, img.values);
    // The top row looks farther away than the bottom row: darker.
    EXPECT_LT(img.at(48, 0, 0), img.at(48, 63, 0));
    // False colour: the legend panel is added to the right of the picture.
    ASSERT_EQ(run_cli("render " + result.string() + " --view oblique --size 96x64 --tonemap falsecolour -o " +
                          (dir / "f.png").string(),
                      &log),
              0)
        << log;
    png = cairo_image_surface_create_from_png((dir / "f.png").c_str());
    ASSERT_EQ(cairo_surface_status(png), CAIRO_STATUS_SUCCESS);
    EXPECT_EQ(cairo_image_surface_get_width(png), 96 + legend_panel_width(64));
    EXPECT_EQ(cairo_image_surface_get_height(png), 64);
    cairo_surface_destroy(png);
    fs::remove_all(dir);
}

TEST(RenderFiles, LightScenesAreTheirWeightedMapsAndLights) {
    // Two point lights in two groups over a plane with a wall (so there is reflected light
    // in the map): a light scene renders its own stored map with its lights at their
    // groups' weights, so pictures are linear in the weights: "double" is twice the run,
    // and "a_only" + "b_only" is the run, to float rounding (the same samples per pixel).
    const fs::path dir = temp_dir();
    const fs::path scene = dir / "two_groups.toml";
    std::ofstream(scene) << R"([[material]]
name = "grey"
reflectance = 0.6

[[shape]]
type = "rectangle"
size = [6, 6]
material = "grey"
subdivisions = 8

[[shape]]
type = "rectangle"
center = [0, 2, 1.5]
normal = [0, -1, 0]
size = [6, 3]
material = "grey"
subdivisions = 8

[[light]]
type = "point"
position = [0.3, -0.2, 2]
flux_lm = 1000
group = "a"

[[light]]
type = "point"
position = [-1, 1, 1.5]
flux_lm = 400
group = "b"

[[light_scene]]
name = "double"
dimming = { a = 2, b = 2 }

[[light_scene]]
name = "a_only"
dimming = { a = 1 }

[[light_scene]]
name = "b_only"
dimming = { b = 1 }

[[camera]]
name = "oblique"
position = [0, -4, 3]
target = [0, 0.5, 0.5]
up = [0, 0, 1]
fov_deg = 50
size = [48, 32]
)";
    const fs::path result = simulate(scene, dir, "40000");
    auto image = [&](const std::string& light_scene) {
        RenderInput in = load_render_input(result, light_scene);
        const Camera c = in.scene.cameras.at(0);
        const Fixture f(std::move(in.scene), std::move(in.secondary_lx), std::move(in.light_weight));
        return f.renderer->render(PinholeCamera(c)).values;
    };
    const std::vector<float> run = image(""), twice = image("double"), a = image("a_only"), b = image("b_only");
    ASSERT_EQ(run.size(), twice.size());
    double brightest = 0.0;
    for (float v : run) brightest = std::max(brightest, static_cast<double>(v));
    ASSERT_GT(brightest, 0.0);
    for (std::size_t i = 0; i < run.size(); ++i) {
        EXPECT_NEAR(twice[i], 2.0 * run[i], 1e-5 * brightest) << "pixel " << i;
        EXPECT_NEAR(a[i] + b[i], run[i], 1e-5 * brightest) << "pixel " << i;
    }
    // Both groups light the picture (each one's share is not all zero).
    EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.0f);
    EXPECT_GT(*std::max_element(b.begin(), b.end()), 0.0f);
    std::string log;
    EXPECT_EQ(run_cli("render " + result.string() + " --view oblique --scene nope -o " + (dir / "n.png").string(),
                      &log),
              2);
    EXPECT_NE(log.find("has no [[light_scene]] named 'nope' (it has: double, a_only, b_only)"), std::string::npos)
        << log;
    EXPECT_FALSE(fs::exists(dir / "n.png"));
    fs::remove_all(dir);
}

TEST(RenderFiles, ColourExrHasOneChannelPerBand) {
    const fs::path dir = temp_dir();
    const fs::path result = simulate(kData / "rgb_plane.toml", dir, "20000");
    std::string log;
    ASSERT_EQ(run_cli("render " + result.string() + " --tonemap exposure -o " + (dir / "c.exr").string(), &log), 0)
        << log;
    EXPECT_TRUE(fs::is_regular_file(dir / "c.png"));
    Imf::InputFile exr((dir / "c.exr").c_str());
    for (const char* ch : {"R", "G", "B"}) EXPECT_NE(exr.header().channels().findChannel(ch), nullptr) << ch;
    EXPECT_EQ(exr.header().channels().findChannel("Y"), nullptr);
    fs::remove_all(dir);
}

TEST(RenderCli, ViewOptionsAreCheckedWithNamedErrors) {
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    for (const char* bad : {"1,2,3", "0,0,1,0,0,1", "0,0,1,1,1,x", "0,0,1,0,0,0,0,0,0", "0,0,1,0,0,0,0,0,1,4", ""})
        EXPECT_EQ(message([&] { parse_camera_option(bad); }).rfind("--camera", 0), 0u) << bad;
    for (const char* bad : {"100", "0x10", "10x", "12.5x10", "20000x10", "axb"})
        EXPECT_EQ(message([&] { parse_size_option(bad); }).rfind("--size", 0), 0u) << bad;
    EXPECT_EQ(parse_size_option("800x500"), std::make_pair(800, 500));
    const Camera c = parse_camera_option("1,2,3,4,5,6");
    EXPECT_EQ(c.up, Vec3(0, 0, 1));
    EXPECT_EQ(c.target, Vec3(4, 5, 6));
    // Image orientation: pixel (0, 0) is the top-left corner.
    const PinholeCamera cam(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), 90.0, 200, 100);
    const Vec3 top_left = cam.direction(0, 0);
    EXPECT_GT(top_left.z, 0.0);
    EXPECT_LT(top_left.x, 0.0);
    EXPECT_NEAR(top_left.x / top_left.y, -1.0, 1e-12);  // horizontal fov 90 deg
    EXPECT_NEAR(top_left.z / top_left.y, 0.5, 1e-12);   // square pixels
}

TEST(RenderCli, BadInputExitsTwoAndWritesNothing) {
    // Each call pays the MPI start-up of the binary (about 1 s here): a few cases only.
    const fs::path dir = temp_dir();
    fs::copy_file(kData / "point_plane.toml", dir / "moved.toml");
    const fs::path result = simulate(dir / "moved.toml", dir, "5000");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    const std::string base = "render " + result.string() + " -o " + (out / "v.png").string() + " ";
    const std::pair<std::string, std::string> cases[] = {
        {"--view nosuch", "nosuch"},
        {"--camera 1,2,3", "--camera"},
        {"--view oblique --size 0x10", "--size"},
        {"--view oblique --tonemap sepia", "--tonemap"},
    };
    for (const auto& [args, word] : cases) {
        std::string log;
        EXPECT_EQ(run_cli(base + args, &log), 2) << args << "\n" << log;
        EXPECT_NE(log.find(word), std::string::npos) << args << "\n" << log;
    }
    fs::remove(dir / "moved.toml");  // the result's scene file is gone
    std::string log;
    EXPECT_EQ(run_cli(base + "--view oblique", &log), 2) << log;
    EXPECT_NE(log.find("scene file"), std::string::npos) << log;
    EXPECT_TRUE(fs::is_empty(out));
    fs::remove_all(dir);
}
