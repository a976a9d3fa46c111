#pragma once
// Annual climate-based daylight metrics of one sensor grid, with their statistical errors.
// The hourly illuminance of a sensor is a linear combination of daylight coefficients that
// carry Monte Carlo errors, so a threshold metric (a count of hours crossing a threshold) has
// an error and a bias (noise smooths the counts towards the threshold's middle). Definitions:
// IES LM-83-12 (DA, sDA300/50%, ASE1000,250h), Nabil & Mardaljevic 2005 (UDI), Rogers 2006
// (continuous DA), EN 17037:2018 Annex A (illuminance method). The errors come from a
// parametric bootstrap: replicate series of fresh runs drawn around a centre
// (AnnualReplicates). Pure functions; docs/DAYLIGHT.md "Annual metrics".
#include "luxtrace/stats/simex.hpp"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace luxtrace {

// One grid's hourly illuminance, hour-major: value [h * sensors + s] in lx.
struct AnnualSeries {
    std::size_t hours = 0, sensors = 0;
    std::vector<double> total_lx;   // everything: sky, sun, interreflections
    std::vector<double> direct_lx;  // direct sun only (LM-83's ASE)
};

// Which hours count, and how much area each sensor stands for.
struct AnnualHours {
    std::vector<std::uint8_t> occupied;       // [hours], 1: occupied (LM-83: 8:00-18:00 local standard time)
    std::vector<std::uint8_t> en17037_hours;  // [hours], 1: an EN 17037 daylight hour (en17037_daylight_hours)
    std::vector<double> area_weights;         // [sensors]; empty: all equal
};

struct AnnualThresholds {
    double da_lx = 300.0;           // DA and continuous DA
    double udi_low_lx = 100.0;      // UDI fell short below, useful from
    double udi_high_lx = 3000.0;    // UDI useful up to, exceeded above
    double sda_da = 0.5;            // sDA counts sensors with DA >= this (LM-83: 50 % of occupied hours)
    double ase_direct_lx = 1000.0;  // ASE: direct sun at or above ...
    double ase_hours = 250.0;       // ... for more than this many occupied hours
};

// EN 17037's illuminance method, per level: the target illuminance over 50 % of the plane
// and the minimum target illuminance over 95 % of it, each for at least 50 % of the daylight
// hours.
struct En17037Level {
    const char* name;
    double target_lx, minimum_lx;
};
inline constexpr std::array<En17037Level, 3> kEn17037Levels = {
    {{"minimum", 300.0, 100.0}, {"medium", 500.0, 300.0}, {"high", 750.0, 500.0}}};
inline constexpr double kEn17037TargetArea = 0.5, kEn17037MinimumArea = 0.95, kEn17037HoursShare = 0.5;

// The EN 17037 daylight hours: the `count` hours with the most outdoor illuminance (pass the
// weather file's diffuse horizontal illuminance to follow ClimateStudio's reading, the hours
// whose median gives the standard's E_v,d,med), ties to the earlier hour; hours without
// daylight (<= 0 or NaN) never count. count 0: half the hours (4380 of 8760).
std::vector<std::uint8_t> en17037_daylight_hours(std::span<const double> outdoor_lx, std::size_t count = 0);

// The metrics; fractions in [0, 1]. A sensor's figures are over the occupied hours, the
// grid's are area-weighted.
struct AnnualMetrics {
    struct Sensors {
        std::vector<double> da;              // share of occupied hours with E >= da_lx
        std::vector<double> continuous_da;   // mean over occupied hours of min(1, E / da_lx)
        std::vector<double> udi_fell_short;  // E < udi_low_lx
        std::vector<double> udi_useful;      // udi_low_lx <= E <= udi_high_lx
        std::vector<double> udi_exceeded;    // E > udi_high_lx
        std::vector<double> ase_hours;       // occupied hours with direct >= ase_direct_lx
    } sensors;
    double sda = 0.0;  // area share with DA >= sda_da
    double ase = 0.0;  // area share with ase_hours > ASE's hours
    double mean_da = 0.0, mean_continuous_da = 0.0;
    double mean_udi_fell_short = 0.0, mean_udi_useful = 0.0, mean_udi_exceeded = 0.0;
    // Per EN 17037 level: the share of the daylight hours at which the target (minimum)
    // illuminance reaches 50 % (95 %) of the area; the level passes when both are >= 50 %.
    std::array<double, 3> en17037_target_hours{}, en17037_minimum_hours{};
};

