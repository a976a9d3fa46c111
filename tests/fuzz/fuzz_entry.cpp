// Entry functions of the fuzz targets; see fuzz_entry.hpp and tests/fuzz/README.md.
#include "fuzz_entry.hpp"

#include "app/result_summary.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/detector/pts_file.hpp"
#include "luxtrace/detector/sensor_points.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/light/ies.hpp"
#include "luxtrace/light/luminaire_file.hpp"
#include "luxtrace/light/luminous_opening.hpp"
#include "luxtrace/render/camera.hpp"
#include "luxtrace/render/renderer.hpp"
#include "luxtrace/render/tone_map.hpp"
#include "luxtrace/scene/radiance_luminaire.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "luxtrace/scene/radiance_reader.hpp"
#include "luxtrace/scene/radiance_sky.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/weather/weather_file.hpp"

#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

namespace luxtrace::fuzz {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------ fixed small files
// Valid files that fuzzed scenes may name by relative path.
constexpr std::string_view kCubeObj = R"(mtllib cube.mtl
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
f 1 4 3 2
f 5 6 7 8
usemtl red
f 1 5 8 4
f 2 3 7 6
usemtl grey
f 1 2 6 5
f 4 8 7 3
)";
constexpr std::string_view kCubeMtl = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl grey\nKd 0.5 0.5 0.5\n";
constexpr std::string_view kTriPly = R"(ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
3 0 1 2
3 0 2 3
)";
constexpr std::string_view kLightIes = R"(IESNA:LM-63-2002
[TEST] fuzz fixture
TILT=NONE
1 1000 1 5 3 1 2 0.1 0.1 0
1 0 20
0 45 90 135 180
0 90 180
300 250 120 10 0
300 240 100 5 0
300 230 90 0 0
)";

// A Radiance file that fuzzed .rad inputs may include with !xform.
constexpr std::string_view kPartRad = R"(void plastic grey
0
0
5 .5 .5 .5 0 0
grey polygon floor
0
0
12 0 0 0 1 0 0 1 1 0 0 1 0
grey sphere ball
0
0
4 .5 .5 .5 .2
)";

// An ies2rad data file (candela / 179; src_phi4 by src_theta) that fuzzed brightdata
// patterns may name; the folder of input.rad is searched first.
constexpr std::string_view kPartDat = R"(2
0 90 3
0 180 5
1.2 1.0 0.6 0.2 0
1.2 0.9 0.5 0.1 0
1.2 0.8 0.4 0.05 0
)";

// The scene of the result target's seeds (tests/fuzz/make_result_seeds.sh writes results
// of it): `render` reloads the scene named in a result, so it lives at a fixed path.
constexpr std::string_view kResultSceneDir = "/tmp/luxtrace-fuzz-result-scene";
constexpr std::string_view kResultScene = R"([scene]
bands = ["R", "G", "B"]
[[material]]
name = "wall"
reflectance = [0.6, 0.5, 0.4]
[[material]]
name = "mirror"
type = "mirror"
specular_reflectance = 0.8
[[material]]
name = "emitter"
type = "black"
[[shape]]
type = "box"
center = [1, 1, 1]
size = [2, 2, 2]
inward = true
material = "wall"
[[shape]]
type = "rectangle"
center = [0.5, 1, 0.01]
normal = [0, 0, 1]
size = [0.5, 0.5]
material = "mirror"
[[shape]]
name = "panel"
type = "rectangle"
center = [1, 1, 1.99]
normal = [0, 0, -1]
size = [0.4, 0.4]
material = "emitter"
[[light]]
type = "point"
position = [1.5, 1.5, 1.5]
ies = "light.ies"
[[light]]
type = "area"
shape = "panel"
flux_lm = 500
colour = [1, 0.8, 0.6]
[[detector]]
name = "floor"
center = [1, 1, 0.05]
size = [1.6, 1.6]
cells = [4, 3]
[[detector]]
name = "wall"
type = "luminance"
center = [0.02, 1, 1]
normal = [1, 0, 0]
up = [0, 0, 1]
size = [1.5, 1.5]
cells = [3, 2]
half_angle_deg = 20
[[camera]]
name = "view"
position = [1.8, 0.2, 1.6]
target = [0.5, 1.5, 0.5]
size = [12, 8]
[run]
seed = 5
photons = 2000
)";

