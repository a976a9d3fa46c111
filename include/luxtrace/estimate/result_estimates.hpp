#pragma once
// Everything a result file stores that is computed from the counts: rank 0 computes it
// before each write, and the writer (io/result_file.hpp) only writes these numbers. To add
// a group of estimates (e.g. per light group or light scene): a member here, filled in
// estimate_result, written by one part of the writer (src/io/result_parts.hpp).
#include "luxtrace/estimate/annual_estimate.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/estimate/observer_estimate.hpp"
#include "luxtrace/stats/daylight_metrics.hpp"
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/stats/illuminance_metrics.hpp"
#include "luxtrace/stats/modelling_ratio.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
struct LightScene;
struct LightSceneEstimates;

struct ResultEstimates {
    GlobalEstimate global;
    SurfaceMaps surface;
    std::vector<DetectorEstimate> detectors;  // per Scene::detectors, eye detectors included
    // Per detector, parallel to detectors[d].metrics: the metrics times the lights'
    // flux-weighted maintenance factor.
    std::vector<std::vector<IlluminanceMetrics>> maintained_metrics;
    // Per detector: cylindrical detectors with a `horizontal` detector only.
    std::vector<std::optional<ModellingRatio>> modelling;
    // Per detector: daylight_factor detectors only, while the lights give E_h,ext > 0.
    std::vector<std::optional<DaylightEstimate>> daylight;
    std::vector<ObserverEstimate> observers;        // per Scene::observers
    std::vector<LightSceneEstimates> light_scenes;  // per Scene::light_scenes (the plain run's only)
    // Per Scene::detectors, annual runs only (estimate_annual; filled for the final result,
    // not for checkpoints).
    std::vector<std::optional<AnnualDetectorEstimate>> annual;
    // Where their hourly series are when they hold none (AnnualSeriesSink): empty otherwise.
    AnnualSeriesSource annual_series;
};

// A [[light_scene]]'s estimates (issue 22): the same as the plain run's, on the groups'
// tallies weighted by the scene's dimming. `surface_available` is false when the run kept
// one surface map for all groups (group_maps = false): then only detectors and observers.
struct LightSceneEstimates {
    std::string name;
    std::vector<double> weights;  // per light group
    double flux_lm = 0.0;         // sum over groups of weight x the group's flux
    bool surface_available = true;
    ResultEstimates estimates;
};

// e0 = flux per photon (lm), photons = N, the photons emitted so far: the plain run's
// estimates and every [[light_scene]]'s.
ResultEstimates estimate_result(const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> data,
                                double e0, std::uint64_t photons);
// The same on the tallies as a light scene weights them (all weights 1: the plain run). UGR
// takes each luminaire's luminance times its group's weight; the maintenance factors stay
// the plain run's.
ResultEstimates estimate_result(const EstimateScene& scene, const WeightedTallies& tallies, double e0,
                                std::uint64_t photons);
// A light scene's estimates: a run's [[light_scene]], or, after the run, any combination of
// a result's light groups (`luxtrace info --scene`, io/light_group_tallies.hpp).
LightSceneEstimates estimate_light_scene(const EstimateScene& scene, const LightScene& light_scene,
                                         const TallyLayout& layout, std::span<const std::uint64_t> data, double e0,
                                         std::uint64_t photons);

}  // namespace luxtrace
