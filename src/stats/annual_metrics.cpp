#include "luxtrace/stats/annual_metrics.hpp"

#include "luxtrace/core/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace luxtrace {

namespace {

// Shares compared with a requirement ("DA >= 50 %") are ratios of counts or weight sums,
// whose rounding must not move a share that meets the requirement exactly.
constexpr double kShareSlack = 1e-12;

void require(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("annual metrics: " + what);
}

// Every figure of m, in a fixed order (per-sensor vectors first, then the grid's figures):
// the replicates' sums and the sigma and bias layouts follow it.
template <class M, class F>
void each_figure(M& m, F&& f) {
    for (auto* v : {&m.sensors.da, &m.sensors.continuous_da, &m.sensors.udi_fell_short, &m.sensors.udi_useful,
                    &m.sensors.udi_exceeded, &m.sensors.ase_hours})
        for (auto& x : *v) f(x);
    for (auto* x : {&m.sda, &m.ase, &m.mean_da, &m.mean_continuous_da, &m.mean_udi_fell_short, &m.mean_udi_useful,
                    &m.mean_udi_exceeded})
        f(*x);
    for (auto& x : m.en17037_target_hours) f(x);
    for (auto& x : m.en17037_minimum_hours) f(x);
}

std::vector<double> flatten(const AnnualMetrics& m) {
    std::vector<double> out;
    each_figure(m, [&](double x) { out.push_back(x); });
    return out;
}

double weighted_mean(std::span<const double> x, std::span<const double> w, double w_sum) {
    double sum = 0.0;
    for (std::size_t s = 0; s < x.size(); ++s) sum += w[s] * x[s];
    return sum / w_sum;
}

}  // namespace

std::vector<std::uint8_t> en17037_daylight_hours(std::span<const double> outdoor_lx, std::size_t count) {
    if (count == 0) count = outdoor_lx.size() / 2;
    std::vector<std::size_t> lit;
    for (std::size_t h = 0; h < outdoor_lx.size(); ++h)
        if (outdoor_lx[h] > 0.0) lit.push_back(h);  // NaN compares false: not a daylight hour
    count = std::min(count, lit.size());
    std::stable_sort(lit.begin(), lit.end(),
                     [&](std::size_t a, std::size_t b) { return outdoor_lx[a] > outdoor_lx[b]; });
    std::vector<std::uint8_t> mask(outdoor_lx.size(), 0);
    for (std::size_t i = 0; i < count; ++i) mask[lit[i]] = 1;
    return mask;
}

namespace {

struct OccupiedThresholds {
    double da_lx, low_lx, high_lx, direct_lx;
};

// One occupied hour of a block's sensors into its sums (five arrays of n, from `sums`): DA,
// continuous DA, UDI fell short and exceeded, ASE. Each sensor's sums run over the hours in
// order, whatever the vector lanes: the same bits on any CPU.
__attribute__((target_clones("avx2", "default"))) void occupied_hour(const double* __restrict e,
                                                                     const double* __restrict d, std::size_t n,
                                                                     OccupiedThresholds t, double* __restrict sums) {
    double* __restrict da = sums;
    double* __restrict cda = sums + n;
    double* __restrict fell = sums + 2 * n;
    double* __restrict exceeded = sums + 3 * n;
    double* __restrict ase = sums + 4 * n;
    for (std::size_t c = 0; c < n; ++c) {
        da[c] += e[c] >= t.da_lx ? 1.0 : 0.0;
        cda[c] += std::min(1.0, e[c] / t.da_lx);
        fell[c] += e[c] < t.low_lx ? 1.0 : 0.0;
        exceeded[c] += e[c] > t.high_lx ? 1.0 : 0.0;
        ase[c] += d[c] >= t.direct_lx ? 1.0 : 0.0;
    }
}

// The area units of the sensors at or above each of two levels (integers: any order).
__attribute__((target_clones("avx2", "default"))) void area_above(const double* __restrict e,
                                                                  const std::int64_t* __restrict w, std::size_t n,
                                                                  double target, double minimum,
                                                                  std::int64_t* __restrict above) {
    std::int64_t at = 0, am = 0;
    for (std::size_t c = 0; c < n; ++c) {
        at += e[c] >= target ? w[c] : 0;
        am += e[c] >= minimum ? w[c] : 0;
    }
    above[0] = at;
    above[1] = am;
}

}  // namespace

