#include "luxtrace/render/renderer.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/light/portal.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace luxtrace {

namespace fs = std::filesystem;

// SplitMix64: each pixel's random numbers depend only on (seed, pixel), never on the thread.
struct Renderer::Rng {
    std::uint64_t state;
    explicit Rng(std::uint64_t s) : state(s) {}
    std::uint64_t next_u64() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double next() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
};

namespace {

using Weights = double[Renderer::kMaxBands];

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2.0 * glm::dot(d, n) * n; }

double radical_inverse2(std::uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return static_cast<double>(i) * 0x1.0p-32;
}

// Start of a ray leaving a surface (unit normal n) along dir: on the ray's own line, at
// height eps above the surface, so reflected and refracted rays stay exact (the distance
// along the ray is capped for grazing directions).
Vec3 leave(const Vec3& p, const Vec3& n, const Vec3& dir, double eps) {
    const double c = std::abs(glm::dot(dir, n));
    return p + std::min(eps / std::max(c, 1e-12), 100.0 * eps) * dir;
}

double band_value(const std::vector<double>& v, int b) { return v.empty() ? 0.0 : v[static_cast<std::size_t>(b)]; }

bool any_positive(const std::vector<double>& v) {
    return std::any_of(v.begin(), v.end(), [](double x) { return x > 0.0; });
}

// A specular branch of a transparent surface: its per-band factor (empty: k0 alone) and
// its direction.
struct SpecularBranch {
    std::vector<double> k;
    double k0 = 1.0;
    Vec3 direction{0.0};
};

// Glass: Fresnel reflection and the refracted rest (times its transmittance); glazing, a
// thin pane: the mirror branch and the straight-through branch, per band.
std::vector<SpecularBranch> transparent_branches(const Material& m, const Vec3& d, const Vec3& n, bool front,
                                                 int bands) {
    std::vector<SpecularBranch> out;
    if (m.type == MaterialType::glass) {
        const double eta = front ? 1.0 / m.ior : m.ior;  // entering through the front side
        const double cos_i = -glm::dot(d, n);
        const double r = fresnel_dielectric(cos_i, eta);
        out.push_back({{}, r, reflect(d, n)});
        if (r < 1.0) {
            const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
            const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
            out.push_back({m.transmittance, 1.0 - r, glm::normalize(eta * d + (eta * cos_i - cos_t) * n)});
        }
        return out;
    }
    if (!m.glazing) return out;
    std::vector<double> r(static_cast<std::size_t>(bands)), t(static_cast<std::size_t>(bands));
    for (std::size_t b = 0; b < r.size(); ++b) {
        const PaneOptics o = (*m.glazing)[b].at(-glm::dot(d, n));
        r[b] = o.reflectance;
        t[b] = o.transmittance;
    }
    out.push_back({std::move(r), 1.0, reflect(d, n)});
    out.push_back({std::move(t), 1.0, d});
    return out;
}

}  // namespace