// One band, targets (so /history has target columns) and a spot and a directional light.
constexpr std::string_view kResultSceneY = R"([[material]]
name = "wall"
reflectance = 0.5
[[material]]
name = "glass"
type = "glass"
ior = 1.5
[[shape]]
type = "box"
center = [0, 0, 1]
size = [2, 2, 2]
inward = true
material = "wall"
[[shape]]
type = "sphere"
center = [0, 0, 0.5]
radius = 0.3
subdivisions = 3
material = "glass"
[[light]]
type = "spot"
position = [0, 0, 1.9]
direction = [0, 0, -1]
half_angle_deg = 40
flux_lm = 1000
[[light]]
type = "point"
position = [0.5, 0.5, 1.5]
flux_lm = 300
[[detector]]
name = "desk"
center = [0, 0, 0.8]
size = [1, 1]
cells = [5, 5]
[[camera]]
name = "top"
position = [0.9, -0.9, 1.8]
target = [0, 0, 0.5]
size = [8, 6]
[run]
seed = 7
photons = 3000
[[run.target]]
on = "detector:desk"
relative_error = 0.5
[[run.target]]
on = "detector:desk[1:3,1:3]"
photons_received = 1000000000000
)";

void write_file(const fs::path& p, std::string_view text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) {
        std::cerr << "fuzz: cannot write " << p << '\n';
        std::abort();
    }
}

// Written through a temporary name and renamed: other fuzzing processes may read it.
void publish_file(const fs::path& p, std::string_view text) {
    const fs::path tmp = p.string() + ".tmp" + std::to_string(::getpid());
    write_file(tmp, text);
    fs::rename(tmp, p);
}

// The process's private folder, removed at exit.
const fs::path& private_dir() {
    static const fs::path dir = [] {
        std::string templ = (fs::temp_directory_path() / "luxtrace-fuzz-XXXXXX").string();
        if (::mkdtemp(templ.data()) == nullptr) {
            std::perror("fuzz: mkdtemp");
            std::abort();
        }
        const fs::path d = templ;
        write_file(d / "cube.obj", kCubeObj);
        write_file(d / "cube.mtl", kCubeMtl);
        write_file(d / "tri.ply", kTriPly);
        write_file(d / "light.ies", kLightIes);
        write_file(d / "part.rad", kPartRad);
        write_file(d / "part.dat", kPartDat);
        std::atexit([] {
            std::error_code ec;
            fs::remove_all(private_dir(), ec);
        });
        return d;
    }();
    return dir;
}

fs::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
    const fs::path p = private_dir() / name;
    write_file(p, std::string_view(reinterpret_cast<const char*>(data), size));
    return p;
}

