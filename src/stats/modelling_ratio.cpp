#include "luxtrace/stats/modelling_ratio.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxtrace {

ModellingRatio modelling_ratio(const DetectorEstimate& c, const DetectorEstimate& h, std::size_t bands) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    ModellingRatio m;
    const std::size_t n = std::min(c.value.size(), h.value.size());
    m.ratio.assign(n, nan);
    m.sigma_rel.assign(n, nan);
    auto quadrature = [](double a, double b) { return std::sqrt(a * a + b * b); };
    for (std::size_t i = 0; i < n; ++i)
        if (h.value[i] > 0.0) {
            m.ratio[i] = c.value[i] / h.value[i];
            m.sigma_rel[i] = quadrature(c.sigma_rel[i], h.sigma_rel[i]);
        }
    m.mean = h.mean_value > 0.0 ? c.mean_value / h.mean_value : nan;
    m.mean_sigma_rel = h.mean_value > 0.0 ? quadrature(c.mean_sigma_rel, h.mean_sigma_rel) : nan;
    m.min = nan;
    m.max = nan;
    for (std::size_t p = 0; bands > 0 && (p + 1) * bands <= n; ++p) {
        double ec = 0.0, eh = 0.0;
        for (std::size_t b = 0; b < bands; ++b) {
            ec += c.value[p * bands + b];
            eh += h.value[p * bands + b];
        }
        if (!(eh > 0.0)) continue;
        const double r = ec / eh;
        m.min = std::isnan(m.min) ? r : std::min(m.min, r);
        m.max = std::isnan(m.max) ? r : std::max(m.max, r);
    }
    return m;
}

}  // namespace luxtrace
