#include "luxtrace/stats/daylight_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace luxtrace {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The bootstrap's cost is cells x replicates; past this product the replicates shrink
// (to no fewer than kMinReplicates): about 0.1 s for 10^4 cells (400 replicates) and
// 0.25 s for 10^5 (100), per grid or task area and result write.
constexpr double kMaxBootstrapDraws = 1e7;
constexpr int kMinReplicates = 50;

// splitmix64 (Steele, Lea & Flood 2014): a counter-based stream, so the bootstrap's
// draws depend on (replicate, cell) only and every run of the same numbers agrees.
std::uint64_t splitmix64(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double uniform_open(std::uint64_t& state) { return (static_cast<double>(splitmix64(state) >> 11) + 0.5) * 0x1p-53; }

// Standard normal pairs by Box-Muller.
struct NormalStream {
    std::uint64_t state;
    double spare = 0.0;
    bool has_spare = false;
    double next() {
        if (has_spare) {
            has_spare = false;
            return spare;
        }
        const double r = std::sqrt(-2.0 * std::log(uniform_open(state)));
        const double phi = 2.0 * std::numbers::pi * uniform_open(state);
        spare = r * std::sin(phi);
        has_spare = true;
        return r * std::cos(phi);
    }
};

// 0-based rank of "exceeded over `fraction`" among k sorted values (exceeded_over).
std::size_t exceeded_rank(std::size_t k, double fraction) {
    const double need = std::ceil(fraction * static_cast<double>(k) - 1e-9);
    const double rank = static_cast<double>(k) - std::clamp(need, 1.0, static_cast<double>(k));
    return static_cast<std::size_t>(rank);
}

double quantile_in_place(std::vector<double>& x, double fraction) {
    const auto it = x.begin() + static_cast<std::ptrdiff_t>(exceeded_rank(x.size(), fraction));
    std::nth_element(x.begin(), it, x.end());
    return *it;
}

// Several quantiles of the same cells from one set of bootstrap replicates (SimexSums: the
// noise added once and sqrt(2) times with the same draws, extrapolated to no noise). It only
// uses smoothed quantiles, so it scatters no more than the raw one; 2 q(x) - g(1), the plain
// bootstrap correction, has the same mean but 1.5 times the scatter.
std::vector<QuantileEstimate> noisy_quantiles(std::span<const double> value, std::span<const double> sigma,
                                              std::span<const double> fractions, int replicates) {
    std::vector<QuantileEstimate> out(fractions.size());
    if (value.empty()) return out;
    std::vector<double> x(value.begin(), value.end());
    for (std::size_t f = 0; f < fractions.size(); ++f) out[f].value = quantile_in_place(x, fractions[f]);
    const bool noisy = std::any_of(sigma.begin(), sigma.end(), [](double s) { return s > 0.0; });
    if (!noisy || replicates < 2) return out;
    const double k = static_cast<double>(value.size());
    const int r_count = std::max(kMinReplicates, std::min(replicates, static_cast<int>(kMaxBootstrapDraws / k)));
    std::vector<SimexSums> sums(fractions.size());
    std::vector<double> z(value.size()), x2(value.size());
    for (int r = 0; r < r_count; ++r) {
        NormalStream normal{0x5eed0000ull + static_cast<std::uint64_t>(r) * 0x100000001b3ull};
        for (std::size_t c = 0; c < value.size(); ++c) {
            z[c] = sigma[c] > 0.0 ? sigma[c] * normal.next() : 0.0;
            x[c] = value[c] + z[c];
            x2[c] = value[c] + std::numbers::sqrt2 * z[c];
        }
        for (std::size_t f = 0; f < fractions.size(); ++f) {
            const double q1 = quantile_in_place(x, fractions[f]) - out[f].value;
            sums[f].add(q1, quantile_in_place(x2, fractions[f]) - out[f].value);
        }
    }
    for (std::size_t f = 0; f < fractions.size(); ++f) out[f] = sums[f].estimate(out[f].value);
    return out;
}

}  // namespace

const char* verdict_name(Verdict v) {
    switch (v) {
    case Verdict::pass: return "pass";
    case Verdict::fail: return "fail";
    case Verdict::undecided: return "undecided";
    }
    return "?";
}