[[noreturn]] void broken(const std::string& what) {
    std::cerr << "fuzz: invariant broken: " << what << '\n';
    std::abort();
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the rest of luxtrace relies on in a scene that load_scene accepted.
void check_scene(const Scene& s) {
    if (s.bands.empty()) broken("no bands");
    const std::size_t T = s.triangles.size(), V = s.vertices.size();
    if (T == 0) broken("no triangles");
    if (s.triangle_material.size() != T || s.triangle_area_m2.size() != T || s.triangle_normal.size() != T)
        broken("per-triangle arrays differ in size");
    for (const auto& v : s.vertices)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) broken("vertex not finite");
    for (std::size_t t = 0; t < T; ++t) {
        for (int k = 0; k < 3; ++k)
            if (s.triangles[t][k] >= V)
                broken("triangle " + std::to_string(t) + " names vertex " + std::to_string(s.triangles[t][k]) + " of " +
                       std::to_string(V));
        if (s.triangle_material[t] >= s.materials.size()) broken("material index out of range");
        if (!(s.triangle_area_m2[t] > 0.0 && std::isfinite(s.triangle_area_m2[t]))) broken("bad triangle area");
        if (!finite(s.triangle_normal[t])) broken("normal not finite");
    }
    if (!finite(s.bounds_min) || !finite(s.bounds_max)) broken("bounds not finite");
    if (!std::isfinite(s.ray_epsilon_m())) broken("ray epsilon not finite");
    const double total = s.lights.total_flux_lm();
    if (!(total > 0.0 && std::isfinite(total))) broken("total flux " + std::to_string(total));
    for (const Light& l : s.lights.lights()) {
        if (!(l.flux_lm > 0.0 && std::isfinite(l.flux_lm))) broken(l.label + ": flux " + std::to_string(l.flux_lm));
        if (l.band_share.size() != s.bands.size()) broken(l.label + ": band shares");
        for (double c : l.band_share)
            if (!(c >= 0.0 && c <= 1.0)) broken(l.label + ": band share " + std::to_string(c));
        const AreaLight* area = l.as<AreaLight>();
        if (area != nullptr && !(area->surface.area_m2 > 0.0 && std::isfinite(area->surface.area_m2)))
            broken(l.label + ": emitter area " + std::to_string(area->surface.area_m2));
        const PointLight* point = l.as<PointLight>();
        if (point != nullptr && point->distribution &&
            !(point->distribution->flux_lm() > 0.0 && std::isfinite(point->distribution->flux_lm())))
            broken(l.label + ": sampling table flux");
        // A few emitted rays must be finite.
        for (int k = 0; k < 4; ++k) {
            const double u = (k + 0.5) / 4.0;
            const EmittedRay ray = l.emit(u, 1.0 - u, u * u, 0.37);
            if (!finite(ray.origin) || !finite(ray.direction)) broken(l.label + ": emitted ray not finite");
        }
    }
    for (const Detector& d : s.detectors) {
        if (!(d.nx >= 1 && d.ny >= 1 && static_cast<double>(d.nx) * d.ny <= 1e8)) broken("detector cells");
        if (!std::isfinite(d.value_per_lm())) broken("detector " + d.name + ": value per lm not finite");
    }
    for (const Camera& c : s.cameras)
        if (!(c.width >= 1 && c.height >= 1 && c.width <= 16384 && c.height <= 16384)) broken("camera size");
    for (const Observer& o : s.observers) {
        if (o.eye_detector >= s.detectors.size() || !s.detectors[o.eye_detector].indirect_only)
            broken("observer " + o.name + ": eye detector");
        for (const GlareSource& g : o.sources)
            if (!(g.luminance_cd_m2 >= 0.0 && g.solid_angle_sr > 0.0 && g.position_index >= 1.0 &&
                  std::isfinite(g.term())))
                broken("observer " + o.name + ": " + g.label + ": UGR term not finite");
    }
}

// Runs `f`; InputError is the expected answer to bad input.
template <class F>
void expect_input_error_only(F&& f) {
    try {
        f();
    } catch (const InputError&) {
    }
}

void quiet_hdf5() {
    static const bool once = [] {
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the error stacks are noise here
        return true;
    }();
    (void)once;
}

// Every HDF5 object a reader opened must be closed again.
void check_hdf5_closed(const char* after) {
    const ssize_t open = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
    if (open != 0) broken(std::to_string(open) + " HDF5 objects left open after " + after);
}

const fs::path& result_scene_dir() {
    static const fs::path dir = [] {
        const fs::path d(kResultSceneDir);
        std::error_code ec;
        fs::create_directories(d, ec);
        publish_file(d / "scene.toml", kResultScene);
        publish_file(d / "scene_y.toml", kResultSceneY);
        publish_file(d / "light.ies", kLightIes);
        return d;
    }();
    return dir;
}

}  // namespace

int fuzz_scene(const std::uint8_t* data, std::size_t size) {
    const fs::path file = write_input("scene.toml", data, size);
    expect_input_error_only([&] { check_scene(load_scene(file)); });
    return 0;
}

