#pragma once
// What each cell of a sensor grid sees of the scene's surfaces (issue 37: the groundwork of
// gathering the light after an event, docs/PERFORMANCE.md "A path to ten times"). Per cell
// and triangle side, the part of the cell's projected solid angle (sr; a whole hemisphere's
// is pi) through which the cell sees that side first: straight, or by way of glazing, times
// the pane's reflectance or transmittance along the way. A Lambertian side of luminance L
// adds K L to the cell's illuminance, so the light that reaches the cell after a diffuse
// reflection is sum over sides of K rho E / pi, E the side's irradiance (the map's).
//
// Estimated by n x n stratified cosine-weighted rays per cell (uniform over the projected
// disc in (r^2, phi), Malley's method), each carrying pi / n^2; an area cell samples its
// area with them. Each ray's numbers come from Philox at (seed, detector, cell, stratum):
// the weights do not depend on which rank or thread computed a cell. A ray that leaves the
// scene (the sky, seen straight or through glass: the direct light's, direct_daylight.hpp)
// adds nothing.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace luxtrace {

class EmbreeScene;
class GatherPatches;
struct Material;
struct Scene;

// The panes (glazing, or glass of index 1) a gather ray passes or is reflected by before
// what lies behind counts no more; the tracer keeps a photon's light the gather's through as
// many (tracer.hpp).
inline constexpr int kGatherPanes = 4;
// Such a pane: glazing with its curves, or glass of index 1 (an open hole).
bool gather_pane(const Material& m);

struct SensorGatherOptions {
    int rays = 4096;  // per cell, the square of an even number (AnnualOptions::valid_direct_rays)
    std::uint64_t seed = 1;
    const GatherPatches* patches = nullptr;  // null: whole triangles
    // Also the rays' own variance as a form in the sites' luminances (SensorGather::form).
    bool rays_form = false;
};

// c L_a L_b, a <= b sites.
struct FormTerm {
    std::uint32_t a = 0, b = 0;
    double coef = 0.0;
};

struct SensorGather {
    std::size_t first = 0, cells = 0;  // the grid's cells [first, first + cells)
    // Cell c's (from first) entries are [offset[c], offset[c + 1]), by ascending site.
    std::vector<std::size_t> offset;
    // A site: side * P + patch, P the patches of one side (without patches: side *
    // triangles + triangle, TallyLayout's side index).
    std::vector<std::uint32_t> site;
    std::vector<double> weight_sr;
    // With SensorGatherOptions::rays_form: per cell (terms [form_offset[c], form_offset[c +
    // 1])), the variance of sum over sites of K L from the rays' sampling, given the sites'
    // luminances L, as sum of coef L_a L_b (collapsed strata: pairs of neighbouring strata
    // in azimuth).
    std::vector<std::size_t> form_offset;
    std::vector<FormTerm> form;
};

// Cells [first, last) of Scene::detectors[det] (a sensor grid), on every core.
SensorGather sensor_gather(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                           const SensorGatherOptions& options, std::size_t first, std::size_t last);

}  // namespace luxtrace
