#pragma once
// The figures a lighting engineer checks on an illuminance grid or a task area of it
// (EN 12464-1: the maintained average illuminance and the uniformity U0 = Emin / Eavg),
// each with its statistical error. Pure functions of band-summed cell values and their
// absolute standard errors; docs/SPEC.md §3 states the formulas.
#include "luxtrace/detector/detector.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace luxtrace {

// Emin (or Emax) is flagged unreliable, and with it U0, when its standard error or its
// possible bias exceeds this share of Emin: at U0 = 0.6 that is +-0.012, about one unit
// of the second decimal EN 12464-1 quotes U0 to.
inline constexpr double kUniformityNoiseLimit = 0.02;
// A cell competes for the minimum when its value lies within this many combined sigmas
// of the observed minimum (1e-3 one-sided chance of leaving out a cell whose true value
// equals the true minimum).
inline constexpr double kCompetitorSigmas = 3.0;

struct IlluminanceMetrics {
    std::string area;  // "" for the whole detector, else the task area's name
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    std::uint64_t cells = 0;
    double avg_lx = 0.0, avg_sigma_lx = 0.0;
    // Extremes: the value of the extreme cell, its standard error, and the expected
    // bias of the extreme of noisy cells (negative for the minimum, positive for the
    // maximum; see expected_extreme_bias); `*_competitors` cells entered that bias.
    double min_lx = 0.0, min_sigma_lx = 0.0, min_bias_lx = 0.0;
    double max_lx = 0.0, max_sigma_lx = 0.0, max_bias_lx = 0.0;
    int min_i = 0, min_j = 0, max_i = 0, max_j = 0;
    std::uint64_t min_competitors = 0, max_competitors = 0;
    double u0 = 0.0, u0_sigma = 0.0;                      // Emin / Eavg
    double u0_bias = 0.0;                                 // Emin's bias / Eavg (<= 0)
    double min_over_max = 0.0, min_over_max_sigma = 0.0;  // Emin / Emax
    // Emin / Emax minus its value with both extremes bias-corrected (<= 0)
    double min_over_max_bias = 0.0;
    // A cell got no photons, or Emin's error or bias exceeds kUniformityNoiseLimit.
    bool unreliable = false;
};

// E[max over c of (mean_c + sigma_c Z_c)] for independent standard normal Z_c: the
// expected maximum of independent normal cells, by numerical integration of
// E[X] = int_0^inf (1 - F) dx - int_-inf^0 F dx with F(x) = prod_c Phi((x - mean_c) / sigma_c)
// (deterministic; cells with sigma 0 enter as constants).
double expected_maximum(std::span<const double> mean, std::span<const double> sigma);

// The expected shift of the extreme of cells that share one true value, i.e.
// E[max_c sigma_c Z_c] >= 0. With every true value of these cells equal it is exactly
// the bias of their observed maximum (and, negated, of their minimum); when they differ
// the bias is smaller, so this bounds it from the cells that compete for the extreme.
double expected_extreme_bias(std::span<const double> sigma);

// Metrics over the cells [i0, i1) x [j0, j1) of a grid with `nx` cells per row; `value`
// and `sigma` (absolute, NaN for a cell without photons) are band-summed, one per cell.
// `avg_sigma_lx`: the standard error of the average when known exactly (the whole grid
// taken as one cell, eq. 8); otherwise sqrt(sum sigma_c^2) / K, which assumes
// independent cells (true up to photons registering in two cells of the area).
IlluminanceMetrics illuminance_metrics(std::span<const double> value, std::span<const double> sigma, int nx,
                                       const TaskArea& area, std::optional<double> avg_sigma_lx = {});

// Maintained values: every illuminance (and its error and bias) times the maintenance
// factor; the ratios do not change.
IlluminanceMetrics maintained(const IlluminanceMetrics& initial, double maintenance_factor);

}  // namespace luxtrace