int fuzz_ies(const std::uint8_t* data, std::size_t size) {
    // Either format, told apart by content as the scene loader does.
    const fs::path file = write_input("input.ies", data, size);
    Photometry p;
    try {
        p = load_photometry(file);
    } catch (const InputError&) {
        return 0;
    }
    if (p.type == PhotometricType::C) {
        const CPlaneSymmetry sym = p.symmetry();  // std::logic_error if load_ies let a bad layout through
        (void)sym;
    }
    const double flux = p.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux))) broken("accepted photometry has flux " + std::to_string(flux));
    for (int g = 0; g <= 12; ++g)
        for (int c = 0; c < 8; ++c) {
            const double gr = g * kPi / 12.0, cr = c * kPi / 4.0 - 1.0;
            const double v = p.intensity_cd(
                Vec3(std::sin(gr) * std::cos(cr), std::sin(gr) * std::sin(cr), std::cos(gr)));
            if (!(v >= 0.0 && std::isfinite(v))) broken("intensity " + std::to_string(v));
        }
    // Start points on the luminous opening stay finite and inside its bounding box.
    for (int k = 0; k < 8; ++k) {
        const double a = 0.7 * k, b = 0.3 + 0.4 * k;
        const Vec3 d = glm::normalize(Vec3(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b)));
        const Vec3 q = sample_opening_point(p.opening, d, (k + 0.5) / 8.0, std::fmod(0.37 * k, 1.0));
        const Vec3 half(0.5 * p.opening.length_m, 0.5 * p.opening.width_m, 0.5 * p.opening.height_m);
        if (!finite(q) || std::abs(q.x) > half.x * (1 + 1e-9) + 1e-12 || std::abs(q.y) > half.y * (1 + 1e-9) + 1e-12 ||
            std::abs(q.z) > half.z * (1 + 1e-9) + 1e-12)
            broken("opening point outside the opening");
    }
    // The scene loader builds the sampling table of a light's photometry; a coarse one
    // here keeps the target fast. No light on the grid's directions is a documented
    // std::invalid_argument, which load_scene turns into an InputError.
    try {
        const PhotometryDistribution dist(p, 24, 48);
        for (int k = 0; k < 16; ++k) {
            const Vec3 d = dist.sample((k + 0.5) / 16.0, std::fmod(0.618 * k, 1.0));
            if (!finite(d) || std::abs(glm::length(d) - 1.0) > 1e-9) broken("sampled direction");
        }
    } catch (const std::invalid_argument&) {
    }
    return 0;
}

int fuzz_mesh(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string ext = (data[0] & 1) ? ".ply" : ".obj";
    write_input("input" + ext, data + 1, size - 1);
    std::string scene = "[[material]]\nname = \"m\"\nreflectance = 0.5\n"
                        "[[material]]\nname = \"red\"\nreflectance = 0.7\n"
                        "[[mesh]]\nfile = \"input" +
                        ext +
                        "\"\nmaterial = \"m\"\n"
                        "[[light]]\ntype = \"point\"\nposition = [0.2, 0.3, 2]\nflux_lm = 100\n";
    const fs::path file = write_input("mesh_scene.toml", reinterpret_cast<const std::uint8_t*>(scene.data()),
                                      scene.size());
    expect_input_error_only([&] { check_scene(load_scene(file)); });
    return 0;
}

int fuzz_result(const std::uint8_t* data, std::size_t size) {
    quiet_hdf5();
    result_scene_dir();
    // A new name each time: HDF5 identifies an open file by its inode, so a file that a
    // leaked handle still holds open must never be mistaken for the next input.
    static unsigned long serial = 0;
    const fs::path file = write_input("input" + std::to_string(serial++) + ".h5", data, size);

    // luxtrace info
    expect_input_error_only([&] {
        std::ostringstream out;
        print_result_summary(ResultFile(file), out);
    });
    check_hdf5_closed("info");
    // luxtrace run --restart: main.cpp's checks, then the simulation's read_checkpoint.
    expect_input_error_only([&] {
        {
            const ResultFile ck(file);
            if (ck.is_checkpoint()) (void)ck.checkpoint_budget();
        }
        const CheckpointState s = read_checkpoint(file);
        if (s.tallies.size() != s.layout_size || s.done.size() % 2 != 0) broken("checkpoint sizes");
        for (const HistoryRow& row : s.history)
            if (row.target_value.size() != row.target_forecast_s.size() ||
                row.target_value.size() != row.target_forecast_photons.size())
                broken("history row sizes");
    });
    check_hdf5_closed("restart");
    // luxtrace render: the views (small, one sample per pixel) and the detector pictures.
    expect_input_error_only([&] {
        RenderInput in = load_render_input(file);
        const EmbreeScene embree(in.scene);
        const Renderer renderer(in.scene, embree, std::move(in.secondary_lx));
        RenderOptions opt;
        opt.samples = 1;
        opt.threads = 1;
        opt.area_light_samples = 2;
        for (Camera c : in.scene.cameras) {
            c.width = std::min(c.width, 12);
            c.height = std::min(c.height, 8);
            const LuminanceImage image = renderer.render(PinholeCamera(c), opt);
            AutoToneParams tone;
            (void)tone_map_auto(image, 2.2, &tone);
            (void)tone_map_exposure(image, tone.white_cd_m2, 2.2);
            (void)tone_map_false_colour(image, FalseColourScale::log_below(tone.white_cd_m2));
        }
    });
    check_hdf5_closed("render");
    std::error_code ec;
    fs::remove(file, ec);
    return 0;
}