AnnualMetricSums::AnnualMetricSums(const AnnualHours& hours, std::size_t sensors, const AnnualThresholds& t)
    : hours_(hours), t_(t), sensors_(sensors), target_units_(kEn17037Levels.size() * hours.occupied.size()),
      minimum_units_(kEn17037Levels.size() * hours.occupied.size()) {
    require(sensors > 0, "no sensors");
    require(hours.en17037_hours.size() == hours.occupied.size(), "the hour masks need one value an hour");
    require(hours.area_weights.empty() || hours.area_weights.size() == sensors, "area weights need one value a sensor");
    weight_ = hours.area_weights;
    if (weight_.empty()) weight_.assign(sensors, 1.0);
    const double w_max = *std::max_element(weight_.begin(), weight_.end());
    require(w_max > 0.0, "the area weights sum to zero");
    for (const double w : weight_) {
        weight_units_.push_back(std::llround(std::max(0.0, w) / w_max * 0x1p32));
        weight_units_sum_ += weight_units_.back();
    }
    for (const std::uint8_t o : hours.occupied) occupied_ += o != 0 ? 1 : 0;
    for (const std::uint8_t d : hours.en17037_hours) daylight_ += d != 0 ? 1 : 0;
    require(occupied_ > 0, "no occupied hour");
    require(daylight_ > 0, "no EN 17037 daylight hour");
    for (auto* v : {&sums_.da, &sums_.continuous_da, &sums_.udi_fell_short, &sums_.udi_useful, &sums_.udi_exceeded,
                    &sums_.ase_hours})
        v->assign(sensors, 0.0);
}

void AnnualMetricSums::add(const AnnualSeries& block, std::size_t first) {
    const std::size_t n_h = block.hours, n_s = block.sensors;
    require(n_h == hours_.occupied.size(), "the hour masks need one value an hour");
    require(block.total_lx.size() == n_h * n_s && block.direct_lx.size() == n_h * n_s,
            "total and direct illuminance need hours x sensors values");
    require(first + n_s <= sensors_, "a block beyond the grid's sensors");
    // The block's sums in arrays of its own (no other pointer reaches them: the loops
    // below run in vector lanes), added to the grid's at the end (each sensor is in one
    // block: 0 + its sum).
    std::vector<double> local(5 * n_s, 0.0);
    double* da = local.data();
    const std::int64_t* w = &weight_units_[first];
    const OccupiedThresholds occ{t_.da_lx, t_.udi_low_lx, t_.udi_high_lx, t_.ase_direct_lx};
    for (std::size_t h = 0; h < n_h; ++h) {
        const double* e = &block.total_lx[h * n_s];
        if (hours_.occupied[h] != 0) occupied_hour(e, &block.direct_lx[h * n_s], n_s, occ, da);
        if (hours_.en17037_hours[h] == 0) continue;
        for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
            std::int64_t above[2] = {0, 0};
            area_above(e, w, n_s, kEn17037Levels[l].target_lx, kEn17037Levels[l].minimum_lx, above);
            target_units_[l * n_h + h].fetch_add(above[0], std::memory_order_relaxed);
            minimum_units_[l * n_h + h].fetch_add(above[1], std::memory_order_relaxed);
        }
    }
    const double* cda = da + n_s;
    const double* fell = cda + n_s;
    const double* exceeded = fell + n_s;
    const double* ase = exceeded + n_s;
    AnnualMetrics::Sensors& s = sums_;
    for (std::size_t c = 0; c < n_s; ++c) {
        s.da[first + c] += da[c];
        s.continuous_da[first + c] += cda[c];
        s.udi_fell_short[first + c] += fell[c];
        s.udi_exceeded[first + c] += exceeded[c];
        s.ase_hours[first + c] += ase[c];
    }
}

