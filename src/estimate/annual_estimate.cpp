#include "luxtrace/estimate/annual_estimate.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <utility>

namespace luxtrace {

namespace {

// The cells of a block of the post-processing: its coefficients (about 30 doubles per sun
// and cell) stay in the core's cache while its hours are summed.
constexpr std::size_t kBlockCells = kAnnualBlockCells;

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

namespace {

// The lights' flux per light group, and per annual sun (Light::annual_sun).
struct GridFlux {
    std::vector<double> group, sun;
};

GridFlux grid_flux(const Scene& scene) {
    GridFlux f{light_group_flux_lm(scene), std::vector<double>(scene.annual->sky->suns().size(), 0.0)};
    for (const Light& l : scene.lights.lights())
        if (l.annual_sun >= 0 && static_cast<std::size_t>(l.annual_sun) < f.sun.size())
            f.sun[static_cast<std::size_t>(l.annual_sun)] += l.flux_lm;
    return f;
}

// The grid's counts as AnnualCoefficients reads them.
AnnualGridCounts grid_counts(const Scene& scene, std::size_t det, const TallyLayout& layout,
                             std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                             const GridFlux& group_flux, const DirectCoefficients* direct) {
    const Detector& d = scene.detectors[det];
    if (scene.annual->options.shadow_rays() != (direct != nullptr))
        throw std::logic_error("estimate_annual_grid: direct coefficients missing or not asked for");
    if (layout.gathered(det) && !(direct != nullptr && direct->gather_unit_lx_per_lm > 0.0))
        throw std::logic_error("estimate_annual_grid: a gathered grid without its unit");
    const double gather_per_unit = layout.gathered(det) ? e0 * direct->gather_unit_lx_per_lm : 0.0;
    return {*scene.annual,
            layout,
            data,
            det,
            static_cast<std::size_t>(d.cells()),
            e0 * d.value_per_lm(),
            gather_per_unit,
            photons,
            group_flux.group,
            direct,
            group_flux.sun};
}

const DirectCoefficients* direct_of(const AnnualDirect& direct, std::size_t det) {
    return det < direct.size() && direct[det].cells > 0 ? &direct[det] : nullptr;
}

// The draws of a block (its coefficients, its series and its replicates'), the block's
// series with their errors to `series` when given (AnnualSeries for value and sigma).
AnnualBlockDraws block_draws(
    const AnnualGridCounts& grid, const AnnualDarkRates& dark, std::uint64_t seed, int replicates,
    const std::function<void(std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma)>* series) {
    return [&grid, &dark, seed, replicates, series](std::size_t first, std::size_t count, const AnnualSink& sink) {
        const AnnualCoefficients c(grid, first, count, dark);
        AnnualSeries s, sigma;
        if (series != nullptr) {
            c.series(s, sigma);
            (*series)(first, s, sigma);
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
}

std::uint64_t replicate_seed(const Scene& scene, std::size_t det) {
    return scene.run.seed * 0x9E3779B97F4A7C15ull + det;
}

// The year's direct exposure by shadow rays per cell (every coefficient's weights sum to
// 1 over the year, annual_sky.hpp), with its error.
void direct_year(const DirectCoefficients& dc, AnnualDetectorEstimate& e) {
    auto year = [&](const std::vector<float>& x, const std::vector<float>& v, std::vector<double>& sum,
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

// A grid's series of `hours` x `cells`: their values, or (with a sink: the values go there)
// their shape alone.
void size_series(std::size_t hours, std::size_t cells, AnnualSeries& x, bool values = true) {
    x.hours = hours;
    x.sensors = cells;
    if (!values) return;
    x.total_lx.assign(hours * cells, 0.0);
    x.direct_lx.assign(hours * cells, 0.0);
}

}  // namespace

AnnualDetectorEstimate estimate_annual_grid(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                            std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                            int replicates, bool series, const AnnualDirect& direct,
                                            const AnnualSeriesSink* sink) {
    const GridFlux group_flux = grid_flux(scene);
    const DirectCoefficients* dc = direct_of(direct, det);
    const AnnualGridCounts grid = grid_counts(scene, det, layout, data, e0, photons, group_flux, dc);
    const AnnualHours hours = annual_hours(*scene.annual);
    AnnualDetectorEstimate e;
    if (dc != nullptr) direct_year(*dc, e);
    annual_gather_year(scene, det, layout, data, e0, photons, dc, e);
    if (series)
        for (AnnualSeries* x : {&e.value, &e.sigma})
            size_series(hours.occupied.size(), grid.cells, *x, sink == nullptr);
    // Block by block on every core: each block's coefficients, its hourly series and its
    // replicates' (annual_metrics.hpp).
    const AnnualDarkRates dark = AnnualCoefficients::dark_rates(grid);
    const std::function<void(std::size_t, const AnnualSeries&, const AnnualSeries&)> place =
        [&](std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma) {
            if (sink != nullptr) return (*sink)(det, first, value, sigma);
            place_block(value, first, e.value);
            place_block(sigma, first, e.sigma);
        };
    const AnnualBlockDraws draws = block_draws(grid, dark, replicate_seed(scene, det), replicates,
                                               series ? &place : nullptr);
    e.metrics = estimate_annual_metrics(draws, grid.cells, kBlockCells, hours, {}, replicates);
    return e;
}

void annual_gather_year(const Scene& scene, std::size_t det, const TallyLayout& layout,
                        std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                        const DirectCoefficients* direct, AnnualDetectorEstimate& e) {
    if (!layout.gathered(det)) return;
    const GridFlux group_flux = grid_flux(scene);
    const AnnualGridCounts g = grid_counts(scene, det, layout, data, e0, photons, group_flux, direct);
    const AnnualSetup& a = *scene.annual;
    const double kg = g.gather_per_unit, inv_n = photons > 0 ? 1.0 / static_cast<double>(photons) : 0.0;
    for (auto* v : {&e.gather_sky_lx_h, &e.gather_sky_sigma_lx_h, &e.gather_sun_lx_h, &e.gather_sun_sigma_lx_h})
        v->assign(g.cells, 0.0);
    const std::size_t patches = a.sky->sky_entries() - 1;  // the ground is the last entry
    const std::size_t suns_end = a.first_sun_group + a.sun_rows();
    for (std::size_t grp = 0; grp < layout.groups(); ++grp) {
        const bool sun = grp >= a.first_sun_group && grp < suns_end;
        const bool sky = grp == a.ground_group || (grp >= a.first_patch_group && grp < a.first_patch_group + patches);
        if (!sun && !sky) continue;
        std::vector<double>& sum = sun ? e.gather_sun_lx_h : e.gather_sky_lx_h;
        std::vector<double>& var = sun ? e.gather_sun_sigma_lx_h : e.gather_sky_sigma_lx_h;
        for (std::size_t c = 0; c < g.cells; ++c) {
            const std::size_t at = layout.detector_gathered(det, c, grp);
            const double y = static_cast<double>(data[at]);
            const double q = std::ldexp(static_cast<double>(data[at + 1]), TallyLayout::kGatherSquareShift);
            sum[c] += kg * y;
            var[c] += kg * kg * std::max(0.0, q - y * y * inv_n);
        }
    }
    // The gather's own rays' error, relative and common to all its light.
    if (direct != nullptr && direct->gather_rel_var.size() == g.cells) {
        e.gather_rays_sigma_rel.resize(g.cells);
        for (std::size_t c = 0; c < g.cells; ++c) {
            const double r = direct->gather_rel_var[c];
            e.gather_rays_sigma_rel[c] = std::sqrt(r);
            e.gather_sky_sigma_lx_h[c] += r * e.gather_sky_lx_h[c] * e.gather_sky_lx_h[c];
            e.gather_sun_sigma_lx_h[c] += r * e.gather_sun_lx_h[c] * e.gather_sun_lx_h[c];
        }
    }
    for (auto* v : {&e.gather_sky_sigma_lx_h, &e.gather_sun_sigma_lx_h})
        for (double& x : *v) x = std::sqrt(x);
}

AnnualCellRange annual_part_cells(std::size_t cells, int part, int parts) {
    const std::size_t blocks = (cells + kBlockCells - 1) / kBlockCells, p = static_cast<std::size_t>(part),
                      n = static_cast<std::size_t>(std::max(1, parts));
    auto at = [&](std::size_t q) { return std::min(cells, blocks * q / n * kBlockCells); };
    return {at(p), at(p + 1)};
}

AnnualDarkRates annual_dark_rates(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                  std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                  const DirectCoefficients* direct) {
    const GridFlux group_flux = grid_flux(scene);
    return AnnualCoefficients::dark_rates(grid_counts(scene, det, layout, data, e0, photons, group_flux, direct));
}

AnnualGridPart estimate_annual_part(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                    std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                    int replicates, AnnualCellRange cells, const AnnualDarkRates& dark,
                                    const DirectCoefficients* direct) {
    const GridFlux group_flux = grid_flux(scene);
    const AnnualGridCounts grid = grid_counts(scene, det, layout, data, e0, photons, group_flux, direct);
    const AnnualHours hours = annual_hours(*scene.annual);
    AnnualGridPart part;
    part.cells = cells;
    const std::size_t n = cells.last - cells.first;
    for (AnnualSeries* x : {&part.value, &part.sigma}) size_series(hours.occupied.size(), n, *x);
    const std::function<void(std::size_t, const AnnualSeries&, const AnnualSeries&)> place =
        [&](std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma) {
            place_block(value, first - cells.first, part.value);
            place_block(sigma, first - cells.first, part.sigma);
        };
    const AnnualBlockDraws draws = block_draws(grid, dark, replicate_seed(scene, det), replicates, &place);
    AnnualMetricDraws sums(hours, grid.cells, {}, replicates);
    sums.run(draws, kBlockCells, cells.first, cells.last);
    part.metric_words = sums.words(cells.first, cells.last);
    return part;
}

AnnualPartsMerge::AnnualPartsMerge(const Scene& scene, std::size_t det, int replicates,
                                   const DirectCoefficients* direct, const AnnualSeriesSink* sink)
    : hours_(annual_hours(*scene.annual)), det_(det), cells_(static_cast<std::size_t>(scene.detectors[det].cells())),
      sink_(sink), sums_(hours_, cells_, {}, replicates) {
    if (direct != nullptr) direct_year(*direct, estimate_);
    for (AnnualSeries* x : {&estimate_.value, &estimate_.sigma})
        size_series(hours_.occupied.size(), cells_, *x, sink_ == nullptr);
}

void AnnualPartsMerge::add(const AnnualGridPart& p) {
    if (p.cells.last < p.cells.first || p.cells.last > cells_ || p.value.sensors != p.cells.last - p.cells.first)
        throw std::logic_error("AnnualPartsMerge: a part beyond the grid");
    if (sink_ != nullptr) {
        if (p.cells.last > p.cells.first) (*sink_)(det_, p.cells.first, p.value, p.sigma);
    } else {
        place_block(p.value, p.cells.first, estimate_.value);
        place_block(p.sigma, p.cells.first, estimate_.sigma);
    }
    sums_.merge(p.metric_words, p.cells.first, p.cells.last);
}

AnnualDetectorEstimate AnnualPartsMerge::finish() {
    estimate_.metrics = sums_.estimate();
    return std::move(estimate_);
}

std::vector<std::optional<AnnualDetectorEstimate>> estimate_annual(const Scene& scene, const TallyLayout& layout,
                                                                   std::span<const std::uint64_t> data, double e0,
                                                                   std::uint64_t photons, int replicates,
                                                                   const AnnualDirect& direct,
                                                                   const AnnualSeriesSink* sink) {
    std::vector<std::optional<AnnualDetectorEstimate>> out(scene.annual ? scene.detectors.size() : 0);
    if (!scene.annual || photons == 0) return out;
    for (std::size_t d = 0; d < scene.detectors.size(); ++d)
        if (annual_grid(scene.detectors[d]))
            out[d] = estimate_annual_grid(scene, d, layout, data, e0, photons, replicates, true, direct, sink);
    return out;
}

}  // namespace luxtrace
