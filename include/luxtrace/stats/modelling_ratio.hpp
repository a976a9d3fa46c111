#pragma once
// Modelling (EN 12464-1): the ratio of cylindrical to horizontal illuminance at a point,
// from a cylindrical detector and the illuminance detector on the same grid.
#include "luxtrace/stats/estimates.hpp"

#include <cstddef>
#include <vector>

namespace luxtrace {

struct ModellingRatio {
    std::vector<double> ratio;      // [ny][nx][B]: E_c / E_h per point and band; NaN where E_h is 0
    std::vector<double> sigma_rel;  // [ny][nx][B]
    // <E_c> / <E_h>: the ratio of the two grid means, and its relative error.
    double mean = 0.0;
    double mean_sigma_rel = 0.0;
    // The least and the largest ratio over the points (bands summed); NaN if no point has
    // horizontal illuminance.
    double min = 0.0, max = 0.0;
};

// First-order propagation: sigma_rel(E_c / E_h)^2 = sigma_rel(E_c)^2 + sigma_rel(E_h)^2.
// It leaves out -2 cov / (E_c E_h), the covariance of the two counts, which photons
// crossing both a cell and its point's cylinder make positive (dropping it can only make
// the error larger) and which is otherwise of order -1/N (eq. 8's own correction).
ModellingRatio modelling_ratio(const DetectorEstimate& cylindrical, const DetectorEstimate& horizontal,
                               std::size_t bands);

}  // namespace luxtrace