Renderer::Renderer(const Scene& scene, const EmbreeScene& embree, std::vector<double> secondary_lx,
                   std::vector<double> light_weight)
    : scene_(scene), embree_(embree), bands_(scene.band_count()), eps_(4.0 * scene.ray_epsilon_m()),
      shadow_(scene, embree, eps_), light_weight_(std::move(light_weight)) {
    if (light_weight_.empty()) light_weight_.assign(scene.lights.lights().size(), 1.0);
    if (light_weight_.size() != scene.lights.lights().size()) throw std::logic_error("Renderer: one weight per light");
    if (bands_ > kMaxBands)
        throw InputError(scene.file.string() + ": rendering supports up to " + std::to_string(kMaxBands) + " bands");
    const std::size_t T = scene.triangle_count(), B = static_cast<std::size_t>(bands_);
    constexpr std::size_t kS = TallyLayout::kSides;
    if (!secondary_lx.empty() && secondary_lx.size() != T * kS * B)
        throw std::invalid_argument("Renderer: secondary map has the wrong size");
    // Per-vertex values of each side: area-weighted mean over the triangles sharing the
    // vertex index (the same side of each: a mesh's triangles share their winding).
    if (!secondary_lx.empty()) {
        std::vector<double> area(scene.vertices.size(), 0.0);
        vertex_secondary_.assign(scene.vertices.size() * kS * B, 0.0);
        for (std::size_t t = 0; t < T; ++t)
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = scene.triangles[t][k];
                area[v] += scene.triangle_area_m2[t];
                for (std::size_t i = 0; i < kS * B; ++i)
                    vertex_secondary_[v * kS * B + i] += scene.triangle_area_m2[t] *
                                                         std::max(0.0, secondary_lx[t * kS * B + i]);
            }
        for (std::size_t v = 0; v < area.size(); ++v)
            if (area[v] > 0.0)
                for (std::size_t i = 0; i < kS * B; ++i) vertex_secondary_[v * kS * B + i] /= area[v];
    }
    emitter_of_.assign(T, -1);
    const auto& lights = scene.lights.lights();
    emitted_radiance_.assign(lights.size() * B, 0.0);
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        const AreaLight* area = l.as<AreaLight>();
        if (area == nullptr || !(area->surface.area_m2 > 0.0)) continue;
        for (int t : area->surface.scene_triangle) emitter_of_[static_cast<std::size_t>(t)] = static_cast<int>(i);
        for (std::size_t b = 0; b < B; ++b)  // Lambertian: L = M / pi, M = flux / area
            emitted_radiance_[i * B + b] = light_weight_[i] * l.flux_lm * l.band_share[b] /
                                           (kPi * area->surface.area_m2);
    }
}

void Renderer::direct(const Vec3& p, const Vec3& n, Rng& rng, const RenderOptions& opt, double* e) const {
    const Vec3 o = p + eps_ * n;  // leave the surface on the lit side
    const auto& lights = scene_.lights.lights();
    for (std::size_t li = 0; li < lights.size(); ++li) {
        const Light& l = lights[li];
        if (light_weight_[li] == 0.0) continue;  // a light scene's weight of its group
        double sum[kMaxBands];
        if (!direct_from(l, p, n, o, rng, opt, sum)) continue;
        for (int b = 0; b < bands_; ++b) e[b] += light_weight_[li] * sum[b] * l.band_share[static_cast<std::size_t>(b)];
    }
}

bool Renderer::direct_from(const Light& l, const Vec3& p, const Vec3& n, const Vec3& o, Rng& rng,
                           const RenderOptions& opt, double* sum) const {
    // Stratified samples of the light arriving at p (light.hpp), each times what a shadow
    // ray lets through: for a light's point, up to it (stopping short of an emitter);
    // through a portal, also from the opening out to the sky (the tracer's ray back out).
    const IncidentSampling plan = l.incident_sampling(std::max(1, opt.area_light_samples));
    if (plan.count == 0) return false;
    std::fill(sum, sum + bands_, 0.0);
    double share[kMaxBands], beyond[kMaxBands];
    for (int k = 0; k < plan.count; ++k) {
        const double u1 = plan.random ? (k + rng.next()) / plan.count : 0.0;
        const double u2 = plan.random ? rng.next() : 0.0;
        IncidentLight in;
        if (!l.incident(p, n, u1, u2, plan.count, in)) continue;
        if (!in.distant && !(in.distance_m > 2.0 * eps_)) continue;  // the light's own point
        const double far = in.distant ? std::numeric_limits<double>::infinity()
                                      : glm::length(in.end - o) - in.end_margin * eps_;
        if (!shadow_.passes(o, in.direction, far, share)) continue;
        if (in.beyond_opening && !shadow_.passes(in.end + eps_ * in.opening_outward, in.direction,
                                                 std::numeric_limits<double>::infinity(), beyond))
            continue;
        for (int b = 0; b < bands_; ++b) sum[b] += in.illuminance_lx * share[b] * (in.beyond_opening ? beyond[b] : 1.0);
    }
    return true;
}

