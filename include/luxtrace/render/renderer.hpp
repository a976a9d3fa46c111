#pragma once
// A view of a simulated scene by backward ray tracing from the eye (SPEC issue 5, as in
// the SPECTER system): at the first diffuse hit the luminance is
//     L_b = rho_d,b / pi * (E_direct,b(p) + E_secondary,b(p))
// with E_direct computed exactly at p from every light (shadow rays; IES intensity in
// the light's frame; area lights sampled) and E_secondary the stored map "all minus
// direct arrivals", smoothed over the mesh (per-vertex area-weighted means of the
// adjacent triangles, barycentric at p). Mirrors, the specular parts of `general` and
// glass (Fresnel, both branches) and glazing (reflected and straight through) are
// followed specularly; emitters seen from the front show M / pi; rays leaving the scene
// see black.
#include "luxtrace/render/camera.hpp"
#include "luxtrace/render/image_io.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/shadow_ray.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace luxtrace {

class EmbreeScene;

struct RenderOptions {
    int samples = 4;              // jittered eye rays per pixel
    int threads = 0;              // 0: all cores
    int max_depth = 8;            // longest chain of specular bounces followed
    int area_light_samples = 16;  // emitter points per area light at each diffuse hit
    std::uint64_t seed = 1;       // jitter and area-light sampling (a pure function of seed and pixel)
    double min_weight = 1e-4;     // specular branches carrying less are dropped
};

class Renderer {
public:
    static constexpr int kMaxBands = 16;

    // secondary_lx: per triangle, side and band ([T][2][B], lux; side 0 the front) the
    // stored illuminance minus its direct part; empty means none (direct light only). Throws InputError for scenes
    // with more than kMaxBands bands.
    // light_weight: per light of the scene, its weight in the picture (a light scene's
    // weight of its group); empty: every light at 1.
    Renderer(const Scene& scene, const EmbreeScene& embree, std::vector<double> secondary_lx,
             std::vector<double> light_weight = {});

    LuminanceImage render(const PinholeCamera& camera, const RenderOptions& opt = {}) const;

    // Luminance per band (cd/m^2) seen along the ray origin + t d (unit d); `seed`
    // drives the area-light sampling.
    std::vector<double> trace(const Vec3& origin, const Vec3& d, std::uint64_t seed,
                              const RenderOptions& opt = {}) const;

    // The smoothed secondary illuminance (lux per band) at point p of side `side` (0 front)
    // of triangle `tri`.
    std::vector<double> secondary_at(std::size_t tri, std::size_t side, const Vec3& p) const;

private:
    struct Rng;
    void shade(const Vec3& o, const Vec3& d, const double* weight, int depth, Rng& rng, const RenderOptions& opt,
               double* out) const;
    void direct(const Vec3& p, const Vec3& n, Rng& rng, const RenderOptions& opt, double* e) const;
    void add_secondary(std::size_t tri, std::size_t side, const Vec3& p, double* e) const;
    // What a ray leaving the scene along d sees: the skies and ground glows.
    void add_sky(const Vec3& d, const double* weight, double* out) const;
    // The illuminance one light gives p (normal n) per band, before its band shares; false
    // if it sends none to a picture (a sky patch, a sun's second portal).
    bool direct_from(const Light& l, const Vec3& p, const Vec3& n, const Vec3& o, Rng& rng, const RenderOptions& opt,
                     double* sum) const;

    const Scene& scene_;
    const EmbreeScene& embree_;
    int bands_;
    double eps_;
    ShadowRay shadow_;                      // through glazing, as the tracer's direct light goes
    std::vector<double> vertex_secondary_;  // [V][2][B]
    std::vector<int> emitter_of_;           // per triangle: area light index or -1
    std::vector<double> emitted_radiance_;  // per light and band: M / pi (area lights), times its weight
    std::vector<double> light_weight_;      // per light
};

// What `luxtrace render` needs from a result: the scene reloaded from the file named by
// its scene_file attribute, checked against the stored mesh, and the secondary map.
// Throws InputError naming what is wrong (no scene file, file gone, mesh changed).
// With `light_scene`, the map and the lights' weights are that [[light_scene]]'s.
struct RenderInput {
    Scene scene;
    std::vector<double> secondary_lx;  // [T][2][B]
    std::vector<double> light_weight;  // per light; empty: all 1
};
RenderInput load_render_input(const std::filesystem::path& result, const std::string& light_scene = "");

}  // namespace luxtrace
