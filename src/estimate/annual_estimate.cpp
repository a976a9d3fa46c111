#include "luxtrace/estimate/annual_estimate.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/scene/scene.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace luxtrace {

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
    const AnnualCoefficients c(*scene.annual, layout, data, det, static_cast<std::size_t>(d.cells()),
                               e0 * d.value_per_lm(), photons, light_group_flux_lm(scene),
                               shadow ? &direct[det] : nullptr);
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
    if (series) c.series(e.value, e.sigma);
    if (replicates > 0) {
        const std::uint64_t seed = scene.run.seed * 0x9E3779B97F4A7C15ull + det;
        const AnnualReplicates draw = [&](AnnualDraw what, std::size_t r, AnnualSeries& s) {
            if (what == AnnualDraw::estimate) c.estimate(s);
            if (what == AnnualDraw::centre) c.centre(s);
            if (what == AnnualDraw::replicate) c.replicate(seed, r, s);
        };
        e.metrics = estimate_annual_metrics(draw, hours, {}, replicates);
    } else {
        if (!series) c.estimate(e.value);
        e.metrics.value = annual_metrics(e.value, hours);
    }
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
