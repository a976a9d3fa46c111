#include "luxtrace/annual/annual_estimate.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/stats/result_estimates.hpp"

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

bool annual_grid(const Detector& d) {
    return (d.type == DetectorType::illuminance || d.type == DetectorType::points) && !d.indirect_only;
}

std::vector<std::optional<AnnualDetectorEstimate>> estimate_annual(const Scene& scene, const TallyLayout& layout,
                                                                   std::span<const std::uint64_t> data, double e0,
                                                                   std::uint64_t photons, int replicates) {
    std::vector<std::optional<AnnualDetectorEstimate>> out(scene.annual ? scene.detectors.size() : 0);
    if (!scene.annual || photons == 0) return out;
    const AnnualHours hours = annual_hours(*scene.annual);
    const std::vector<double> group_flux = light_group_flux_lm(scene);
    for (std::size_t d = 0; d < scene.detectors.size(); ++d) {
        const Detector& det = scene.detectors[d];
        if (!annual_grid(det)) continue;
        const AnnualCoefficients c(*scene.annual, layout, data, d, static_cast<std::size_t>(det.cells()),
                                   e0 * det.value_per_lm(), photons, group_flux);
        AnnualDetectorEstimate e;
        c.series(e.value, e.sigma);
        const std::uint64_t seed = scene.run.seed * 0x9E3779B97F4A7C15ull + d;
        const AnnualReplicates draw = [&](std::size_t r, double noise_scale, AnnualSeries& series) {
            c.replicate(noise_scale, seed, r, series);
        };
        if (replicates > 0) {
            e.metrics = estimate_annual_metrics(draw, hours, {}, replicates);
        } else {
            e.metrics.value = annual_metrics(e.value, hours);
        }
        out[d] = std::move(e);
    }
    return out;
}

}  // namespace luxtrace
