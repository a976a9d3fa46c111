#include "luxtrace/stats/simex.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

double SimexEstimate::uncertainty() const { return std::hypot(sigma, bias); }

void SimexSums::add(double delta1, double delta2) {
    sum1_ += delta1;
    sum1_sq_ += delta1 * delta1;
    sum2_ += delta2;
    ++count_;
}

SimexEstimate SimexSums::estimate(double observed) const {
    SimexEstimate e;
    e.value = observed;
    if (count_ < 2) return e;
    const double g1 = sum1_ / count_, g2 = sum2_ / count_;  // relative to the observed value
    e.bias = -(3.0 * g1 - 2.0 * g2);
    e.sigma = std::sqrt(std::max(0.0, (sum1_sq_ - count_ * g1 * g1) / (count_ - 1)));
    return e;
}

}  // namespace luxtrace