std::vector<double> Renderer::secondary_at(std::size_t tri, std::size_t side, const Vec3& p) const {
    std::vector<double> e(static_cast<std::size_t>(bands_), 0.0);
    add_secondary(tri, side, p, e.data());
    return e;
}

void Renderer::add_secondary(std::size_t tri, std::size_t side, const Vec3& p, double* e) const {
    if (vertex_secondary_.empty()) return;
    const glm::uvec3 t = scene_.triangles[tri];
    const Vec3 a(scene_.vertices[t.x]), b(scene_.vertices[t.y]), c(scene_.vertices[t.z]);
    // Barycentric coordinates of p (projected onto the triangle's plane).
    const Vec3 e1 = b - a, e2 = c - a, w = p - a;
    const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    const double w1 = glm::dot(w, e1), w2 = glm::dot(w, e2);
    const double det = d11 * d22 - d12 * d12;
    double beta = det > 0.0 ? (d22 * w1 - d12 * w2) / det : 1.0 / 3.0;
    double gamma = det > 0.0 ? (d11 * w2 - d12 * w1) / det : 1.0 / 3.0;
    beta = std::clamp(beta, 0.0, 1.0);
    gamma = std::clamp(gamma, 0.0, 1.0 - beta);
    const double alpha = 1.0 - beta - gamma;
    const std::size_t B = static_cast<std::size_t>(bands_), stride = TallyLayout::kSides * B, at = side * B;
    for (std::size_t k = 0; k < B; ++k)
        e[k] += alpha * vertex_secondary_[t.x * stride + at + k] + beta * vertex_secondary_[t.y * stride + at + k] +
                gamma * vertex_secondary_[t.z * stride + at + k];
}

void Renderer::shade(const Vec3& o, const Vec3& d, const double* weight, int depth, Rng& rng, const RenderOptions& opt,
                     double* out) const {
    const Hit hit = embree_.intersect(o, d);
    if (!hit.found) {  // leaves the scene: the sky and the ground glow there are, else black
        add_sky(d, weight, out);
        return;
    }
    const std::size_t tri = hit.triangle;
    const Vec3 p = o + static_cast<double>(hit.t) * d;
    const Vec3& ng = scene_.triangle_normal[tri];
    const bool front = glm::dot(d, ng) < 0.0;
    const Vec3 n = front ? ng : -ng;  // the normal on the viewer's side
    const Material& m = scene_.materials[scene_.triangle_material[tri]];

    if (front && emitter_of_[tri] >= 0) {
        const double* le = &emitted_radiance_[static_cast<std::size_t>(emitter_of_[tri]) * bands_];
        for (int b = 0; b < bands_; ++b) out[b] += weight[b] * le[b];
    }
    // Lambertian part: rho / pi times the illuminance on the side of the surface whose
    // normal is `side` (the stored map keeps each side's own secondary illuminance).
    const std::size_t viewer_side = front ? 0 : 1;
    auto lambertian = [&](const std::vector<double>& rho, const Vec3& side, std::size_t map_side) {
        if (!any_positive(rho)) return;
        Weights e{};
        direct(p, side, rng, opt, e);
        add_secondary(tri, map_side, p, e);
        for (int b = 0; b < bands_; ++b) out[b] += weight[b] * band_value(rho, b) / kPi * e[b];
    };
    // A specular branch with per-band factor k (or the scalar k0 when k is empty).
    auto follow = [&](const std::vector<double>* k, double k0, const Vec3& dir) {
        if (depth + 1 >= opt.max_depth) return;
        Weights w{};
        double wmax = 0.0;
        for (int b = 0; b < bands_; ++b) {
            w[b] = weight[b] * k0 * (k != nullptr ? band_value(*k, b) : 1.0);
            wmax = std::max(wmax, w[b]);
        }
        if (wmax < opt.min_weight) return;
        shade(leave(p, n, dir, eps_), dir, w, depth + 1, rng, opt, out);
    };

    // The specular reflection: a mirror's direction, or with a roughness one drawn from the
    // Ward lobe as the photons draw it (absorbed with probability 1 - albedo), so the
    // pixel's samples average the glossy reflection.
    auto glossy = [&]() {
        if (!m.lobe) {
            follow(&m.specular_reflectance, 1.0, reflect(d, n));
            return;
        }
        const double u0 = rng.next(), u1 = rng.next(), u2 = rng.next();
        if (const auto dir = m.lobe->reflect(d, n, u0, u1, u2)) follow(&m.specular_reflectance, 1.0, *dir);
    };
    switch (m.type) {
    case MaterialType::black: break;
    case MaterialType::diffuse: lambertian(m.diffuse_reflectance, n, viewer_side); break;
    case MaterialType::general:
        lambertian(m.diffuse_reflectance, n, viewer_side);
        // Light through a thin diffuser: what arrives on the far side.
        lambertian(m.diffuse_transmittance, -n, 1 - viewer_side);
        if (any_positive(m.specular_reflectance)) glossy();
        if (any_positive(m.specular_transmittance)) follow(&m.specular_transmittance, 1.0, d);
        break;
    case MaterialType::mirror: glossy(); break;
    case MaterialType::glass:
    case MaterialType::glazing:
        for (const SpecularBranch& branch : transparent_branches(m, d, n, front, bands_))
            follow(branch.k.empty() ? nullptr : &branch.k, branch.k0, branch.direction);
        break;
    }
}