int fuzz_weather(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string ext = (data[0] & 1) ? ".wea" : ".epw";
    const fs::path file = write_input("input" + ext, data + 1, size - 1);
    weather::WeatherFile w;
    try {
        w = weather::read_weather_file(file.string());
    } catch (const InputError&) {
        return 0;
    }
    // What a read file promises: hours, in the calendar, each value missing (NaN) or
    // inside its physical range.
    if (w.hours.empty()) broken("weather file read with no hours");
    if (!(std::abs(w.site.latitude_deg) <= 90.0 && std::abs(w.site.longitude_deg) <= 180.0))
        broken("site out of range");
    for (const auto& h : w.hours) {
        if (h.month < 1 || h.month > 12 || h.day < 1 || h.day > 31 || !(h.hour >= 0.0 && h.hour <= 24.0))
            broken("hour outside the calendar");
        for (double v : {h.global_horizontal_w_m2, h.direct_normal_w_m2, h.diffuse_horizontal_w_m2,
                         h.global_horizontal_lx, h.direct_normal_lx, h.diffuse_horizontal_lx})
            if (v < 0.0 || std::isinf(v)) broken("irradiance or illuminance " + std::to_string(v));
    }
    return 0;
}

int fuzz_pts(const std::uint8_t* data, std::size_t size) {
    const fs::path file = write_input("input.pts", data, size);
    SensorPointList p;
    try {
        p = read_pts(file.string());
    } catch (const InputError&) {
        return 0;
    }
    // What a read file promises: sensors with finite positions and unit directions; the
    // lookup built on them (the default radius, or the loader's fallback) returns valid
    // sensors, and a ray straight at a sensor crosses its disc.
    if (p.positions.empty() || p.positions.size() != p.directions.size() || p.lines.size() != p.positions.size())
        broken("pts read with no sensor or mismatched lists");
    for (std::size_t k = 0; k < p.positions.size(); ++k) {
        const Vec3 &x = p.positions[k], &d = p.directions[k];
        if (!(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z))) broken("non-finite sensor position");
        if (!(std::abs(glm::length(d) - 1.0) < 1e-9)) broken("sensor direction not a unit vector");
    }
    double radius = SensorPoints::half_smallest_spacing_m(p.positions, p.directions);
    if (!(radius > 0.0)) radius = 0.1;
    const SensorPoints sensors(p.positions, p.directions, radius);
    std::vector<int> cells;
    for (std::size_t k = 0; k < std::min<std::size_t>(p.positions.size(), 64); ++k) {
        // Straight at sensor k from in front of it: it must be among the crossed discs.
        const Vec3 o = p.positions[k] + p.directions[k];
        cells.clear();
        sensors.crossings(o, -p.directions[k], 2.0, Vec3(0.0), 1e-4, cells);
        for (int c : cells)
            if (c < 0 || static_cast<std::size_t>(c) >= p.positions.size()) broken("sensor index out of range");
        // (Rounding of coordinates up to 1e9 m may move the crossing by ~1e-7 m.)
        if (radius > 1e-6 && std::find(cells.begin(), cells.end(), static_cast<int>(k)) == cells.end())
            broken("a ray straight at a sensor misses its disc");
    }
    return 0;
}

