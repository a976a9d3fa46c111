#include "luxtrace/estimate/result_estimates.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

ResultEstimates estimate_result(const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> data,
                                double e0, std::uint64_t photons) {
    const EstimateScene s = estimate_scene(scene);
    ResultEstimates r = estimate_result(s, WeightedTallies(layout, data), e0, photons);
    for (const LightScene& ls : scene.light_scenes)
        r.light_scenes.push_back(estimate_light_scene(s, ls, layout, data, e0, photons));
    return r;
}

namespace {
// The observer as a light scene sees it: each luminaire's luminance times its group's
// weight, the luminaires switched off left out.
Observer dimmed(const Observer& o, const EstimateScene& scene, std::span<const double> weights) {
    Observer d = o;
    d.sources.clear();
    for (GlareSource s : o.sources) {
        const double w = weights[scene.light_group[s.light]];
        if (w <= 0.0) continue;
        s.luminance_cd_m2 *= w;
        s.intensity_cd *= w;
        d.sources.push_back(s);
    }
    return d;
}
}  // namespace

LightSceneEstimates estimate_light_scene(const EstimateScene& scene, const LightScene& ls, const TallyLayout& layout,
                                         std::span<const std::uint64_t> data, double e0, std::uint64_t photons) {
    LightSceneEstimates e;
    e.name = ls.name;
    e.weights = ls.weights;
    for (std::size_t g = 0; g < scene.group_flux_lm.size(); ++g) e.flux_lm += ls.weights[g] * scene.group_flux_lm[g];
    const WeightedTallies w(layout, data, ls.weights);
    e.surface_available = w.map_available();
    e.estimates = estimate_result(scene, w, e0, photons);
    return e;
}

ResultEstimates estimate_result(const EstimateScene& scene, const WeightedTallies& w, double e0,
                                std::uint64_t photons) {
    ResultEstimates r;
    if (w.map_available()) {
        r.global = estimate_global(w, scene.triangle_area_m2, e0, photons);
        r.surface = surface_maps(w, scene.triangle_area_m2, e0, photons);
    }
    for (std::size_t d = 0; d < scene.detectors.size(); ++d)
        r.detectors.push_back(estimate_detector(scene.detectors[d], d, w, e0, photons));
    const double mf = scene.maintenance_factor;
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
                                                     scene.bands));
        else r.modelling.emplace_back();
    }
    const double reference_lx = daylight_reference_lx(scene, w.plain() ? std::span<const double>{} : w.weights());
    for (std::size_t d = 0; d < scene.detectors.size(); ++d) {
        const Detector& det = scene.detectors[d];
        const DetectorEstimate& e = r.detectors[d];
        if (det.daylight_factor && reference_lx > 0.0 && !e.summed_value.empty())
            r.daylight.emplace_back(estimate_daylight(det, e.summed_value, e.summed_sigma, reference_lx));
        else r.daylight.emplace_back();
    }
    for (const Observer& o : scene.observers)
        r.observers.push_back(estimate_observer(w.plain() ? o : dimmed(o, scene, w.weights()),
                                                r.detectors[o.eye_detector], mf, scene.maintenance_factor_uniform));
    return r;
}

}  // namespace luxtrace