// The grid figures a run target may be on (`on = "annual:GRID:NAME"`), by their names in
// the result's /annual attributes.
struct AnnualGridFigure {
    const char* name;
    double AnnualMetrics::*member;
};
inline constexpr AnnualGridFigure kAnnualTargetFigures[] = {{"sda", &AnnualMetrics::sda},
                                                            {"ase", &AnnualMetrics::ase},
                                                            {"mean_da", &AnnualMetrics::mean_da},
                                                            {"mean_continuous_da", &AnnualMetrics::mean_continuous_da},
                                                            {"mean_udi_fell_short",
                                                             &AnnualMetrics::mean_udi_fell_short},
                                                            {"mean_udi_useful", &AnnualMetrics::mean_udi_useful},
                                                            {"mean_udi_exceeded", &AnnualMetrics::mean_udi_exceeded}};

// Bad sizes or no occupied or daylight hour throw std::invalid_argument (the caller's bug).
AnnualMetrics annual_metrics(const AnnualSeries& series, const AnnualHours& hours, const AnnualThresholds& t = {});

// The metrics of one grid's series, gathered in blocks of sensors: add() each block's
// series (hours x its sensors), from any thread, in any order, then metrics() gives the
// same figures, to the bit, however the grid was split. The per-hour area shares of
// EN 17037 are sums of integer weights (each sensor's area weight in units of 2^-32 of the
// largest), exact in any order; the grid means are summed in sensor order by metrics().
class AnnualMetricSums {
public:
    AnnualMetricSums(const AnnualHours& hours, std::size_t sensors, const AnnualThresholds& t = {});
    // Sensors [first, first + block.sensors); blocks must not overlap.
    void add(const AnnualSeries& block, std::size_t first);
    AnnualMetrics metrics() const;
    // What sensors [first, last) added (their sums, bit for bit) and the hours' area units,
    // appended to `out` as word_count(last - first) words; add_words() adds another part's
    // (its sensors none of this one's) as add() would have. Returns the words it read.
    std::size_t word_count(std::size_t sensors) const;
    void to_words(std::size_t first, std::size_t last, std::vector<std::uint64_t>& out) const;
    std::size_t add_words(std::span<const std::uint64_t> words, std::size_t first, std::size_t last);

private:
    const AnnualHours& hours_;
    AnnualThresholds t_;
    std::size_t sensors_ = 0, occupied_ = 0, daylight_ = 0;
    std::vector<double> weight_;              // [sensors], the area weights
    std::vector<std::int64_t> weight_units_;  // [sensors], the same as integers
    std::int64_t weight_units_sum_ = 0;
    AnnualMetrics::Sensors sums_;  // per sensor, the hours' sums (not yet divided)
    std::vector<std::atomic<std::int64_t>> target_units_, minimum_units_;  // [level x hours]
};

// The hourly series a grid's errors come from (estimate/annual_coefficients.hpp): the run's
// own estimate; the centre the replicates are drawn around (what the data say a fresh run's
// expected values are); replicate r, one fresh run's values drawn around that centre.
// Replicates are independent of each other.
enum class AnnualDraw { estimate, centre, replicate };
using AnnualReplicates = std::function<void(AnnualDraw what, std::size_t replicate, AnnualSeries& out)>;
// The same draws for a block of sensors: `draws(first, count, sink)` passes sink the
// series (hours x count) of sensors [first, first + count) for the estimate, the centre and
// each replicate, in any order. Blocks run on every core at once.
using AnnualSink = std::function<void(AnnualDraw what, std::size_t replicate, const AnnualSeries& block)>;
using AnnualBlockDraws = std::function<void(std::size_t first, std::size_t count, const AnnualSink& sink)>;