namespace {

// What map_radiance_modifier promises of a mapping for `nb` bands: probabilities per band
// in [0, 1] that sum to at most 1, a roughness WardLobe takes (with its lobe), finite
// non-negative luminances, and a glazing whose curve reflects and transmits in [0, 1].
void check_radiance_mapping(const RadianceMapping& r, std::size_t nb) {
    const Material& mat = r.material;
    const std::string who = "modifier " + mat.name + ": ";
    (void)r.describe();
    if (r.role == RadianceRole::light) {
        if (r.luminance_cd_m2.size() != nb) broken(who + "luminances per band");
        for (const double L : r.luminance_cd_m2)
            if (!(L >= 0.0 && std::isfinite(L))) broken(who + "luminance " + std::to_string(L));
    }
    if (r.role == RadianceRole::ignored) return;
    const std::vector<double>* probabilities[] = {&mat.diffuse_reflectance, &mat.specular_reflectance,
                                                  &mat.diffuse_transmittance, &mat.specular_transmittance,
                                                  &mat.transmittance};
    for (const std::vector<double>* v : probabilities) {
        if (!v->empty() && v->size() != nb) broken(who + "a per-band list of " + std::to_string(v->size()));
        for (const double x : *v)
            if (!(x >= 0.0 && x <= 1.0)) broken(who + "reflectance or transmittance " + std::to_string(x));
    }
    for (std::size_t b = 0; b < nb; ++b) {
        double sum = 0.0;
        for (std::size_t k = 0; k < 4; ++k)
            if (!probabilities[k]->empty()) sum += (*probabilities[k])[b];
        if (!(sum <= 1.0 + 1e-9)) broken(who + "reflectances and transmittances sum to " + std::to_string(sum));
    }
    if (!(mat.roughness >= 0.0 && mat.roughness <= WardLobe::kMaxRoughness))
        broken(who + "roughness " + std::to_string(mat.roughness));
    if ((mat.roughness > 0.0) != (mat.lobe != nullptr)) broken(who + "roughness without its lobe");
    if (mat.type == MaterialType::glass || mat.type == MaterialType::glazing) {
        if (!(mat.ior > 0.0 && std::isfinite(mat.ior))) broken(who + "refractive index " + std::to_string(mat.ior));
        if (mat.transmittance.size() != nb) broken(who + "transmittance per band");
    }
    if (mat.type == MaterialType::glazing) {
        if (!mat.glazing || mat.glazing->size() != nb) broken(who + "glazing curves per band");
        for (const GlazingCurve& c : *mat.glazing)
            for (const double cos_i : {0.0, 0.01, 0.3, 0.7, 1.0}) {
                const PaneOptics o = c.at(cos_i);
                if (!(o.reflectance >= 0.0 && o.transmittance >= 0.0 && o.reflectance + o.transmittance <= 1.0 + 1e-9))
                    broken(who + "glazing R " + std::to_string(o.reflectance) + " T " +
                           std::to_string(o.transmittance) + " at cos " + std::to_string(cos_i));
            }
    }
}

// What map_radiance_sky promises: the `[[light]]` keys of a sky and a sun.
void check_radiance_sky(const RadianceSky& s) {
    const RadianceSkyLight& k = s.sky;
    const std::string who = "sky '" + s.command + "': ";
    (void)s.describe();
    auto angles = [&](double altitude, double azimuth) {
        if (!(altitude >= -90.0 && altitude <= 90.0)) broken(who + "sun altitude " + std::to_string(altitude));
        if (!(azimuth >= 0.0 && azimuth <= 360.0)) broken(who + "sun azimuth " + std::to_string(azimuth));
    };
    auto non_negative = [&](double x, const char* what) {
        if (!(x >= 0.0 && std::isfinite(x))) broken(who + what + " " + std::to_string(x));
    };
    if (k.sky != "cie" && k.sky != "perez" && k.sky != "uniform") broken(who + "kind '" + k.sky + "'");
    if (k.sky == "cie" && k.cie_type != 12 && k.cie_type != 7 && k.cie_type != 16)
        broken(who + "CIE type " + std::to_string(k.cie_type));
    const bool perez = k.sky == "perez";
    if (perez ? (k.zenith_luminance_cd_m2 || k.diffuse_horizontal_lx)
              : (k.zenith_luminance_cd_m2.has_value() == k.diffuse_horizontal_lx.has_value()))
        broken(who + "brightness keys");
    if (k.zenith_luminance_cd_m2) non_negative(*k.zenith_luminance_cd_m2, "zenith luminance");
    if (k.diffuse_horizontal_lx) non_negative(*k.diffuse_horizontal_lx, "diffuse horizontal illuminance");
    non_negative(k.diffuse_horizontal_w_m2, "diffuse horizontal irradiance");
    non_negative(k.direct_normal_w_m2, "direct normal irradiance");
    if (!std::isfinite(k.dew_point_c)) broken(who + "dew point");
    angles(k.sun_altitude_deg, k.sun_azimuth_deg);
    if (!(k.ground_reflectance >= 0.0 && k.ground_reflectance <= 1.0))
        broken(who + "ground reflectance " + std::to_string(k.ground_reflectance));
    if (s.sun) {
        non_negative(s.sun->direct_normal_lx, "sun's direct normal illuminance");
        angles(s.sun->sun_altitude_deg, s.sun->sun_azimuth_deg);
    }
}

// What radiance_luminaire promises: a positive finite flux, placed at a finite position
// in an orthonormal frame (b = t x n), emitted by existing surfaces.
void check_radiance_luminaire(const RadianceModel& m, std::size_t brightdata, const RadianceLuminaire& l) {
    const std::string who = "luminaire " + l.name + ": ";
    if (l.name != m.modifiers[brightdata].name) broken(who + "named after another modifier");
    const double flux = l.photometry.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux))) broken(who + "flux " + std::to_string(flux));
    if (!finite(l.position_m)) broken(who + "position not finite");
    const Frame& f = l.frame;
    for (const Vec3& v : {f.t, f.b, f.n})
        if (!(std::abs(glm::length(v) - 1.0) < 1e-9)) broken(who + "frame axis not of unit length");
    if (!(std::abs(glm::dot(f.t, f.n)) < 1e-9) || !(glm::length(f.b - glm::cross(f.t, f.n)) < 1e-9))
        broken(who + "frame not orthonormal");
    if (l.surfaces.empty()) broken(who + "no emitting surface");
    for (const std::size_t s : l.surfaces)
        if (s >= m.surfaces.size()) broken(who + "surface index out of range");
    (void)l.photometry.symmetry();  // std::logic_error for a table that fits no rule
    for (const Vec3& d : {Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0.6, 0.48, -0.64), Vec3(-0.6, -0.8, 0)}) {
        const double i = l.photometry.intensity_cd(d);
        if (!(i >= 0.0 && std::isfinite(i))) broken(who + "intensity " + std::to_string(i));
    }
}

}  // namespace

