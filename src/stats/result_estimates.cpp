#include "luxtrace/stats/result_estimates.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

ResultEstimates estimate_result(const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> data,
                                double e0, std::uint64_t photons) {
    ResultEstimates r;
    r.global = estimate_global(layout, data, scene.triangle_area_m2, e0, photons);
    r.surface = surface_maps(layout, data, scene.triangle_area_m2, e0, photons);
    for (std::size_t d = 0; d < scene.detectors.size(); ++d)
        r.detectors.push_back(estimate_detector(scene.detectors[d], d, layout, data, e0, photons));
    const double mf = scene.lights.maintenance_factor();
    for (const DetectorEstimate& e : r.detectors) {
        std::vector<IlluminanceMetrics> m;
        for (const IlluminanceMetrics& initial : e.metrics) m.push_back(maintained(initial, mf));
        r.maintained_metrics.push_back(std::move(m));
    }
    for (std::size_t d = 0; d < scene.detectors.size(); ++d) {
        const Detector& det = scene.detectors[d];
        if (det.cylinders() && det.horizontal_index >= 0)
            r.modelling.emplace_back(modelling_ratio(r.detectors[d],
                                                     r.detectors[static_cast<std::size_t>(det.horizontal_index)],
                                                     scene.bands.size()));
        else r.modelling.emplace_back();
    }
    for (const Observer& o : scene.observers)
        r.observers.push_back(
            estimate_observer(o, r.detectors[o.eye_detector], mf, scene.lights.maintenance_factor_uniform()));
    return r;
}

}  // namespace luxtrace
