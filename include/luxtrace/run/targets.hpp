#pragma once
// Stop criteria of [[run.target]]: the current value of each target from reduced
// tallies, and whether it is met.
#include "luxtrace/annual/direct_coefficients.hpp"
#include "luxtrace/scene/run_config.hpp"
#include "luxtrace/stats/estimates.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;

enum class TargetKind { relative_error, absolute_error, photons_received };

struct TargetStatus {
    TargetKind kind = TargetKind::relative_error;
    double value = 0.0;  // current error (relative, or lx / cd/m^2) or photons received
    double goal = 0.0;
    bool met = false;
    std::string label;  // e.g. "detector:desk rel (arith)"
};

TargetKind kind_of(const Target& t);

// The global estimates a reduction needs: [0] the plain run's, then one per light scene a
// target on the whole map reads. Each is weights for WeightedTallies (empty: plain); a
// distributed reduction has every rank sum its sides for each (stats/global_sums.hpp).
struct GlobalRequests {
    std::vector<std::vector<double>> weights;
    std::vector<std::size_t> of_target;  // per [[run.target]]: its estimate's index
};
GlobalRequests global_requests(const Scene& scene);

// `global` is the target's global estimate (GlobalRequests) for the same tallies; a target
// on a detector or an annual metric reads only the words after the surface map of `data`;
// an annual metric, also the run's direct coefficients by shadow rays (`direct`).
TargetStatus evaluate_target(const Target& t, const Scene& scene, const TallyLayout& layout,
                             std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                             const GlobalEstimate& global, const AnnualDirect& direct = {});

}  // namespace luxtrace