std::size_t AnnualMetricSums::word_count(std::size_t sensors) const { return 5 * sensors + 2 * target_units_.size(); }

void AnnualMetricSums::to_words(std::size_t first, std::size_t last, std::vector<std::uint64_t>& out) const {
    require(first <= last && last <= sensors_, "words of sensors beyond the grid's");
    for (const std::vector<double>* v :
         {&sums_.da, &sums_.continuous_da, &sums_.udi_fell_short, &sums_.udi_exceeded, &sums_.ase_hours})
        for (std::size_t c = first; c < last; ++c) out.push_back(std::bit_cast<std::uint64_t>((*v)[c]));
    for (const auto* units : {&target_units_, &minimum_units_})
        for (const std::atomic<std::int64_t>& u : *units) out.push_back(static_cast<std::uint64_t>(u.load()));
}

std::size_t AnnualMetricSums::add_words(std::span<const std::uint64_t> words, std::size_t first, std::size_t last) {
    require(first <= last && last <= sensors_, "words of sensors beyond the grid's");
    const std::size_t n = word_count(last - first);
    require(words.size() >= n, "too few words for the sensors");
    std::size_t at = 0;
    for (std::vector<double>* v :
         {&sums_.da, &sums_.continuous_da, &sums_.udi_fell_short, &sums_.udi_exceeded, &sums_.ase_hours})
        for (std::size_t c = first; c < last; ++c) (*v)[c] += std::bit_cast<double>(words[at++]);
    for (auto* units : {&target_units_, &minimum_units_})
        for (std::atomic<std::int64_t>& u : *units)
            u.fetch_add(static_cast<std::int64_t>(words[at++]), std::memory_order_relaxed);
    return n;
}

AnnualMetrics AnnualMetricSums::metrics() const {
    const std::size_t n_h = hours_.occupied.size();
    const double w_sum = std::accumulate(weight_.begin(), weight_.end(), 0.0);
    AnnualMetrics m;
    m.sensors = sums_;
    AnnualMetrics::Sensors& s = m.sensors;
    const double n_occ = static_cast<double>(occupied_);
    double sda = 0.0, ase = 0.0;
    for (std::size_t c = 0; c < sensors_; ++c) {
        for (auto* v : {&s.da, &s.continuous_da, &s.udi_fell_short, &s.udi_exceeded}) (*v)[c] /= n_occ;
        s.udi_useful[c] = std::max(0.0, 1.0 - s.udi_fell_short[c] - s.udi_exceeded[c]);
        sda += s.da[c] >= t_.sda_da - kShareSlack ? weight_[c] : 0.0;
        ase += s.ase_hours[c] > t_.ase_hours ? weight_[c] : 0.0;
    }
    m.sda = sda / w_sum;
    m.ase = ase / w_sum;
    m.mean_da = weighted_mean(s.da, weight_, w_sum);
    m.mean_continuous_da = weighted_mean(s.continuous_da, weight_, w_sum);
    m.mean_udi_fell_short = weighted_mean(s.udi_fell_short, weight_, w_sum);
    m.mean_udi_useful = weighted_mean(s.udi_useful, weight_, w_sum);
    m.mean_udi_exceeded = weighted_mean(s.udi_exceeded, weight_, w_sum);
    const double units = static_cast<double>(weight_units_sum_);
    for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
        std::size_t target_met = 0, minimum_met = 0;
        for (std::size_t h = 0; h < n_h; ++h) {
            if (hours_.en17037_hours[h] == 0) continue;
            const double above_target = static_cast<double>(target_units_[l * n_h + h].load());
            const double above_minimum = static_cast<double>(minimum_units_[l * n_h + h].load());
            target_met += above_target >= (kEn17037TargetArea - kShareSlack) * units ? 1 : 0;
            minimum_met += above_minimum >= (kEn17037MinimumArea - kShareSlack) * units ? 1 : 0;
        }
        m.en17037_target_hours[l] = static_cast<double>(target_met) / static_cast<double>(daylight_);
        m.en17037_minimum_hours[l] = static_cast<double>(minimum_met) / static_cast<double>(daylight_);
    }
    return m;
}

