#include "luxtrace/estimate/annual_estimate.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace luxtrace {

namespace {

// The cells of a block of the post-processing: its coefficients (about 30 doubles per sun
// and cell) stay in the core's cache while its hours are summed.
constexpr std::size_t kBlockCells = 32;

// A block's series (hours x its cells) into the grid's, from cell `first`.
void place_block(const AnnualSeries& block, std::size_t first, AnnualSeries& grid) {
    for (std::size_t h = 0; h < block.hours; ++h) {
        std::copy_n(&block.total_lx[h * block.sensors], block.sensors, &grid.total_lx[h * grid.sensors + first]);
        std::copy_n(&block.direct_lx[h * block.sensors], block.sensors, &grid.direct_lx[h * grid.sensors + first]);
    }
}

}  // namespace

AnnualHours annual_hours(const AnnualSetup& annual) {
    const std::vector<AnnualHour>& hours = annual.sky->hours();
    AnnualHours out;
    std::vector<double> outdoor(hours.size(), 0.0);
    for (std::size_t h = 0; h < hours.size(); ++h) {
        out.occupied.push_back(hours[h].occupied ? 1 : 0);
        outdoor[h] = hours[h].daylit ? hours[h].diffuse_horizontal_lx : 0.0;
    }
    out.en17037_hours = en17037_daylight_hours(outdoor);
    return out;
}

AnnualDetectorEstimate estimate_annual_grid(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                            std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                            int replicates, bool series, const AnnualDirect& direct) {
    const Detector& d = scene.detectors[det];
    const bool shadow = det < direct.size() && direct[det].cells > 0;
    if (scene.annual->options.shadow_rays() != shadow)
        throw std::logic_error("estimate_annual_grid: direct coefficients missing or not asked for");
    const std::vector<double> group_flux = light_group_flux_lm(scene);
    const std::size_t cells = static_cast<std::size_t>(d.cells());
    const AnnualGridCounts grid{*scene.annual, layout,     data,
                                det,           cells,      e0 * d.value_per_lm(),
                                photons,       group_flux, shadow ? &direct[det] : nullptr};
    const AnnualHours hours = annual_hours(*scene.annual);
    AnnualDetectorEstimate e;
    if (shadow) {  // every coefficient's weights sum to 1 over the year (annual_sky.hpp)
        const DirectCoefficients& dc = direct[det];
        auto year = [&](const std::vector<double>& x, const std::vector<double>& v, std::vector<double>& sum,
                        std::vector<double>& sigma) {
            sum.assign(dc.cells, 0.0);
            sigma.assign(dc.cells, 0.0);
            for (std::size_t i = 0; i < x.size(); ++i) {
                sum[i % dc.cells] += x[i];
                sigma[i % dc.cells] += v[i];
            }
            for (double& s : sigma) s = std::sqrt(s);
        };
        year(dc.sky_lx, dc.sky_var, e.direct_sky_lx_h, e.direct_sky_sigma_lx_h);
        year(dc.sun_lx, dc.sun_var, e.direct_sun_lx_h, e.direct_sun_sigma_lx_h);
    }
    if (series) {
        for (AnnualSeries* x : {&e.value, &e.sigma}) {
            x->hours = hours.occupied.size();
            x->sensors = cells;
            x->total_lx.assign(x->hours * cells, 0.0);
            x->direct_lx.assign(x->hours * cells, 0.0);
        }
    }
    // Block by block on every core: each block's coefficients, its hourly series and its
    // replicates' (annual_metrics.hpp).
    const AnnualDarkRates dark = AnnualCoefficients::dark_rates(grid);
    const std::uint64_t seed = scene.run.seed * 0x9E3779B97F4A7C15ull + det;
    const AnnualBlockDraws draws = [&](std::size_t first, std::size_t count, const AnnualSink& sink) {
        const AnnualCoefficients c(grid, first, count, dark);
        AnnualSeries s, sigma;
        if (series) {
            c.series(s, sigma);
            place_block(s, first, e.value);
            place_block(sigma, first, e.sigma);
        } else {
            c.estimate(s);
        }
        sink(AnnualDraw::estimate, 0, s);
        if (replicates == 0) return;
        c.centre(s);
        sink(AnnualDraw::centre, 0, s);
        for (int r = 0; r < replicates; ++r) {
            c.replicate(seed, static_cast<std::uint64_t>(r), s);
            sink(AnnualDraw::replicate, static_cast<std::size_t>(r), s);
        }
    };
    e.metrics = estimate_annual_metrics(draws, cells, kBlockCells, hours, {}, replicates);
    return e;
}

std::vector<std::optional<AnnualDetectorEstimate>> estimate_annual(const Scene& scene, const TallyLayout& layout,
                                                                   std::span<const std::uint64_t> data, double e0,
                                                                   std::uint64_t photons, int replicates,
                                                                   const AnnualDirect& direct) {
    std::vector<std::optional<AnnualDetectorEstimate>> out(scene.annual ? scene.detectors.size() : 0);
    if (!scene.annual || photons == 0) return out;
    for (std::size_t d = 0; d < scene.detectors.size(); ++d)
        if (annual_grid(scene.detectors[d]))
            out[d] = estimate_annual_grid(scene, d, layout, data, e0, photons, replicates, true, direct);
    return out;
}

}  // namespace luxtrace
