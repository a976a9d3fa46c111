#pragma once
// Error estimates of SPEC §3 from reduced tallies. Pure functions of the counts: rank 0
// calls them after every reduction and the result writer stores what they return.
#include "luxtrace/stats/illuminance_metrics.hpp"
#include "luxtrace/stats/weighted_tallies.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

struct Detector;

// The error of the whole surface map. Every quantity runs over the lit sides: the
// triangle sides that received at least one photon (the back of a closed room's walls is
// never lit, so a closed solid reads as it did with one-sided maps).
struct GlobalEstimate {
    // Eq. (5): D from the odd and even half-maps; sigma_lx = D / 2. The paper's estimate,
    // with about as many degrees of freedom as lit sides.
    double odd_even_rms_lx = 0.0;
    double sigma_lx = 0.0;
    double sigma_rel_arithmetic = 0.0;
    double sigma_rel_quadratic = 0.0;
    double mean_arithmetic_lx = 0.0;  // eq. (4), area-weighted
    double mean_quadratic_lx = 0.0;
    // From each side's second moment (issue 13): sigma_t^2 = (E0 / A_t)^2 (Q_t - S_t^2 / N),
    // S_t the side's arrivals, Q_t = sum over photons of their arrivals there squared, and
    // sigma = sqrt(sum_t A_t sigma_t^2 / S): about N degrees of freedom. Meaningful for
    // independent photons (random); sobol's photons are not.
    double moment_sigma_lx = 0.0;
    double moment_sigma_rel_arithmetic = 0.0;
    double moment_sigma_rel_quadratic = 0.0;
    // sobol (issue 22): sigma_t from the spread of side t's R replicate maps
    // (replicate_estimate), summed the same way; (R - 1) degrees of freedom per lit side.
    double replicate_sigma_lx = 0.0;
    double replicate_sigma_rel_arithmetic = 0.0;
    double replicate_sigma_rel_quadratic = 0.0;
    enum class Estimator { odd_even, second_moment, replicate_spread };
    Estimator primary = Estimator::odd_even;  // what targets and the history use
    double lit_area_m2 = 0.0;                 // S
    std::uint64_t lit_sides = 0;

    // The estimate targets, forecasts and the history use.
    double target_sigma_lx() const {
        return primary == Estimator::second_moment      ? moment_sigma_lx
               : primary == Estimator::replicate_spread ? replicate_sigma_lx
                                                        : sigma_lx;
    }
    double target_sigma_rel(bool arithmetic) const {
        switch (primary) {
        case Estimator::second_moment: return arithmetic ? moment_sigma_rel_arithmetic : moment_sigma_rel_quadratic;
        case Estimator::replicate_spread:
            return arithmetic ? replicate_sigma_rel_arithmetic : replicate_sigma_rel_quadratic;
        case Estimator::odd_even: break;
        }
        return arithmetic ? sigma_rel_arithmetic : sigma_rel_quadratic;
    }
    const char* estimator_name() const {
        return primary == Estimator::second_moment      ? "second_moment"
               : primary == Estimator::replicate_spread ? "replicate_spread"
                                                        : "odd_even";
    }
};

// Every estimate below reads the tallies of a light scene (WeightedTallies) or, in the
// overloads taking the layout and the words, of the plain run.

