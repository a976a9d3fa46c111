#pragma once
// Each hour's illuminance on a detector from its daylight coefficients (issue 24,
// docs/ANNUAL.md). A run keeps every detector cell's tallies per light group: the sky
// patches, the ground and every hour's sun (annual/annual_sky.hpp). Group g's coefficient
// of cell c is C_gc = k n_gc (k the cell's value per count, eq. 8's n_c), with variance
// k^2 (q_gc - n_gc^2 / N); hour h's illuminance is E_hc = sum_g w_hg C_gc, w_hg the hour's
// luminance of the group over what the group emitted, and its variance
// k^2 (sum_g w_hg^2 q_gc - (sum_g w_hg n_gc)^2 / N): the groups' photons are disjoint, so
// this is exact for the weighted sum (stats/weighted_tallies.hpp). A cell that no photon of
// an emitting group reached gets, in its hourly error, the variance of its expected count
// estimated from data (sky_coefficients, dark_rates), not 0. A sun's interreflected part is
// pooled over the same hour of the neighbouring days (its direct part stays the hour's
// own); the replicates draw a sun's direct count around its pooled mean and its
// interreflected count around an empirical-Bayes centre. The direct sun (LM-83's ASE) is
// the hour's sun group's direct registrations alone (TallyLayout::detector_direct).
//
// With direct coefficients by shadow rays (annual/direct_coefficients.hpp) the photons'
// counts hold only the light that arrived after an event (TallyLayout::direct_apart), and
// each coefficient is the shadow rays' direct plus the photons' rest: the two are
// independent, so their variances add. The direct sun (ASE) is then the shadow rays'.
//
// With the light after a diffuse reflection gathered (tracer/gather_table.hpp), each
// group's coefficient also has the gathered sum, G_gc = k_G Y_gc (k_G = e0 / W, Y the
// tally's units) with variance k_G^2 (Q_gc - Y_gc^2 / N) (Q the sum of squares in units^2);
// a sun's gathered part is pooled over the neighbouring days like its interreflected counts
// (a sun hour's few photons), and the replicates draw it normal around its value, with the
// grid's correlation (AnnualDarkRates::gather_total).
#include "luxtrace/annual/annual_sky.hpp"
#include "luxtrace/annual/direct_coefficients.hpp"
#include "luxtrace/stats/annual_metrics.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

// One grid's counts as a run's tallies hold them. `det` the detector's index in the
// layout, `cells` its cells, `per_count` its value of one registration (e0 x
// Detector::value_per_lm()), `photons` N. `group_flux_lm`, per light group
// (light_group_flux_lm, estimate_scene.hpp): a group that emits nothing (a patch or sun
// behind every portal) has exactly zero coefficients, with no error. `direct`: the
// detector's direct coefficients by shadow rays, or null.
struct AnnualGridCounts {
    const AnnualSetup& annual;
    const TallyLayout& layout;
    std::span<const std::uint64_t> data;
    std::size_t det = 0, cells = 0;
    double per_count = 0.0;
    double gather_per_unit = 0.0;  // k_G: lx of a gathered unit, 0 without a gather
    std::uint64_t photons = 0;
    std::span<const double> group_flux_lm;
    const DirectCoefficients* direct = nullptr;
    // Per sun (AnnualSky::suns()), its own flux (the sum of its lights'): a sun of a shared
    // row (AnnualSetup::sun_row) that emits nothing has zero coefficients. Empty: its
    // group's.
    std::span<const double> sun_flux_lm;
};

// The expected count, per neighbour and unit share, of a (sun, cell) pair whose
// neighbouring days read nothing: its total and its direct count, over the whole grid.
struct AnnualDarkRates {
    double total = 0.5, direct = 0.5;
    // With a gather, per light group (kGatherFactorWords from g kGatherFactorWords): its
    // factor (estimate/gather_factors.hpp, AnnualCoefficients::gather_totals), from which
    // each cell's loadings follow: the replicates draw each cell's noise as a common part
    // plus its own, so that a grid figure's error holds the cells' correlation.
    std::vector<double> gather_total;
};

// The coefficients of a block of the grid's cells, and the hourly series made of them.
class AnnualCoefficients {
public:
    // Over the whole grid (every block shares them).
    static AnnualDarkRates dark_rates(const AnnualGridCounts& grid);
    // Cells [first, first + count) of the grid.
    AnnualCoefficients(const AnnualGridCounts& grid, std::size_t first, std::size_t count, const AnnualDarkRates& dark);

