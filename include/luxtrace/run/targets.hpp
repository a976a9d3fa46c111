#pragma once
// Stop criteria of [[run.target]]: the current value of each target from reduced
// tallies, and whether it is met.
#include "luxtrace/scene/run_config.hpp"
#include "luxtrace/stats/estimates.hpp"

#include <cstdint>
#include <span>
#include <string>

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

// `global` is estimate_global's answer for the same tallies (computed once per
// reduction for all targets).
TargetStatus evaluate_target(const Target& t, const Scene& scene, const TallyLayout& layout,
                             std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                             const GlobalEstimate& global);

}  // namespace luxtrace
