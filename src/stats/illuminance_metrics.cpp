#include "luxtrace/stats/illuminance_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace luxtrace {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// log Phi(t), -inf where Phi underflows.
double log_normal_cdf(double t) { return std::log(0.5 * std::erfc(-t / std::numbers::sqrt2)); }

// E[max_c X_c] for independent X_c ~ N(mean_c, sigma_c^2), cell c standing for
// `weight_c` identical cells: E[X] = lo + int_lo^hi (1 - F(x)) dx, F = prod Phi^w,
// with lo below which F vanishes and hi above which 1 - F does (composite Simpson).
double expected_maximum_weighted(std::span<const double> mean, std::span<const double> sigma,
                                 std::span<const double> weight) {
    double constant = -std::numeric_limits<double>::infinity();  // the largest sigma-0 cell
    double top_mean = -std::numeric_limits<double>::infinity(), top_sigma = 0.0, hi = constant, count = 0.0;
    for (std::size_t c = 0; c < mean.size(); ++c) {
        count += weight[c];
        if (!(sigma[c] > 0.0)) {
            constant = std::max(constant, mean[c]);
            continue;
        }
        if (mean[c] > top_mean) top_mean = mean[c], top_sigma = sigma[c];
    }
    if (top_sigma == 0.0) return constant;
    // P(max > x) <= count (1 - Phi(t)) < exp(-24.5), about 2e-11, past t = sqrt(2 ln count) + 7.
    const double tail = std::sqrt(2.0 * std::log(std::max(count, 1.0))) + 7.0;
    for (std::size_t c = 0; c < mean.size(); ++c)
        if (sigma[c] > 0.0) hi = std::max(hi, mean[c] + tail * sigma[c]);
    // F(x) <= Phi((x - top_mean) / top_sigma): negligible 9 sigma below the highest mean.
    const double lo = std::max(constant, top_mean - 9.0 * top_sigma);
    if (!(hi > lo)) return lo;
    auto survival = [&](double x) {
        double log_f = 0.0;
        for (std::size_t c = 0; c < mean.size() && std::isfinite(log_f); ++c)
            if (sigma[c] > 0.0) log_f += weight[c] * log_normal_cdf((x - mean[c]) / sigma[c]);
        return 1.0 - std::exp(log_f);
    };
    // Even, with a step of at most 0.05 of the narrowest cell's sigma (the width of the
    // finest feature of F): the tables of E[max] are then met to 2e-5 sigma
    // (illuminance_metrics_test).
    double narrowest = top_sigma;
    for (std::size_t c = 0; c < mean.size(); ++c)
        if (sigma[c] > 0.0) narrowest = std::min(narrowest, sigma[c]);
    const int n = 2 * static_cast<int>(std::clamp(std::ceil((hi - lo) / (0.1 * narrowest)), 100.0, 10000.0));
    const double h = (hi - lo) / n;
    double s = survival(lo) + survival(hi);
    for (int k = 1; k < n; ++k) s += (k % 2 == 1 ? 4.0 : 2.0) * survival(lo + k * h);
    return lo + s * h / 3.0;
}

}  // namespace

double expected_maximum(std::span<const double> mean, std::span<const double> sigma) {
    const std::vector<double> ones(mean.size(), 1.0);
    return expected_maximum_weighted(mean, sigma, ones);
}

double expected_extreme_bias(std::span<const double> sigma) {
    std::vector<double> s;
    for (double x : sigma)
        if (x > 0.0) s.push_back(x);
    if (s.size() <= 1) return 0.0;                                            // one noisy cell: E[sigma Z] = 0
    if (s.size() == 2) return std::hypot(s[0], s[1]) / std::sqrt(2.0 * kPi);  // max(a Z1, b Z2), exactly
    // Many cells: sigmas that agree to 0.1 % share one factor Phi^count (the cost then
    // does not grow with the grid; the bias changes by far less than 0.1 %).
    std::sort(s.begin(), s.end());
    std::vector<double> group_sigma, group_count;
    for (double x : s) {
        if (!group_sigma.empty() && x <= group_sigma.back() * 1.001 && group_count.back() < 1e300) {
            group_count.back() += 1.0;
            continue;
        }
        group_sigma.push_back(x);
        group_count.push_back(1.0);
    }
    const std::vector<double> zero(group_sigma.size(), 0.0);
    return expected_maximum_weighted(zero, group_sigma, group_count);
}