// Band-summed illuminance of every triangle side, [2 t + side] (the result file's order,
// not the tallies'); E0 = flux per photon (lm).
std::vector<double> side_illuminance_lx(const WeightedTallies& tallies, std::span<const double> area_m2, double e0);
// Per side [2 t + side]: the standard error of the band-summed illuminance from the second
// moment (NaN for photons = 0); side_replicate_sigma_lx: from the spread of the side's
// replicate maps (sobol; empty without replicates).
std::vector<double> side_sigma_lx(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                                  std::uint64_t photons);
std::vector<double> side_replicate_sigma_lx(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                                            std::uint64_t photons);
// The surface map's illuminance as the result stores it, per triangle side (front 0).
struct SurfaceMaps {
    std::vector<double> illuminance_lx;          // [T][2][B]: E0 / A_t (n_odd + n_even)
    std::vector<double> illuminance_direct_lx;   // [T][2][B]: direct arrivals only (tracer.hpp)
    std::vector<double> odd_even_difference_lx;  // [T][2], band-summed E_odd - E_even (the terms of eq. 5)
    std::vector<double> sigma_lx;                // [T][2], side_sigma_lx
    std::vector<double> replicate_sigma_lx;      // [T][2], side_replicate_sigma_lx (sobol only)
};
SurfaceMaps surface_maps(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                         std::uint64_t photons);
// photons = N, the photons emitted so far. Primary: the second moment for random runs,
// the replicate spread for sobol (layout with replicates).
GlobalEstimate estimate_global(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                               std::uint64_t photons);
GlobalEstimate estimate_global(const TallyLayout& layout, std::span<const std::uint64_t> data,
                               std::span<const double> area_m2, double e0, std::uint64_t photons);

struct CellRange {
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};  // [i0,i1) x [j0,j1); i1 = 0: all

struct DetectorEstimate {
    std::vector<double> value;      // [ny][nx][B], lx or cd/m^2
    std::vector<double> sigma_rel;  // [ny][nx][B], eq. (8); NaN where the cell got nothing
    double mean_arithmetic = 0.0;   // over the range, band-summed values
    double mean_quadratic = 0.0;
    double sigma_abs = 0.0;  // sqrt(mean sigma_c^2), eq. (9) numerator
    double sigma_rel_arithmetic = 0.0;
    double sigma_rel_quadratic = 0.0;
    // The detector's mean value over the whole grid and its relative standard error,
    // eq. (8) applied to the grid as one cell.
    double mean_value = 0.0;
    double mean_sigma_rel = 0.0;
    std::uint64_t photons_received = 0;  // whole detector
    std::uint64_t registrations = 0;     // sum of n_c over the range
    // How sigma_rel and the summaries were estimated: eq. (8) (independent photons,
    // random) or the spread of the R replicate means (sobol, replicate_estimate), with
    // `dof` = R - 1 degrees of freedom (0 for eq. 8).
    bool replicate_spread = false;
    int dof = 0;
    // Illuminance detectors, whole-grid estimates only: Eavg, Emin, Emax, U0 of the whole
    // grid (first, area "") and of each of its task areas (illuminance_metrics.hpp).
    std::vector<IlluminanceMetrics> metrics;
    // The same, whole-grid illuminance only: band-summed cells [ny][nx] and their absolute
    // standard errors (NaN where a cell got nothing), for daylight factors.
    std::vector<double> summed_value, summed_sigma;
};

// A mean from R independent randomisations of a QMC estimator (replicates, issue 11;
// docs/QMC.md): replicate r scored `sums[r]` over `photons[r]` photons. Eq. (8)'s
// per-photon variance assumes independent photons, which QMC points are not; the
// replicates are independent of each other, so the spread of their means is an honest
// error. mean = sum / N (N = sum of photons[r]); sigma^2 = R / (R - 1) * sum over r of
// (photons[r] / N)^2 (m_r - mean)^2, m_r = sums[r] / photons[r], which for equal
// photons[r] is s^2 / R with s^2 the sample variance of the m_r; R - 1 degrees of freedom.
struct ReplicateEstimate {
    double mean = 0.0;   // per photon
    double sigma = 0.0;  // standard error of mean
    int dof = 0;         // R - 1
};
// Needs R >= 2 replicates with photons each; otherwise sigma is NaN and dof 0.
ReplicateEstimate replicate_estimate(std::span<const double> sums, std::span<const std::uint64_t> photons);

// photons = N, the photons emitted so far.
DetectorEstimate estimate_detector(const Detector& det, std::size_t det_index, const WeightedTallies& tallies,
                                   double e0, std::uint64_t photons, CellRange range = {});
DetectorEstimate estimate_detector(const Detector& det, std::size_t det_index, const TallyLayout& layout,
                                   std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                   CellRange range = {});

}  // namespace luxtrace
