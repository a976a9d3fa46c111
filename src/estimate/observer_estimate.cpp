#include "luxtrace/estimate/observer_estimate.hpp"

#include <cmath>

namespace luxtrace {

ObserverEstimate estimate_observer(const Observer& o, const DetectorEstimate& eye, double maintenance_factor,
                                   bool maintenance_uniform) {
    ObserverEstimate out;
    out.ugr = estimate_ugr(o.sources, eye.mean_value, eye.mean_sigma_rel);
    if (maintenance_uniform && maintenance_factor < 1.0)
        out.ugr_maintained = out.ugr.ugr + 8.0 * std::log10(maintenance_factor);
    return out;
}

}  // namespace luxtrace