AnnualMetrics annual_metrics(const AnnualSeries& series, const AnnualHours& hours, const AnnualThresholds& t) {
    require(hours.occupied.size() == series.hours, "the hour masks need one value an hour");
    AnnualMetricSums sums(hours, series.sensors, t);
    sums.add(series, 0);
    return sums.metrics();
}

VerdictFlip judge_threshold(const SimexEstimate& m, double target, bool pass_at_or_above) {
    const double c = m.corrected();
    VerdictFlip v;
    v.pass = pass_at_or_above ? c >= target - kShareSlack : c <= target + kShareSlack;
    const double u = m.uncertainty();
    v.flip_probability = u > 0.0 ? 0.5 * std::erfc(std::abs(c - target) / (u * std::numbers::sqrt2)) : 0.0;
    return v;
}

namespace {

// The errors from the replicates' figures (value: the estimate's metrics).
AnnualEstimate finish_estimate(AnnualMetrics value, const AnnualMetrics& centre_metrics,
                               const std::vector<AnnualMetrics>& replicate_metrics, const AnnualHours& hours) {
    const int k = static_cast<int>(replicate_metrics.size());
    AnnualEstimate e;
    e.value = std::move(value);
    const std::vector<double> centre = flatten(centre_metrics);
    // Sums relative to the centre's figure (no cancellation).
    std::vector<double> sum(centre.size(), 0.0), sum_sq(centre.size(), 0.0);
    for (const AnnualMetrics& m : replicate_metrics) {
        const std::vector<double> x = flatten(m);
        for (std::size_t i = 0; i < centre.size(); ++i) {
            const double d = x[i] - centre[i];
            sum[i] += d;
            sum_sq[i] += d * d;
        }
    }
    e.replicates = k;
    e.sigma = e.value;
    e.bias = e.value;
    std::size_t i = 0;
    each_figure(e.sigma, [&](double& x) {
        x = k > 1 ? std::sqrt(std::max(0.0, (sum_sq[i] - sum[i] * sum[i] / k) / (k - 1))) : 0.0;
        ++i;
    });
    i = 0;
    each_figure(e.bias, [&](double& x) {
        x = k > 0 ? sum[i] / k : 0.0;
        ++i;
    });
    // Where the noise is large (few photons) the bias can overshoot: the corrected figure is
    // kept within the figure's range, [0, 1] for shares and [0,
    // occupied hours] for ASE hours.
    AnnualMetrics upper = e.value;
    each_figure(upper, [](double& x) { x = 1.0; });
    const double occupied = static_cast<double>(std::count(hours.occupied.begin(), hours.occupied.end(), 1));
    for (double& x : upper.sensors.ase_hours) x = occupied;
    const std::vector<double> values = flatten(e.value), uppers = flatten(upper);
    i = 0;
    each_figure(e.bias, [&](double& b) {
        const double v = values[i], corrected = std::clamp(v - b, 0.0, uppers[i]);
        b = v - corrected;
        ++i;
    });
    // A level passes when both criteria do; the truth passes with P(a) P(b).
    for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
        // Judged on the corrected share, value - bias, with the bias in the uncertainty as
        // well (judge_threshold): measured on the annual office, the corrected shares lie
        // within 0.5-2.6 sigma of a 10 times longer run, the raw ones up to 7 sigma
        // (docs/VALIDATION.md §9.1).
        const auto criterion = [&](const std::array<double, 3> AnnualMetrics::*f) {
            return judge_threshold({(e.value.*f)[l], (e.sigma.*f)[l], (e.bias.*f)[l]}, kEn17037HoursShare);
        };
        const VerdictFlip a = criterion(&AnnualMetrics::en17037_target_hours);
        const VerdictFlip b = criterion(&AnnualMetrics::en17037_minimum_hours);
        const double true_pass = (a.pass ? 1.0 - a.flip_probability : a.flip_probability) *
                                 (b.pass ? 1.0 - b.flip_probability : b.flip_probability);
        e.en17037[l].pass = a.pass && b.pass;
        e.en17037[l].flip_probability = e.en17037[l].pass ? 1.0 - true_pass : true_pass;
    }
    return e;
}

}  // namespace

