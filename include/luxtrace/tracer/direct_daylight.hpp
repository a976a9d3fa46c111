#pragma once
// Annual daylight's direct part by shadow rays (issue 37, annual/direct_coefficients.hpp):
// from each cell of a sensor grid, rays toward every sky patch, the ground and every
// hour's sun, each times what the scene lets through along it (shadow_ray.hpp). That is
// Radiance's -ab 0 at the exact point: a points grid's sensor is its point, an
// illuminance grid's cell is sampled over its area (the cell's mean, as the photons'
// count is).
//
// Sampling: per cell and target, an n x n stratified grid over the patch (uniform in
// sin altitude and azimuth, dw = d(sin alt) d(az)) or over the sun's disc (uniform in
// the cone), each sample from Philox at (cell, target, stratum): the values do not depend
// on which rank or thread computed a cell. Each stratum's cosine is integrated exactly and
// only what passes is sampled, so an unobstructed or a wholly shaded target is exact, and
// the noise (with its variance, direct_coefficients.hpp) lies at the edges of what is seen.
#include "luxtrace/annual/direct_coefficients.hpp"

#include <cstddef>
#include <cstdint>

namespace luxtrace {

class EmbreeScene;
struct Scene;

struct DirectDaylightOptions {
    // Per sky patch and cell, AnnualOptions::valid_direct_rays (n x n strata); 0: about 9,216
    // per cell over all patches (64 per patch at MF 1, 16 at MF 2, 4 at MF 4). The ground
    // takes 256.
    int sky_rays = 0;
    // Per sun and cell, AnnualOptions::valid_direct_rays: an illuminance grid's cell always, a
    // points sensor where five fixed rays find the sun's disc cut (direct_daylight.cpp).
    int sun_rays = 16;
    std::uint64_t seed = 1;
};

// Cells [first, last) of Scene::detectors[det] (an annual scene's illuminance or points
// grid) into `out`, which must be sized for the detector's cells (out.resize). Spread over
// the cores with TBB.
void direct_daylight(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                     const DirectDaylightOptions& options, std::size_t first, std::size_t last,
                     DirectCoefficients& out);

}  // namespace luxtrace