    // Series are hours x the block's cells (AnnualSeries::sensors = count), hour-major,
    // every hour of the weather file (0 in the dark ones). A series passed in is either of
    // another size (it is remade) or one these methods made (its zeros are kept).
    // The estimate and its standard errors (sigma_lx: of total_lx and direct_lx).
    void series(AnnualSeries& estimate, AnnualSeries& sigma) const;
    // The estimate alone (kept: later calls copy it).
    void estimate(AnnualSeries& out) const;
    // What the replicates are drawn around: a fresh run's expected values as the data say
    // them (the sky and ground at their counts, a sun's direct count at its mean pooled over
    // the neighbouring days, its interreflected count at its empirical-Bayes centre).
    void centre(AnnualSeries& out) const;
    // A fresh run's values, from (seed, replicate): every count redrawn around its centre as
    // a Poisson count of its variance, for the errors of nonlinear metrics
    // (stats/annual_metrics.hpp). Each cell's draws are its own Philox stream of (seed,
    // replicate, the cell's index in the grid), the suns' interreflected counts the block's
    // (its first cell): the same however the blocks are shared among cores and ranks.
    void replicate(std::uint64_t seed, std::uint64_t replicate, AnnualSeries& out) const;

private:
    // The constructor reads the block's counts per light group (Counts) in four steps,
    // each filling the members under its name below (the dark rates come in):
    //   sky_coefficients  the sky patches' and the ground's coefficients and their errors
    //   SunRows           per sun, the rows (the photons' sun groups) it reads: its own and
    //                     those of the same hour on the neighbouring days, or its shared row
    //   sun_priors        per clock hour and cell, the prior of a sun's interreflected count
    //   sun_coefficients  per sun and cell, the coefficients, their errors and a fresh run's draw
    struct Counts;
    struct SunRows;
    static std::vector<double> gather_totals(const AnnualGridCounts& grid, const Counts& c);
    void gather_loadings(const Counts& c, const AnnualDarkRates& dark);
    void sky_coefficients(const Counts& counts);
    void sun_priors(const Counts& counts);
    void sun_coefficients(const Counts& counts);
    void row_centres(const Counts& counts);
    void sun_gathered(const Counts& counts);

    // sum over the emitting sky entries of w^power x[entry][cell], w the hour's weight.
    void sky_row(const AnnualHour& hour, const std::vector<double>& x, int power, std::vector<double>& row) const;
    void combine(const std::vector<double>& sky, const std::vector<double>& sun, const std::vector<double>& direct,
                 AnnualSeries& out) const;
    // [sun][cell]: sun = direct + the [row][cell] indirect pooled over the rows the sun
    // reads (pool_share_ times their sum).
    void pool(const std::vector<double>& indirect, const std::vector<double>& direct, std::vector<double>& sun) const;

    // replicate(): a fresh run's interreflected sun of every sun and cell (its counts drawn
    // around their centres, in lx per unit weight, not yet pooled) into `indirect`.
    void draw_sun_indirect(std::uint64_t seed, std::uint64_t replicate, std::vector<double>& indirect) const;

    // The shadow rays' direct light of the hour (sky, ground and sun) into `out` (cells);
    // with `variance`, its variance instead.
    void direct_hour(const AnnualHour& hour, bool variance, std::vector<double>& out) const;

    const AnnualSetup& annual_;
    bool shadow_ = false;
    std::size_t first_ = 0, cells_ = 0;
    double inv_photons_ = 0.0;
    double per_count_ = 0.0;        // k
    double gather_per_unit_ = 0.0;  // k_G
    AnnualDarkRates dark_;

    // The block's part of the shadow rays' direct coefficients (DirectCoefficients' layout,
    // the block's cells), when shadow_.
    std::vector<double> shadow_sky_lx_, shadow_sky_var_, shadow_sun_lx_, shadow_sun_var_;

    // sky_coefficients, [entry][cell] (sky patches then the ground, AnnualSky's sky vector
    // order): the coefficients (lx per unit weight), k^2 q for the hourly error (with a floor
    // where the cell saw nothing) and the plain counts' variances for the replicates.
    std::vector<double> sky_, sky_q_, sky_var_;
    // The gathered part (empty without a gather): its variance per [entry][cell], and per
    // [row][cell] the row's own (unpooled) value and variance.
    std::vector<double> sky_gather_var_, sun_gather_, sun_gather_var_;
    // Per [entry][cell] and [row][cell], kGatherRegions each: the cell's loadings on its
    // group's common draws.
    std::vector<float> sky_loading_, sun_loading_;
    // The gathered value per [entry][cell] and, pooled, per [sun][cell]; per cell the
    // relative variance of the gather's own rays (DirectCoefficients::gather_rel_var), an
    // error common to every hour.
    std::vector<double> sky_gather_, sun_gather_pooled_, gather_rel_var_;
    // sun += pool share x (the sum of the rows it reads), per [sun][cell].
    void pool_gathered(const std::vector<double>& own, std::vector<double>& sun) const;
    std::vector<std::size_t> entries_;  // the sky entries whose groups emit

    // SunRows, per sun: the rows it reads (its own first), its share of them, their flux
    // and its dark count's scale (sun_coefficients); per row: the rows its replicates'
    // centre reads, their flux, and its clock hour.
    std::vector<std::vector<std::size_t>> pool_, evidence_;
    std::vector<double> pool_share_, pool_flux_, dark_scale_, evidence_flux_;
    std::vector<std::size_t> row_clock_;

    // sun_priors, [clock hour][cell]: the prior's mean count per unit flux and its shape.
    std::vector<double> eb_rho_, eb_alpha_;

    // sun_coefficients, [sun][cell]: the coefficients (lx per unit weight) and the direct
    // sun's; for the hourly errors k^2 q of the pooled estimate (with a dark floor) and the
    // direct sun's variance; a fresh run's draw, in counts: the direct count's pooled mean;
    // [row][cell]: the indirect count's empirical-Bayes centre and its variance.
    std::vector<double> sun_, direct_, sun_q_, direct_var_;
    std::vector<float> rep_direct_mu_, rep_indirect_mu_, rep_indirect_var_;

    // The estimate, made once.
    mutable AnnualSeries estimate_;
    mutable bool have_estimate_ = false;
};

}  // namespace luxtrace