// 32 replicates: sigma to 1 / sqrt(2 x 31) = 13 % of itself, 32 generator calls per grid
// (docs/DAYLIGHT.md says why this is enough).
inline constexpr int kAnnualReplicates = 32;

// A verdict "value >= target" (or "<=") from the corrected value, and the probability that
// the truth lies on the other side: Phi(-|corrected - target| / uncertainty), normal errors.
struct VerdictFlip {
    bool pass = false;
    double flip_probability = 0.0;
};
VerdictFlip judge_threshold(const SimexEstimate& m, double target, bool pass_at_or_above = true);

// The metrics with, for every figure in the same layout, its sigma and its bias (corrected
// = value - bias), and EN 17037's level verdicts with their flip probabilities (the two
// criteria taken as independent).
struct AnnualEstimate {
    AnnualMetrics value, sigma, bias;
    std::array<VerdictFlip, 3> en17037;
    int replicates = 0;
    // A grid figure's estimate, e.g. figure(&AnnualMetrics::sda).
    SimexEstimate figure(double AnnualMetrics::*f) const { return {value.*f, sigma.*f, bias.*f}; }
};

// One grid's metric sums of the estimate, the centre and k replicates, filled block by
// block from AnnualBlockDraws; the blocks may be shared among parts (ranks), each running
// its own and passing its words to one that merges them: the figures are the same, to the
// bit, however the blocks were shared.
class AnnualMetricDraws {
public:
    AnnualMetricDraws(const AnnualHours& hours, std::size_t sensors, const AnnualThresholds& t, int k);
    // The blocks of `block` sensors (counted from sensor 0) that start in [first, last),
    // on every core.
    void run(const AnnualBlockDraws& draws, std::size_t block, std::size_t first, std::size_t last);
    // Sensors [first, last)'s sums (whole blocks this part ran) as words, and merge() of
    // another part's.
    std::vector<std::uint64_t> words(std::size_t first, std::size_t last) const;
    void merge(std::span<const std::uint64_t> words, std::size_t first, std::size_t last);
    // The figures with their errors (k = 0: the estimate's values alone).
    AnnualEstimate estimate() const;
    // The words words() gives for `sensors` sensors, over `hours` hours, with k replicates.
    static std::size_t word_count(std::size_t hours, std::size_t sensors, int k);

private:
    const AnnualHours& hours_;
    std::size_t sensors_ = 0;
    std::size_t replicates_ = 0;
    // [0] the estimate, [1] the centre, [2 + r] replicate r.
    std::vector<std::unique_ptr<AnnualMetricSums>> sums_;
};

// The metrics of the estimate, and their errors from K replicates: sigma their spread, bias
// their mean minus the centre's figure (the bootstrap's bias: what noise does to a figure
// around the centre, it does around the truth), kept so that value - bias stays within the
// figure's range.
AnnualEstimate estimate_annual_metrics(const AnnualReplicates& replicates, const AnnualHours& hours,
                                       const AnnualThresholds& t = {}, int k = kAnnualReplicates);
// The same from `sensors` sensors in blocks of `block` (the last one shorter); k = 0: the
// estimate's metrics alone (value; no sigma, bias or verdicts). The figures do not depend
// on the core count; they depend on `block` only through the draws' own dependence on it.
AnnualEstimate estimate_annual_metrics(const AnnualBlockDraws& draws, std::size_t sensors, std::size_t block,
                                       const AnnualHours& hours, const AnnualThresholds& t = {},
                                       int k = kAnnualReplicates);

}  // namespace luxtrace
