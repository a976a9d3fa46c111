#pragma once
// A figure computed from noisy values, with its standard error and its bias, estimated by a
// parametric bootstrap with SIMEX (simulation-extrapolation; J. R. Cook and L. A. Stefanski,
// JASA 89, 1994). The observed figure already carries the values' noise (variance 1 s^2);
// replicate r adds that noise once more (lambda = 1: 2 s^2 in all) and sqrt(2) times it
// (lambda = 2: 3 s^2), the same draws for both so that their difference is smooth. g(lambda),
// the mean replicate figure, on the straight line through lambda = 1 and 2 meets zero noise
// (lambda = -1) at 3 g(1) - 2 g(2): the corrected figure. sigma: the spread at lambda = 1.
// Used by the daylight-factor quantiles and the annual metrics; docs/DAYLIGHT.md.

namespace luxtrace {

struct SimexEstimate {
    double value = 0.0, sigma = 0.0, bias = 0.0;  // bias = E[observed] - true
    double corrected() const { return value - bias; }
    // The bias is trusted to within its own size: sqrt(sigma^2 + bias^2).
    double uncertainty() const;
};

// Running sums of the replicates' figures, each taken relative to the observed figure (no
// cancellation in the sums).
class SimexSums {
public:
    // One replicate: its figure at lambda = 1 and at lambda = 2, minus the observed one.
    void add(double delta1, double delta2);
    // sigma and bias from the replicates so far (both 0 with fewer than 2).
    SimexEstimate estimate(double observed) const;

private:
    double sum1_ = 0.0, sum1_sq_ = 0.0, sum2_ = 0.0;
    int count_ = 0;
};

}  // namespace luxtrace
