#pragma once
// What the result stores of an observer (/observers/NAME): UGR (CIE 117, glare/ugr.hpp)
// from the eye detector's indirect illuminance and the luminaires' terms fixed at load.
#include "luxtrace/glare/observer.hpp"
#include "luxtrace/glare/ugr.hpp"
#include "luxtrace/stats/estimates.hpp"

#include <optional>

namespace luxtrace {

struct ObserverEstimate {
    UgrEstimate ugr;
    // With maintained luminaires: L^2 / Lb scales as a maintenance factor all lights share,
    // so UGR moves by 8 log10(mf). Only when the factor is shared and below 1.
    std::optional<double> ugr_maintained;
};

// `eye` is the estimate of o.eye_detector; `maintenance_factor` the lights' flux-weighted
// one, `maintenance_uniform` whether all lights share it.
ObserverEstimate estimate_observer(const Observer& o, const DetectorEstimate& eye, double maintenance_factor,
                                   bool maintenance_uniform);

}  // namespace luxtrace
