#pragma once
// Daylight factors and EN 17037's daylight-factor method, with their statistical errors.
// DF = E / E_h,ext (%), E_h,ext the unobstructed horizontal illuminance the daylight sources
// give by their model (exact, so a cell's DF error is its illuminance error over E_h,ext).
// EN 17037:2018 §A.2 asks for the DF exceeded over 50 % of the reference plane (against the
// target D_T) and over 95 % of it (against the minimum target D_TM); these are quantiles of
// noisy cells, which have both an error and a bias (noise widens the distribution, so the
// 95 % value of noisy cells sits below the true one). Pure functions; docs/DAYLIGHT.md
// "Daylight factor and EN 17037" states the method and its calibration.
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/stats/simex.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

// One-sided 95 % confidence: the verdict's reach in standard errors.
inline constexpr double kVerdictSigmas = 1.6448536269514722;
// Replicates of the parametric bootstrap of a quantile (noisy_quantile); its own Monte
// Carlo error is then about 1/sqrt(2 x 400) = 3.5 % of the reported sigma and a few % of a
// sigma on the bias.
inline constexpr int kQuantileBootstrapReplicates = 400;
// Past this many times the photons a verdict is not worth waiting for: "cannot decide".
inline constexpr double kUndecidableFactor = 1e4;

// A quantile of noisy cells: the observed value, its standard error and its bias
// (E[observed] - true); corrected() = value - bias. The bootstrap's bias is right to within
// its own size, not exactly (calibration: 20 to 100 % off where the true values crowd near
// an edge or leave gaps wider than the noise), so a verdict takes the corrected value with
// the uncertainty sqrt(sigma^2 + bias^2).
using QuantileEstimate = SimexEstimate;

enum class Verdict { pass, fail, undecided };
const char* verdict_name(Verdict v);

// A criterion "quantile >= target" judged at one-sided 95 %: pass when the corrected value
// lies k = kVerdictSigmas uncertainties u or more above the target, fail when that far
// below, else undecided, with the factor on the photons that would decide it if the value
// stayed where it is, (k u / |value - target|)^2 (sigma falls as 1/sqrt(N) and the bias
// faster, so this is enough); infinite when the value equals the target (or needs more
// than kUndecidableFactor times): cannot decide.
struct CriterionVerdict {
    Verdict verdict = Verdict::undecided;
    double photons_factor = 0.0;  // > 1 when undecided; 0 when decided
};
CriterionVerdict judge(const QuantileEstimate& q, double target);
// The words for an undecided criterion: "about N x the photons", or "cannot decide: ...".
std::string decide_hint(const CriterionVerdict& v, const QuantileEstimate& q, double target);

// The DF figures of a detector or one task area of it.
struct DaylightAreaMetrics {
    std::string area;  // "" for the whole detector
    std::uint64_t cells = 0;
    std::uint64_t cells_without_photons = 0;
    double mean_df = 0.0, mean_df_sigma = 0.0;  // mean over the cells, sqrt(sum sigma^2)/K
    QuantileEstimate median;                    // exceeded over 50 % of the cells
    QuantileEstimate df_95;                     // exceeded over 95 % of the cells
    bool has_targets = false;                   // en17037 given: the verdicts below are set
    En17037Targets targets;
    CriterionVerdict target_verdict, minimum_verdict;
    Verdict overall = Verdict::undecided;
    double overall_photons_factor = 0.0;  // undecided: the most any undecided criterion needs
};

// The value exceeded over (at least) a share `fraction` of `values`: with the K values sorted
// ascending, x_(K + 1 - ceil(fraction K)) (1-based), so that ceil(fraction K) cells reach it.
double exceeded_over(std::span<const double> values, double fraction);

// That quantile of noisy cells (value, absolute sigma per cell; sigma 0 for an exact cell)
// with its standard error and bias, by a deterministic parametric bootstrap (normal draws
// from a fixed counter-based generator) that adds the cells' own noise once and twice more
// and extrapolates the mean quantile back to no noise (SIMEX; daylight_metrics.cpp and
// docs/DAYLIGHT.md say why and how well).
QuantileEstimate noisy_quantile(std::span<const double> value, std::span<const double> sigma, double fraction,
                                int replicates = kQuantileBootstrapReplicates);

// DF (%) per cell from band-summed illuminance and its absolute standard error (NaN for a
// cell without photons, kept NaN).
std::vector<double> daylight_factor_pct(std::span<const double> illuminance_lx, double reference_lx);

// The figures over cells [i0, i1) x [j0, j1) of a grid `nx` cells wide; `df` and `df_sigma`
// (NaN: no photons, taken as 0 +- 0) in percent; targets null: no verdicts.
DaylightAreaMetrics daylight_area_metrics(std::span<const double> df, std::span<const double> df_sigma, int nx,
                                          const TaskArea& area, const En17037Targets* targets);

// A daylight_factor detector's DF map and figures: the whole grid first, then each task area.
struct DaylightEstimate {
    double reference_lx = 0.0;         // E_h,ext
    std::vector<double> df, df_sigma;  // [ny][nx], %, band-summed; sigma NaN: no photons
    std::vector<DaylightAreaMetrics> areas;
};

// From band-summed illuminance and its absolute errors per cell ([ny][nx]); reference_lx > 0.
DaylightEstimate estimate_daylight(const Detector& d, std::span<const double> illuminance_lx,
                                   std::span<const double> sigma_lx, double reference_lx);

}  // namespace luxtrace