void Renderer::add_sky(const Vec3& d, const double* weight, double* out) const {
    const auto& lights = scene_.lights.lights();
    for (std::size_t li = 0; li < lights.size(); ++li) {
        const Light& l = lights[li];
        if (light_weight_[li] == 0.0) continue;
        const double lum = light_weight_[li] * l.luminance_seen_cd_m2(d);
        for (int b = 0; b < bands_; ++b) out[b] += weight[b] * lum * l.band_share[static_cast<std::size_t>(b)];
    }
}

std::vector<double> Renderer::trace(const Vec3& origin, const Vec3& d, std::uint64_t seed,
                                    const RenderOptions& opt) const {
    Rng rng(seed);
    Weights one{}, out{};
    for (int b = 0; b < bands_; ++b) one[b] = 1.0;
    shade(origin, glm::normalize(d), one, 0, rng, opt, out);
    return std::vector<double>(out, out + bands_);
}

LuminanceImage Renderer::render(const PinholeCamera& camera, const RenderOptions& opt) const {
    const int w = camera.width(), h = camera.height();
    LuminanceImage image(w, h, scene_.bands);
    const int samples = std::max(1, opt.samples);
    std::atomic<int> next_row{0};
    auto worker = [&] {
        Weights one{};
        for (int b = 0; b < bands_; ++b) one[b] = 1.0;
        for (int y = next_row.fetch_add(1); y < h; y = next_row.fetch_add(1))
            for (int x = 0; x < w; ++x) {
                Rng rng(opt.seed * 0x2545F4914F6CDD1Dull ^ (static_cast<std::uint64_t>(y) * w + x));
                rng.next_u64();
                // Hammersley points in the pixel with a random (Cranley-Patterson) shift.
                const double sx = rng.next(), sy = rng.next();
                Weights sum{};
                for (int i = 0; i < samples; ++i) {
                    const double jx = std::fmod((i + 0.5) / samples + sx, 1.0);
                    const double jy = std::fmod(radical_inverse2(static_cast<std::uint32_t>(i)) + sy, 1.0);
                    shade(camera.position(), camera.direction(x + jx, y + jy), one, 0, rng, opt, sum);
                }
                for (int b = 0; b < bands_; ++b) image.at(x, y, b) = static_cast<float>(sum[b] / samples);
            }
    };
    const int threads = opt.threads > 0 ? opt.threads
                                        : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    {
        std::vector<std::jthread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
        worker();
    }
    return image;
}