int fuzz_radiance(const std::uint8_t* data, std::size_t size) {
    const fs::path file = write_input("input.rad", data, size);
    RadianceModel m;
    RadianceOptions options;
    options.chord_tolerance = 0.05;  // coarse: many curved surfaces stay quick
    try {
        m = read_radiance(file, options);
    } catch (const InputError&) {
        return 0;
    }
    // What a read model promises: triangles naming existing vertices, finite vertices,
    // one material per triangle that is a material record, surfaces covering the
    // triangles in order, unit source directions.
    if (m.triangle_modifier.size() != m.mesh.triangles.size()) broken("per-triangle modifiers differ in size");
    for (const Vec3& v : m.mesh.vertices)
        if (!finite(v)) broken("vertex not finite");
    for (std::size_t t = 0; t < m.mesh.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k)
            if (m.mesh.triangles[t][k] >= m.mesh.vertices.size()) broken("triangle names a missing vertex");
        if (m.triangle_modifier[t] >= m.modifiers.size()) broken("triangle modifier out of range");
    }
    std::size_t next = 0;
    for (const RadianceSurface& s : m.surfaces) {
        if (s.first_triangle != next) broken("surfaces do not cover the triangles in order");
        next += s.triangle_count;
        if (s.modifier < 0 || static_cast<std::size_t>(s.modifier) >= m.modifiers.size()) broken("surface modifier");
    }
    if (next != m.mesh.triangles.size()) broken("surfaces do not cover the triangles");
    for (const RadianceSource& src : m.sources)
        if (!(std::abs(glm::length(src.direction) - 1.0) < 1e-9) || !(src.angle_deg > 0.0))
            broken("source direction or angle");
    for (std::size_t k = 0; k < m.modifiers.size(); ++k) {
        expect_input_error_only([&] { check_radiance_mapping(map_radiance_modifier(m, k, {"Y"}), 1); });
        expect_input_error_only([&] { check_radiance_mapping(map_radiance_modifier(m, k, {"R", "G", "B"}), 3); });
    }
    for (const RadianceCommand& cmd : m.sky_commands)
        expect_input_error_only([&] { check_radiance_sky(map_radiance_sky(m, cmd)); });
    for (const std::size_t b : radiance_luminaire_modifiers(m)) {
        if (b >= m.modifiers.size() || m.modifiers[b].type != "brightdata") broken("luminaire modifier");
        expect_input_error_only([&] { check_radiance_luminaire(m, b, radiance_luminaire(m, b)); });
    }
    return 0;
}

Entry entry_by_name(const std::string& name) {
    if (name == "scene") return fuzz_scene;
    if (name == "ies") return fuzz_ies;
    if (name == "mesh") return fuzz_mesh;
    if (name == "result") return fuzz_result;
    if (name == "weather") return fuzz_weather;
    if (name == "pts") return fuzz_pts;
    if (name == "radiance") return fuzz_radiance;
    return nullptr;
}

}  // namespace luxtrace::fuzz