CriterionVerdict judge(const QuantileEstimate& q, double target) {
    const double v = q.corrected();
    const double reach = kVerdictSigmas * q.uncertainty();
    if (v - reach >= target) return {Verdict::pass, 0.0};
    if (v + reach < target) return {Verdict::fail, 0.0};
    const double gap = std::abs(v - target);
    const double factor = gap > 0.0 ? (reach / gap) * (reach / gap) : std::numeric_limits<double>::infinity();
    return {Verdict::undecided, factor > kUndecidableFactor ? std::numeric_limits<double>::infinity() : factor};
}

std::string decide_hint(const CriterionVerdict& v, const QuantileEstimate& q, double target) {
    if (v.verdict != Verdict::undecided) return "";
    char buf[160];
    if (std::isinf(v.photons_factor))
        std::snprintf(buf, sizeof buf, "cannot decide: the value equals the target within %.2g %%",
                      std::max(std::abs(q.corrected() - target), kVerdictSigmas * q.uncertainty()));
    else std::snprintf(buf, sizeof buf, "about %.3g x the photons would decide it", v.photons_factor);
    return buf;
}

double exceeded_over(std::span<const double> values, double fraction) {
    if (values.empty()) return kNaN;
    std::vector<double> x(values.begin(), values.end());
    return quantile_in_place(x, fraction);
}

QuantileEstimate noisy_quantile(std::span<const double> value, std::span<const double> sigma, double fraction,
                                int replicates) {
    const double f[1] = {fraction};
    return noisy_quantiles(value, sigma, f, replicates).front();
}

std::vector<double> daylight_factor_pct(std::span<const double> illuminance_lx, double reference_lx) {
    std::vector<double> df(illuminance_lx.size());
    for (std::size_t c = 0; c < df.size(); ++c) df[c] = 100.0 * illuminance_lx[c] / reference_lx;
    return df;
}

DaylightAreaMetrics daylight_area_metrics(std::span<const double> df, std::span<const double> df_sigma, int nx,
                                          const TaskArea& area, const En17037Targets* targets) {
    DaylightAreaMetrics m;
    m.area = area.name;
    std::vector<double> v, s;
    for (int j = area.j0; j < area.j1; ++j)
        for (int i = area.i0; i < area.i1; ++i) {
            const std::size_t c = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + i;
            const bool empty = !std::isfinite(df_sigma[c]);
            m.cells_without_photons += empty ? 1 : 0;
            v.push_back(df[c]);
            s.push_back(empty ? 0.0 : df_sigma[c]);
        }
    m.cells = v.size();
    if (v.empty()) return m;
    double sum = 0.0, sum_s2 = 0.0;
    for (std::size_t c = 0; c < v.size(); ++c) sum += v[c], sum_s2 += s[c] * s[c];
    m.mean_df = sum / v.size();
    m.mean_df_sigma = std::sqrt(sum_s2) / v.size();
    const double fractions[2] = {0.5, 0.95};
    const std::vector<QuantileEstimate> q = noisy_quantiles(v, s, fractions, kQuantileBootstrapReplicates);
    m.median = q[0];
    m.df_95 = q[1];
    if (targets == nullptr) return m;
    m.has_targets = true;
    m.targets = *targets;
    m.target_verdict = judge(m.median, targets->target_df);
    m.minimum_verdict = judge(m.df_95, targets->minimum_df);
    const Verdict a = m.target_verdict.verdict, b = m.minimum_verdict.verdict;
    if (a == Verdict::fail || b == Verdict::fail) m.overall = Verdict::fail;
    else if (a == Verdict::pass && b == Verdict::pass) m.overall = Verdict::pass;
    else {
        m.overall = Verdict::undecided;
        m.overall_photons_factor = std::max(m.target_verdict.photons_factor, m.minimum_verdict.photons_factor);
    }
    return m;
}

DaylightEstimate estimate_daylight(const Detector& d, std::span<const double> illuminance_lx,
                                   std::span<const double> sigma_lx, double reference_lx) {
    DaylightEstimate e;
    e.reference_lx = reference_lx;
    e.df = daylight_factor_pct(illuminance_lx, reference_lx);
    e.df_sigma = daylight_factor_pct(sigma_lx, reference_lx);  // E_h,ext is exact: sigma scales
    const En17037Targets* targets = d.en17037 ? &*d.en17037 : nullptr;
    e.areas.push_back(daylight_area_metrics(e.df, e.df_sigma, d.nx, TaskArea{"", 0, d.nx, 0, d.ny}, targets));
    for (const TaskArea& a : d.task_areas) e.areas.push_back(daylight_area_metrics(e.df, e.df_sigma, d.nx, a, targets));
    return e;
}

}  // namespace luxtrace