AnnualMetricDraws::AnnualMetricDraws(const AnnualHours& hours, std::size_t sensors, const AnnualThresholds& t, int k)
    : hours_(hours), sensors_(sensors), replicates_(static_cast<std::size_t>(std::max(0, k))) {
    for (std::size_t i = 0; i < (replicates_ > 0 ? replicates_ + 2 : 1); ++i)
        sums_.push_back(std::make_unique<AnnualMetricSums>(hours, sensors, t));
}

void AnnualMetricDraws::run(const AnnualBlockDraws& draws, std::size_t block, std::size_t first, std::size_t last) {
    require(block > 0, "blocks of no sensors");
    require(first % block == 0 && first <= last && last <= sensors_, "a part of whole blocks within the grid");
    const std::size_t first_block = first / block, blocks = (last - first + block - 1) / block;
    for_each_index(blocks, 1, [&](std::size_t i) {
        const std::size_t b0 = (first_block + i) * block, count = std::min(block, sensors_ - b0);
        const AnnualSink at = [&](AnnualDraw what, std::size_t r, const AnnualSeries& series) {
            const std::size_t j = what == AnnualDraw::estimate ? 0 : what == AnnualDraw::centre ? 1 : 2 + r;
            require(series.sensors == count, "a block's series of another size");
            if (j < sums_.size()) sums_[j]->add(series, b0);
        };
        draws(b0, count, at);
    });
}

std::size_t AnnualMetricDraws::word_count(std::size_t hours, std::size_t sensors, int k) {
    const std::size_t draws = k > 0 ? static_cast<std::size_t>(k) + 2 : 1;
    return draws * (5 * sensors + 2 * kEn17037Levels.size() * hours);
}

std::vector<std::uint64_t> AnnualMetricDraws::words(std::size_t first, std::size_t last) const {
    std::vector<std::uint64_t> out;
    for (const auto& s : sums_) s->to_words(first, last, out);
    return out;
}

void AnnualMetricDraws::merge(std::span<const std::uint64_t> words, std::size_t first, std::size_t last) {
    std::size_t at = 0;
    for (const auto& s : sums_) at += s->add_words(words.subspan(at), first, last);
    require(at == words.size(), "more words than the sensors' sums");
}

AnnualEstimate AnnualMetricDraws::estimate() const {
    if (replicates_ == 0) {
        AnnualEstimate e;
        e.value = sums_[0]->metrics();
        return e;
    }
    std::vector<AnnualMetrics> replicate_metrics;
    for (std::size_t r = 0; r < replicates_; ++r) replicate_metrics.push_back(sums_[2 + r]->metrics());
    return finish_estimate(sums_[0]->metrics(), sums_[1]->metrics(), replicate_metrics, hours_);
}

AnnualEstimate estimate_annual_metrics(const AnnualBlockDraws& draws, std::size_t sensors, std::size_t block,
                                       const AnnualHours& hours, const AnnualThresholds& t, int k) {
    AnnualMetricDraws d(hours, sensors, t, k);
    d.run(draws, block, 0, sensors);
    return d.estimate();
}

AnnualEstimate estimate_annual_metrics(const AnnualReplicates& replicates, const AnnualHours& hours,
                                       const AnnualThresholds& t, int k) {
    AnnualSeries series;
    replicates(AnnualDraw::estimate, 0, series);
    const AnnualMetrics value = annual_metrics(series, hours, t);
    replicates(AnnualDraw::centre, 0, series);
    const AnnualMetrics centre = annual_metrics(series, hours, t);
    std::vector<AnnualMetrics> replicate_metrics;
    for (int r = 0; r < k; ++r) {
        replicates(AnnualDraw::replicate, static_cast<std::size_t>(r), series);
        replicate_metrics.push_back(annual_metrics(series, hours, t));
    }
    return finish_estimate(value, centre, replicate_metrics, hours);
}

}  // namespace luxtrace