IlluminanceMetrics illuminance_metrics(std::span<const double> value, std::span<const double> sigma, int nx,
                                       const TaskArea& area, std::optional<double> avg_sigma_lx) {
    IlluminanceMetrics m;
    m.area = area.name;
    m.i0 = area.i0, m.i1 = area.i1, m.j0 = area.j0, m.j1 = area.j1;
    const int k = (area.i1 - area.i0) * (area.j1 - area.j0);
    if (k <= 0) return m;
    m.cells = static_cast<std::uint64_t>(k);
    auto at = [&](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + i; };
    auto sigma_of = [&](std::size_t c) { return std::isfinite(sigma[c]) ? sigma[c] : 0.0; };
    double sum = 0.0, sum_s2 = 0.0;
    bool missing = false;
    std::size_t cmin = at(area.i0, area.j0), cmax = cmin;
    m.min_i = m.max_i = area.i0;
    m.min_j = m.max_j = area.j0;
    for (int j = area.j0; j < area.j1; ++j)
        for (int i = area.i0; i < area.i1; ++i) {
            const std::size_t c = at(i, j);
            sum += value[c];
            sum_s2 += sigma_of(c) * sigma_of(c);
            missing = missing || !std::isfinite(sigma[c]);
            if (value[c] < value[cmin]) cmin = c, m.min_i = i, m.min_j = j;
            if (value[c] > value[cmax]) cmax = c, m.max_i = i, m.max_j = j;
        }
    m.avg_lx = sum / k;
    m.avg_sigma_lx = avg_sigma_lx.value_or(std::sqrt(sum_s2) / k);
    m.min_lx = value[cmin];
    m.max_lx = value[cmax];
    m.min_sigma_lx = sigma_of(cmin);
    m.max_sigma_lx = sigma_of(cmax);
    // The cells that could hold the extreme: within kCompetitorSigmas combined sigmas of it.
    // The bias the observed extreme would have if they shared one true value
    // (expected_extreme_bias) is exact for ties and larger than the true bias when their
    // true values differ (1.0 to 1.5 times in docs/VALIDATION.md case 6); a clear extreme
    // has no competitor and no bias.
    std::vector<double> low, high;
    for (int j = area.j0; j < area.j1; ++j)
        for (int i = area.i0; i < area.i1; ++i) {
            const std::size_t c = at(i, j);
            const double s = sigma_of(c);
            if (value[c] - m.min_lx <= kCompetitorSigmas * std::hypot(s, m.min_sigma_lx)) low.push_back(s);
            if (m.max_lx - value[c] <= kCompetitorSigmas * std::hypot(s, m.max_sigma_lx)) high.push_back(s);
        }
    m.min_competitors = low.size();
    m.max_competitors = high.size();
    m.min_bias_lx = -expected_extreme_bias(low);
    m.max_bias_lx = expected_extreme_bias(high);
    // U0 = Emin / Eavg: relative variances add, less twice the covariance of the two,
    // which is the minimum cell's own variance over K (it is one of the K cells averaged).
    const double r_min = m.min_lx > 0.0 ? m.min_sigma_lx / m.min_lx : kNaN;
    const double r_avg = m.avg_lx > 0.0 ? m.avg_sigma_lx / m.avg_lx : kNaN;
    const double r_max = m.max_lx > 0.0 ? m.max_sigma_lx / m.max_lx : kNaN;
    if (m.avg_lx > 0.0) {
        m.u0 = m.min_lx / m.avg_lx;
        m.u0_bias = m.min_bias_lx / m.avg_lx;
        const double cov = m.min_lx > 0.0 ? m.min_sigma_lx * m.min_sigma_lx / (k * m.min_lx * m.avg_lx) : 0.0;
        m.u0_sigma = m.min_lx > 0.0 ? m.u0 * std::sqrt(std::max(0.0, r_min * r_min + r_avg * r_avg - 2.0 * cov))
                                    : m.min_sigma_lx / m.avg_lx;
    } else {
        m.u0 = m.u0_sigma = m.u0_bias = kNaN;
    }
    if (m.max_lx > 0.0) {
        m.min_over_max = m.min_lx / m.max_lx;
        m.min_over_max_bias = m.min_over_max - (m.min_lx - m.min_bias_lx) / (m.max_lx - m.max_bias_lx);
        // Two different cells are independent; one cell (K = 1) gives exactly 1.
        m.min_over_max_sigma = cmin == cmax     ? 0.0
                               : m.min_lx > 0.0 ? m.min_over_max * std::hypot(r_min, r_max)
                                                : m.min_sigma_lx / m.max_lx;
    } else {
        m.min_over_max = m.min_over_max_sigma = m.min_over_max_bias = kNaN;
    }
    m.unreliable = missing || !(m.min_lx > 0.0) ||
                   std::max(-m.min_bias_lx, m.min_sigma_lx) > kUniformityNoiseLimit * m.min_lx;
    return m;
}

IlluminanceMetrics maintained(const IlluminanceMetrics& initial, double mf) {
    IlluminanceMetrics m = initial;
    for (double* x : {&m.avg_lx, &m.avg_sigma_lx, &m.min_lx, &m.min_sigma_lx, &m.min_bias_lx, &m.max_lx,
                      &m.max_sigma_lx, &m.max_bias_lx})
        *x *= mf;
    return m;
}

}  // namespace luxtrace
