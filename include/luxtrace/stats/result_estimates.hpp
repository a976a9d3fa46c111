#pragma once
// Everything a result file stores that is computed from the counts: rank 0 computes it
// before each write, and the writer (io/result_file.hpp) only writes these numbers. To add
// a group of estimates (e.g. per light group or light scene): a member here, filled in
// estimate_result, written by one part of the writer (src/io/result_parts.hpp).
#include "luxtrace/glare/observer_estimate.hpp"
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/stats/illuminance_metrics.hpp"
#include "luxtrace/stats/modelling_ratio.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

struct ResultEstimates {
    GlobalEstimate global;
    SurfaceMaps surface;
    std::vector<DetectorEstimate> detectors;  // per Scene::detectors, eye detectors included
    // Per detector, parallel to detectors[d].metrics: the metrics times the lights'
    // flux-weighted maintenance factor.
    std::vector<std::vector<IlluminanceMetrics>> maintained_metrics;
    // Per detector: cylindrical detectors with a `horizontal` detector only.
    std::vector<std::optional<ModellingRatio>> modelling;
    std::vector<ObserverEstimate> observers;  // per Scene::observers
};

// e0 = flux per photon (lm), photons = N, the photons emitted so far.
ResultEstimates estimate_result(const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> data,
                                double e0, std::uint64_t photons);

}  // namespace luxtrace