namespace {

// The scene a result was made from: its scene file, or the Radiance files of a bare model run.
Scene reload_scene(const RunInfo& info) {
    if (info.radiance_models.empty()) return load_scene(info.scene_file);
    RadianceRun run;
    for (const std::string& m : info.radiance_models) run.models.emplace_back(m);
    if (!info.radiance_sensors.empty()) run.sensors = info.radiance_sensors;
    if (info.radiance_sensor_radius_m > 0.0) run.sensor_radius_m = info.radiance_sensor_radius_m;
    run.scale = info.radiance_scale;
    return load_radiance_scene(run);
}

}  // namespace

RenderInput load_render_input(const fs::path& result, const std::string& light_scene) {
    const ResultFile r(result);
    const std::string name = result.string();
    if (r.run_info().scene_file.empty())
        throw InputError(name + ": the result names no scene file (root attribute scene_file), so its scene "
                                "cannot be reloaded for rendering");
    const fs::path scene_file = r.run_info().scene_file;
    if (!fs::is_regular_file(scene_file))
        throw InputError(name + ": its scene file " + scene_file.string() + " does not exist any more");
    const std::vector<double> vertices = r.vertices();
    RenderInput in{reload_scene(r.run_info()), {}, {}};
    const Scene& s = in.scene;
    std::string map_group = "/global";
    if (!light_scene.empty()) {
        const auto it = std::find_if(s.light_scenes.begin(), s.light_scenes.end(),
                                     [&](const LightScene& ls) { return ls.name == light_scene; });
        if (it == s.light_scenes.end()) {
            std::string have;
            for (const LightScene& ls : s.light_scenes) have += (have.empty() ? "" : ", ") + ls.name;
            throw InputError("--scene: " + scene_file.string() + " has no [[light_scene]] named '" + light_scene +
                             "' (it has: " + (have.empty() ? "none" : have) + ")");
        }
        map_group = "/light_scenes/" + light_scene + "/global";
        if (!r.raw().has(map_group))
            throw InputError("--scene: " + name + " holds no surface map of light scene '" + light_scene +
                             "' (the run kept one map for all light groups: [run] group_maps = false)");
        for (const Light& l : s.lights.lights()) in.light_weight.push_back(it->weights.at(l.group));
    }
    const SurfaceIlluminance map = r.surface_illuminance(map_group);
    bool same = map.shape.triangles == s.triangle_count() && map.shape.bands == s.bands.size() &&
                vertices.size() == 3 * s.vertices.size();
    for (std::size_t v = 0; same && v < s.vertices.size(); ++v)
        for (int k = 0; k < 3; ++k)
            same = same && std::abs(vertices[3 * v + k] - static_cast<double>(s.vertices[v][k])) <=
                               1e-5 * (1.0 + std::abs(vertices[3 * v + k]));
    if (same && !r.bands().empty()) same = r.bands() == s.bands;
    if (!same)
        throw InputError(name + ": the scene file " + scene_file.string() +
                         " has changed since the run (its mesh or bands differ from the result's)");
    const std::size_t T = s.triangle_count(), B = s.bands.size();
    in.secondary_lx.resize(T * TallyLayout::kSides * B);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side)
            for (std::size_t b = 0; b < B; ++b) {
                const std::size_t from = map.shape.index(t, side, b);
                in.secondary_lx[(t * TallyLayout::kSides + side) * B + b] = std::max(0.0, map.total_lx[from] -
                                                                                              map.direct_lx[from]);
            }
    return in;
}

}  // namespace luxtrace
