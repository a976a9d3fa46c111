#pragma once
// An annual run's figures per detector (issue 24, docs/ANNUAL.md): every hour's illuminance
// and direct sun with their standard errors (annual_illuminance.hpp), and the annual metrics
// with their errors, biases and verdict flip probabilities (stats/annual_metrics.hpp).
#include "luxtrace/annual/annual_illuminance.hpp"
#include "luxtrace/stats/annual_metrics.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;
struct Detector;

struct AnnualDetectorEstimate {
    AnnualSeries value, sigma;
    AnnualEstimate metrics;
};

// The hours LM-83 and EN 17037 count (occupied; EN 17037's daylight hours: the half of the
// year with the most diffuse horizontal illuminance, annual_metrics.hpp).
AnnualHours annual_hours(const AnnualSetup& annual);

// Whether a detector is a sensor grid of an annual run: illuminance and points detectors.
bool annual_grid(const Detector& d);

// One sensor grid (Scene::detectors[det], annual_grid): its metrics with their errors from
// `replicates` replicate years (0: the values alone), and, with `series`, every hour's
// values and their errors (value, sigma). The replicates' draws depend on the run's seed and
// the detector, so a target and the result agree.
AnnualDetectorEstimate estimate_annual_grid(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                            std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                            int replicates, bool series);

// Per Scene::detectors (empty for a scene without [annual]; std::nullopt for detectors that
// are not sensor grids). e0 = flux per photon, photons = N. `replicates` for the metrics'
// errors (0: no errors, for checkpoints).
std::vector<std::optional<AnnualDetectorEstimate>> estimate_annual(const Scene& scene, const TallyLayout& layout,
                                                                   std::span<const std::uint64_t> data, double e0,
                                                                   std::uint64_t photons, int replicates);

}  // namespace luxtrace
