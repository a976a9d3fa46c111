#include "luxtrace/estimate/annual_coefficients.hpp"

#include "luxtrace/estimate/gather_factors.hpp"
#include "luxtrace/sampler/normal_quantile.hpp"
#include "luxtrace/sampler/philox_bits.hpp"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

namespace luxtrace {

namespace {
// The suns of one clock hour share an empirical-Bayes prior (sun_priors).
constexpr std::size_t kClockHours = 24;
// The replicates' common draws of the gathered light, per light group (apart from the cells'
// streams by their key).
constexpr std::uint64_t kGatherFactorKey = 0x9A7E5C0FFEE11A7Dull;
// The replicates' streams of a block's interreflected sun (draw_sun_indirect), apart from
// its cells' own (a cell index stays below 2^39).
constexpr std::uint64_t kSunDrawStream = std::uint64_t{1} << 39;
// Above this mean count over a block a sun's cells are drawn one by one.
constexpr double kSharedSunDrawMean = 16.0;

// A cell's own stream of a replicate year (AnnualCoefficients::replicate): (seed,
// replicate, its index in the grid), drawn in the same order whatever the loops' (the rays,
// the sky entries, then the suns), so the loops can run along the coefficients' rows.
struct ReplicateStream {
    PhiloxBits bits;
    std::normal_distribution<double> normal;
    double k = 0.0;     // lx of a count
    double rays = 0.0;  // the gather's rays' relative error, for all the cell's light and hours

    ReplicateStream(std::uint64_t seed, std::uint64_t stream, double per_count) : bits(seed, stream), k(per_count) {}
    double unit() { return standard_normal(bits); }  // by the quantile: thousands per cell
    // A count's zero-mean noise of variance var: Poisson of mean var / k^2, counts, not a
    // small normal wobble that crosses a threshold every time; normal above 1,000 counts.
    double count(double var) {
        const double k2 = k * k;
        if (!(var > 0.0) || !(k2 > 0.0)) return 0.0;
        const double mu = var / k2;
        if (mu > 1000.0) return k * std::sqrt(mu) * normal(bits);
        return k * (static_cast<double>(std::poisson_distribution<std::int64_t>(mu)(bits)) - mu);
    }
    // The shadow rays' direct light: normal around its value with its own variance.
    double normal_noise(double var) { return var > 0.0 ? std::sqrt(var) * normal(bits) : 0.0; }
    // The gathered light's: its part common to the grid (loadings a, draws z) and its own,
    // sqrt(1 - |a|^2).
    double gathered(double var, const float* a, const double* z) {
        if (!(var > 0.0)) return 0.0;
        double common = 0.0, a2 = 0.0;
        for (std::size_t r = 0; r < kGatherRegions; ++r) {
            common += a[r] * z[r];
            a2 += static_cast<double>(a[r]) * a[r];
        }
        return std::sqrt(var) * (common + std::sqrt(std::max(0.0, 1.0 - a2)) * unit());
    }
};
}  // namespace

// The detector's counts per light group, as the constructor's steps read them.
struct AnnualCoefficients::Counts {
    const AnnualSetup& annual;
    const TallyLayout& layout;
    std::span<const std::uint64_t> data;
    std::size_t det = 0;
    std::span<const double> group_flux_lm, sun_flux_lm;
    // The photons' n and q hold no direct registration (shadow rays give the direct light):
    // for the estimate their direct count is then 0.
    bool direct_apart = false;
    bool gathered = false;
    std::size_t first = 0;  // the block's first cell: `cell` below counts from it

    Counts(const AnnualGridCounts& g, std::size_t first_cell)
        : annual(g.annual), layout(g.layout), data(g.data), det(g.det), group_flux_lm(g.group_flux_lm),
          sun_flux_lm(g.sun_flux_lm), direct_apart(g.layout.direct_apart(g.det)), gathered(g.layout.gathered(g.det)),
          first(first_cell) {}

    double flux(std::size_t group) const { return group < group_flux_lm.size() ? group_flux_lm[group] : 0.0; }
    double n(std::size_t cell, std::size_t group) const {
        return static_cast<double>(data[layout.detector_n(det, first + cell, 0, group)]);
    }
    double q(std::size_t cell, std::size_t group) const {
        return static_cast<double>(data[layout.detector_q(det, first + cell, 0, group)]);
    }
    // The gathered sum Y and sum of squares Q, in units and units^2 (tally.hpp).
    double gather_y(std::size_t cell, std::size_t group) const {
        return gathered ? static_cast<double>(data[layout.detector_gathered(det, first + cell, group)]) : 0.0;
    }
    double gather_q(std::size_t cell, std::size_t group) const {
        return gathered ? std::ldexp(static_cast<double>(data[layout.detector_gathered(det, first + cell, group) + 1]),
                                     TallyLayout::kGatherSquareShift)
                        : 0.0;
    }
    // Sum of Y T_r (units^2), T_r the photon's sum over region r of the grid.
    double gather_x(std::size_t cell, std::size_t group, std::size_t r) const {
        return gathered
                   ? std::ldexp(static_cast<double>(data[layout.detector_gathered(det, first + cell, group) + 2 + r]),
                                TallyLayout::kGatherSquareShift)
                   : 0.0;
    }
    // The regions' totals per photon, as cells (TallyLayout::detector_gathered_total): the
    // sum of T_r (units) and of T_r T_s (units^2).
    double gather_total_y(std::size_t group, std::size_t r) const {
        return static_cast<double>(data[layout.detector_gathered_total(det, group) + r]);
    }
    double gather_total_q(std::size_t group, std::size_t r, std::size_t s) const {
        return std::ldexp(static_cast<double>(data[layout.detector_gathered_total(det, group) +
                                                   TallyLayout::kGatherRegions + TallyLayout::gather_pair(r, s)]),
                          TallyLayout::kGatherSquareShift);
    }
    double direct(std::size_t cell, std::size_t group) const {
        return layout.direct_scores() && !direct_apart
                   ? static_cast<double>(data[layout.detector_direct(det, first + cell, group)])
                   : 0.0;
    }
    // Sky entry e's group (AnnualSky's sky vector order: the patches, then the ground), and
    // sun s's.
    std::size_t sky_group(std::size_t e) const {
        return e == annual.sky->ground_entry() ? annual.ground_group : annual.first_patch_group + e;
    }
    // Sun row r's group (AnnualSetup::sun_row), and sun s's own flux.
    std::size_t row_group(std::size_t r) const { return annual.first_sun_group + r; }
    bool row_emits(std::size_t r) const { return flux(row_group(r)) > 0.0; }
    double sun_flux(std::size_t s) const {
        return s < sun_flux_lm.size() ? sun_flux_lm[s] : flux(annual.sun_group(static_cast<int>(s)));
    }
    bool sun_emits(std::size_t s) const { return sun_flux(s) > 0.0; }
    // Per (row, cell): the direct count d, the other (interreflected) registrations
    // i = n - d and their second moment v = q - d (a photon's direct count in a cell is 0 or
    // 1, its square itself, tally.hpp; a photon registering a cell both directly and after a
    // reflection is taken as rare).
    double row_direct(std::size_t r, std::size_t cell) const { return direct(cell, row_group(r)); }
    double row_indirect(std::size_t r, std::size_t cell) const {
        return n(cell, row_group(r)) - direct(cell, row_group(r));
    }
    double row_indirect_moment(std::size_t r, std::size_t cell) const {
        return q(cell, row_group(r)) - direct(cell, row_group(r));
    }
};

// What each sun reads of the photons' sun groups (rows). With a row per sun, a sun reads
// its own and the emitting suns' of the same hour on the day before and after (their
// positions within half a degree: the same shadows and nearly the same reflections), its
// share of the three being pool_share = Phi_s / (Phi_s + sum Phi_o) (the groups' fluxes
// decide their photons). With shared rows (sun_group_days) a sun reads its row in its
// share of the row's direct normal illuminance, Y_s / sum Y (the row's count is the sum of
// its suns' Y_s g_s, g the cell's response per unit Y, alike over the row's days), the
// suns that emit nothing (behind every portal) left out. Per row: its neighbours (the
// emitting rows of the same clock hour on the days next to it), for the dark rates.
struct AnnualCoefficients::SunRows {
    std::vector<std::vector<std::size_t>> pool, evidence, neighbours;
    std::vector<double> pool_share, pool_flux, dark_scale;  // per sun
    std::vector<double> evidence_flux, neighbour_share;     // per row
    std::vector<std::size_t> clock;                         // per row

    explicit SunRows(const Counts& c) {
        const AnnualSetup& a = c.annual;
        const std::size_t suns = a.sky->suns().size(), rows = a.sun_rows();
        clock.assign(rows, 0);
        for (std::size_t s = 0; s < suns; ++s) clock[a.sun_row(s)] = a.sky->suns()[s] % kClockHours;
        find_neighbours(c);
        pool.assign(suns, {});
        pool_share.assign(suns, 1.0);
        pool_flux.assign(suns, 0.0);
        dark_scale.assign(suns, 1.0);
        if (a.shared_sun_row.empty()) {
            own_rows(c);
        } else {
            shared_rows(c);
        }
    }

    // Rows of the same clock hour in consecutive blocks of days (a day each without shared
    // rows: hours h - 24 and h + 24).
    void find_neighbours(const Counts& c) {
        const AnnualSetup& a = c.annual;
        const std::size_t rows = clock.size(), days = static_cast<std::size_t>(std::max(1, a.options.sun_group_days));
        std::vector<std::size_t> block(rows, 0);
        std::map<std::pair<std::size_t, std::size_t>, std::size_t> row_at;
        for (std::size_t s = 0; s < a.sky->suns().size(); ++s) {
            const std::size_t h = a.sky->suns()[s], r = a.sun_row(s);
            block[r] = h / 24 / days;
            row_at.try_emplace({block[r], clock[r]}, r);
        }
        neighbours.assign(rows, {});
        neighbour_share.assign(rows, 0.0);
        for (std::size_t r = 0; r < rows; ++r) {
            if (!c.row_emits(r)) continue;
            double near_flux = 0.0;
            for (const std::size_t b : {block[r] - 1, block[r] + 1}) {  // block 0 - 1 wraps: none
                const auto it = row_at.find({b, clock[r]});
                if (it == row_at.end() || !c.row_emits(it->second)) continue;
                neighbours[r].push_back(it->second);
                near_flux += c.flux(c.row_group(it->second));
            }
            neighbour_share[r] = near_flux > 0.0 ? c.flux(c.row_group(r)) / near_flux : 0.0;
        }
    }
    double neighbour_scale(std::size_t r) const {
        return neighbours[r].empty() ? 1.0 : static_cast<double>(neighbours[r].size()) * neighbour_share[r];
    }

    void own_rows(const Counts& c) {
        for (std::size_t s = 0; s < pool.size(); ++s) {
            pool[s] = {s};
            if (!c.sun_emits(s)) continue;
            double near_flux = 0.0;
            for (const std::size_t o : neighbours[s]) {
                pool[s].push_back(o);
                near_flux += c.flux(c.row_group(o));
            }
            const double flux = c.sun_flux(s);
            pool_share[s] = flux / (flux + near_flux);
            pool_flux[s] = flux / pool_share[s];
            dark_scale[s] = neighbour_scale(s);
        }
        evidence = pool;
        evidence_flux = pool_flux;
    }

    void shared_rows(const Counts& c) {
        const AnnualSetup& a = c.annual;
        const std::size_t rows = clock.size();
        std::vector<double> row_y(rows, 0.0);
        auto y = [&](std::size_t s) {
            return c.sun_emits(s) ? a.sky->hours()[a.sky->suns()[s]].direct_normal_lx : 0.0;
        };
        for (std::size_t s = 0; s < pool.size(); ++s) row_y[a.sun_row(s)] += y(s);
        for (std::size_t s = 0; s < pool.size(); ++s) {
            const std::size_t r = a.sun_row(s);
            pool[s] = {r};
            pool_flux[s] = c.flux(c.row_group(r));
            pool_share[s] = row_y[r] > 0.0 ? y(s) / row_y[r] : 0.0;
            // The pooled count's expected variance where the row is dark: share^2 E[n_row].
            dark_scale[s] = pool_share[s] * pool_share[s] * neighbour_scale(r);
        }
        evidence.assign(rows, {});
        evidence_flux.assign(rows, 0.0);
        for (std::size_t r = 0; r < rows; ++r) {
            evidence[r] = {r};
            evidence_flux[r] = c.flux(c.row_group(r));
        }
    }
};

AnnualCoefficients::AnnualCoefficients(const AnnualGridCounts& grid, std::size_t first, std::size_t count,
                                       const AnnualDarkRates& dark)
    : annual_(grid.annual), shadow_(grid.direct != nullptr), first_(first), cells_(count),
      inv_photons_(grid.photons > 0 ? 1.0 / static_cast<double>(grid.photons) : 0.0), per_count_(grid.per_count),
      gather_per_unit_(grid.gather_per_unit), dark_(dark) {
    const AnnualSky& sky = *annual_.sky;
    if (first + count > grid.cells) throw std::logic_error("AnnualCoefficients: a block beyond the grid");
    if (const DirectCoefficients* d = grid.direct) {
        if (!d->holds(first, first + count) || d->entries != sky.sky_entries() || d->suns != sky.suns().size())
            throw std::logic_error("AnnualCoefficients: direct coefficients of other cells or another sky");
        // The block's columns of the [entry or sun][cell] tables.
        auto columns = [&](const auto& all, std::size_t rows, std::vector<double>& out) {
            out.resize(rows * count);
            for (std::size_t r = 0; r < rows; ++r) std::copy_n(&all[d->at(r, first)], count, &out[r * count]);
        };
        columns(d->sky_lx, d->entries, shadow_sky_lx_);
        columns(d->sky_var, d->entries, shadow_sky_var_);
        columns(d->sun_lx, d->suns, shadow_sun_lx_);
        columns(d->sun_var, d->suns, shadow_sun_var_);
        if (!d->gather_rel_var.empty()) columns(d->gather_rel_var, 1, gather_rel_var_);
    }
    const Counts counts(grid, first);
    SunRows rows(counts);
    pool_ = std::move(rows.pool);
    pool_share_ = std::move(rows.pool_share);
    pool_flux_ = std::move(rows.pool_flux);
    dark_scale_ = std::move(rows.dark_scale);
    evidence_ = std::move(rows.evidence);
    evidence_flux_ = std::move(rows.evidence_flux);
    row_clock_ = std::move(rows.clock);
    if (counts.gathered) gather_loadings(counts, dark);
    sky_coefficients(counts);
    sun_priors(counts);
    sun_coefficients(counts);
}

// Each cell's loadings on its group's common draws (estimate/gather_factors.hpp), so that
// the replicates' draws move with the grid's regions as the cell's light does (one photon
// lights many sensors; the cells nearer each other more alike).
void AnnualCoefficients::gather_loadings(const Counts& c, const AnnualDarkRates& dark) {
    const AnnualSky& sky = *annual_.sky;
    const double photons = inv_photons_ > 0.0 ? 1.0 / inv_photons_ : 0.0;
    auto loadings = [&](std::size_t group, std::vector<float>& out) {
        const std::size_t at = group * kGatherFactorWords;
        if (at + kGatherFactorWords > dark.gather_total.size()) {
            out.resize(out.size() + cells_ * kGatherRegions, 0.0F);
            return;
        }
        const std::span<const double> factor(dark.gather_total.data() + at, kGatherFactorWords);
        std::array<double, kGatherRegions> x{};
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double y = c.gather_y(cell, group);
            const double sd = std::sqrt(std::max(0.0, c.gather_q(cell, group) - y * y * inv_photons_));
            for (std::size_t r = 0; r < kGatherRegions; ++r) x[r] = c.gather_x(cell, group, r);
            out.resize(out.size() + kGatherRegions);
            gather_cell_loadings(factor, y, sd, x, photons,
                                 std::span<float>(out.data() + out.size() - kGatherRegions, kGatherRegions));
        }
    };
    for (std::size_t e = 0; e < sky.sky_entries(); ++e) loadings(c.sky_group(e), sky_loading_);
    for (std::size_t r = 0; r < row_clock_.size(); ++r) loadings(c.row_group(r), sun_loading_);
}

// In an hour's error, a cell that no photon of an emitting group reached is not exact: its
// expected count lambda is small but not zero, and its variance is k^2 lambda. The sky
// patches and the ground: lambda from the cell's indirect registrations pooled over all of
// them, shared out by the groups' fluxes (which decide their photons), lambda =
// (I_c + 1/2) Phi_g / Phi_sky, the 1/2 Jeffreys' prior for a Poisson count seen as 0. (The
// suns: dark_rates.)
void AnnualCoefficients::sky_coefficients(const Counts& c) {
    const std::size_t entries = annual_.sky->sky_entries();
    const double k2 = per_count_ * per_count_;
    sky_.assign(entries * cells_, 0.0);
    sky_q_ = sky_var_ = sky_;
    const double kg = gather_per_unit_, kg2 = kg * kg;
    if (c.gathered) sky_gather_var_ = sky_gather_ = sky_;
    double sky_flux = 0.0;
    for (std::size_t e = 0; e < entries; ++e) sky_flux += c.flux(c.sky_group(e));
    std::vector<double> indirect(cells_, 0.5);
    for (std::size_t e = 0; e < entries; ++e) {
        const std::size_t g = c.sky_group(e);
        if (c.flux(g) > 0.0)
            for (std::size_t cell = 0; cell < cells_; ++cell) indirect[cell] += c.n(cell, g) - c.direct(cell, g);
    }
    for (std::size_t e = 0; e < entries; ++e) {
        const std::size_t g = c.sky_group(e);
        if (!(c.flux(g) > 0.0)) continue;  // emits nothing: exactly zero
        entries_.push_back(e);
        const double share = c.flux(g) / sky_flux;
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double n = c.n(cell, g);
            const double qq = c.q(cell, g);
            const std::size_t i = e * cells_ + cell;
            sky_[i] = per_count_ * n + (shadow_ ? shadow_sky_lx_[i] : 0.0);
            sky_q_[i] = n > 0.0 ? k2 * qq : k2 * indirect[cell] * share;
            // The replicates' variance: the plain counts' (no floor: see sun_coefficients).
            sky_var_[i] = n > 0.0 ? std::max(0.0, k2 * (qq - n * n * inv_photons_)) : 0.0;
            if (!c.gathered) continue;
            const double y = c.gather_y(cell, g), yq = c.gather_q(cell, g);
            sky_gather_[i] = kg * y;
            sky_[i] += kg * y;
            sky_q_[i] += kg2 * yq;
            sky_gather_var_[i] = std::max(0.0, kg2 * (yq - y * y * inv_photons_));
        }
    }
}

// A sun's counts are pooled with those of the same hour on the day before and after, for
// the total and for the direct count alike. Where the neighbours read nothing either (a
// shadow, or light too rare to show), the expected count is the mean count of all such
// (sun, cell) pairs of the detector, with half a count of prior: most are true shadows, and
// their few counts say how rare. The rate per unit of photon share, as a ratio of sums (a
// mean of ratios would weigh a weak sun's rare count by its tiny share).
AnnualDarkRates AnnualCoefficients::dark_rates(const AnnualGridCounts& grid) {
    const Counts c(grid, 0);
    const SunRows p(c);
    auto near_sum = [&](std::size_t r, std::size_t cell, bool direct) {
        double m = 0.0;
        for (const std::size_t o : p.neighbours[r]) m += direct ? c.row_direct(o, cell) : c.n(cell, c.row_group(o));
        return m;
    };
    double dark_n = 0.5, dark_d = 0.5, dark_share = 0.0, dark_share_d = 0.0;
    for (std::size_t r = 0; r < p.neighbours.size(); ++r) {
        if (!c.row_emits(r) || p.neighbours[r].empty()) continue;
        const double weight = p.neighbour_scale(r);
        for (std::size_t cell = 0; cell < grid.cells; ++cell) {
            if (near_sum(r, cell, false) == 0.0) {
                dark_n += c.n(cell, c.row_group(r));
                dark_share += weight;
            }
            if (near_sum(r, cell, true) == 0.0) {
                dark_d += c.row_direct(r, cell);
                dark_share_d += weight;
            }
        }
    }
    // Per neighbour and unit share.
    AnnualDarkRates r;
    r.total = dark_share > 0.0 ? dark_n / dark_share : 0.5;
    r.direct = dark_share_d > 0.0 ? dark_d / dark_share_d : 0.5;
    if (c.gathered) r.gather_total = gather_totals(grid, c);
    return r;
}

// Per light group, its factor (estimate/gather_factors.hpp) from the regions' totals per
// photon, from which each cell's loadings follow (the constructor).
std::vector<double> AnnualCoefficients::gather_totals(const AnnualGridCounts& grid, const Counts& c) {
    std::vector<double> factors(kGatherFactorWords * grid.layout.groups(), 0.0);
    std::array<double, kGatherRegions> sums{};
    std::array<double, TallyLayout::kGatherPairs> products{};
    for (std::size_t g = 0; g < grid.layout.groups(); ++g) {
        for (std::size_t r = 0; r < kGatherRegions; ++r) {
            sums[r] = c.gather_total_y(g, r);
            for (std::size_t q = r; q < kGatherRegions; ++q)
                products[TallyLayout::gather_pair(r, q)] = c.gather_total_q(g, r, q);
        }
        gather_group_factor(sums, products, static_cast<double>(grid.photons),
                            std::span<double>(factors.data() + g * kGatherFactorWords, kGatherFactorWords));
    }
    return factors;
}

// The replicates' centre for a sun's interreflected count (empirical Bayes): light too rare
// to have been seen on any of the three days (a deep cell's rare sun reflection) must still
// be drawn now and then, or the bootstrap cannot see the bias it causes. The suns of one
// clock hour (similar positions over the year) share a prior per cell: a Gamma distribution
// of the count per unit flux, its mean rho the class's ratio of sums and its shape alpha by
// the method of moments (Var n = mu + mu^2 / alpha for a Poisson-Gamma count of mean
// mu = Phi rho). Each sun's centre is its posterior mean given the three days' counts N3
// over their flux E3: Phi (N3 + alpha) / (E3 + alpha / rho) (sun_coefficients).
void AnnualCoefficients::sun_priors(const Counts& c) {
    const std::size_t rows = row_clock_.size();
    eb_rho_.assign(kClockHours * cells_, 0.0);
    eb_alpha_.assign(kClockHours * cells_, 0.0);
    std::vector<double> class_flux(kClockHours, 0.0), sum_mu2(kClockHours * cells_, 0.0),
        excess(kClockHours * cells_, 0.0);
    for (std::size_t r = 0; r < rows; ++r) {
        if (!c.row_emits(r)) continue;
        class_flux[row_clock_[r]] += c.flux(c.row_group(r));
        for (std::size_t cell = 0; cell < cells_; ++cell)
            eb_rho_[row_clock_[r] * cells_ + cell] += c.row_indirect(r, cell);
    }
    for (std::size_t h = 0; h < kClockHours; ++h)
        for (std::size_t cell = 0; cell < cells_; ++cell)
            eb_rho_[h * cells_ + cell] = class_flux[h] > 0.0 ? eb_rho_[h * cells_ + cell] / class_flux[h] : 0.0;
    for (std::size_t r = 0; r < rows; ++r) {
        if (!c.row_emits(r)) continue;
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const std::size_t j = row_clock_[r] * cells_ + cell;
            const double mu = c.flux(c.row_group(r)) * eb_rho_[j], n = c.row_indirect(r, cell);
            sum_mu2[j] += mu * mu;
            excess[j] += (n - mu) * (n - mu) - n;
        }
    }
    // No excess over Poisson: the suns of the class share one rate (alpha infinite).
    for (std::size_t j = 0; j < eb_alpha_.size(); ++j)
        eb_alpha_[j] = excess[j] > 0.0 ? sum_mu2[j] / excess[j] : std::numeric_limits<double>::infinity();
}

// Per (sun, cell): the estimate and its hourly errors; per (row, cell) a fresh run's
// draw of its interreflected count (replicate()).
void AnnualCoefficients::sun_coefficients(const Counts& c) {
    const AnnualSky& sky = *annual_.sky;
    const std::size_t suns = sky.suns().size();
    const double k2 = per_count_ * per_count_;
    sun_.assign(suns * cells_, 0.0);
    sun_q_ = direct_ = direct_var_ = sun_;
    rep_direct_mu_.assign(suns * cells_, 0.0f);
    for (std::size_t s = 0; s < suns; ++s) {
        if (!c.sun_emits(s)) continue;
        const double share = pool_share_[s];
        const std::size_t own = annual_.sun_row(s);
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            // Pooled over the rows it reads per unit of flux (a ratio of sums: a weak
            // neighbour's few photons count for little), for this sun's photons.
            double d_sum = 0.0, i_sum = 0.0, v_sum = 0.0;
            for (const std::size_t r : pool_[s]) {
                d_sum += c.row_direct(r, cell);
                i_sum += c.row_indirect(r, cell);
                v_sum += c.row_indirect_moment(r, cell);
            }
            // Its own direct count (0 with shared rows: their direct light is the shadow rays').
            const double d = c.row_direct(own, cell);
            const double m_d = share * d_sum, m_i = share * i_sum, m_v = share * v_sum;  // pooled means
            const std::size_t i = s * cells_ + cell;
            // The estimate: the hour's own direct sun (a shadow's edge moves between days:
            // ASE's direct sun stays the hour's own), plus the interreflected sun pooled over
            // the three days. The sun moves at most 0.4 degrees a day at a given hour, which
            // hardly moves its reflections, and the pooled count has a third of the lumps:
            // at 10 M photons one count is 1,000-3,600 lx on the example's sensors, more
            // than every threshold, so the lumps decide the threshold figures' noise bias
            // (docs/VALIDATION.md "Annual daylight": UDI useful's halved).
            // With shadow rays the photons' d is 0 (direct_apart) and the direct sun theirs.
            const double shadow_sun = shadow_ ? shadow_sun_lx_[i] : 0.0;
            sun_[i] = per_count_ * (d + m_i) + shadow_sun;
            direct_[i] = shadow_ ? shadow_sun : per_count_ * d;
            // The hour's errors. Direct: its count's variance, taken from the pooled mean (a
            // few-count cell's own count is a poor guess of it: 0 says "never"). Total: that
            // plus the pooled indirect's exact variance c^2 sum v. Where the cell and its
            // neighbours all read nothing, the detector's dark mean (never a variance of 0 for
            // a count that might have been 1).
            direct_var_[i] = shadow_ ? shadow_sun_var_[i] : k2 * (m_d > 0.0 ? m_d : dark_.direct * dark_scale_[s]);
            const double total_var = m_d + share * m_v;
            sun_q_[i] = k2 * (total_var > 0.0 ? total_var : dark_.total * dark_scale_[s]);
            rep_direct_mu_[i] = static_cast<float>(m_d);
        }
    }
    row_centres(c);
    if (c.gathered) sun_gathered(c);
}

// A fresh run (replicate()): a sun's direct count Poisson of its pooled mean (above); a
// row's indirect count around its empirical-Bayes centre (sun_priors), then pooled like the
// estimate. No dark floor here: over many hours the plain counts are an unbiased variance,
// and a floor on every unreached (group, cell) would add a variance the counts already hold
// (docs/VALIDATION.md "Annual daylight": the floor made DA's sigma twice, continuous DA's 16
// times the scatter); the posterior mean adds none on average over the class.
void AnnualCoefficients::row_centres(const Counts& c) {
    const std::size_t rows = row_clock_.size();
    rep_indirect_mu_.assign(rows * cells_, 0.0f);
    rep_indirect_var_ = rep_indirect_mu_;
    for (std::size_t r = 0; r < rows; ++r) {
        if (!c.row_emits(r)) continue;
        const double flux = c.flux(c.row_group(r));
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            double i_sum = 0.0, v_sum = 0.0;
            for (const std::size_t o : evidence_[r]) {
                i_sum += c.row_indirect(o, cell);
                v_sum += c.row_indirect_moment(o, cell);
            }
            const std::size_t i = r * cells_ + cell, j = row_clock_[r] * cells_ + cell;
            const double rho = eb_rho_[j], alpha = eb_alpha_[j];
            const double e3 = evidence_flux_[r];  // the flux of the counts it reads
            const double centre_i = !(rho > 0.0)        ? 0.0
                                    : std::isinf(alpha) ? flux * rho
                                                        : flux * (i_sum + alpha) / (e3 + alpha / rho);
            rep_indirect_mu_[i] = static_cast<float>(centre_i);
            // Its variance in the pooled counts' proportion of second moment to count (a
            // photon may register a cell more than once).
            rep_indirect_var_[i] = static_cast<float>(centre_i * (i_sum > 0.0 ? std::max(1.0, v_sum / i_sum) : 1.0));
        }
    }
}

// A sun's gathered light, pooled over the rows it reads as its interreflected counts
// are: X = share sum Y_r, variance share^2 sum Q. Where they gathered less than their
// clock hour's rows do per unit flux (few photons, or none), the variance is at least the
// class's: share^2 r mu Phi_3, mu the class's Y per unit flux and r its Q per unit Y (a
// sun hour seen as nothing is not exact).
void AnnualCoefficients::sun_gathered(const Counts& c) {
    const std::size_t suns = annual_.sky->suns().size(), rows = row_clock_.size();
    const double kg = gather_per_unit_, kg2 = kg * kg;
    sun_gather_.assign(rows * cells_, 0.0);
    sun_gather_var_ = sun_gather_;
    std::vector<double> class_flux(kClockHours, 0.0), class_y(kClockHours * cells_, 0.0), class_q(class_y);
    for (std::size_t r = 0; r < rows; ++r) {
        if (!c.row_emits(r)) continue;
        const std::size_t h = row_clock_[r];
        class_flux[h] += c.flux(c.row_group(r));
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double y = c.gather_y(cell, c.row_group(r)), q = c.gather_q(cell, c.row_group(r));
            sun_gather_[r * cells_ + cell] = kg * y;
            sun_gather_var_[r * cells_ + cell] = std::max(0.0, kg2 * (q - y * y * inv_photons_));
            class_y[h * cells_ + cell] += y;
            class_q[h * cells_ + cell] += q;
        }
    }
    std::vector<double>& pooled = sun_gather_pooled_;
    pooled.assign(suns * cells_, 0.0);
    pool_gathered(sun_gather_, pooled);
    for (std::size_t s = 0; s < suns; ++s) {
        if (!c.sun_emits(s)) continue;
        const std::size_t h = row_clock_[annual_.sun_row(s)];
        const double share = pool_share_[s], flux3 = pool_flux_[s];
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const std::size_t i = s * cells_ + cell, j = h * cells_ + cell;
            double q3 = 0.0;
            for (const std::size_t r : pool_[s]) q3 += c.gather_q(cell, c.row_group(r));
            // r mu = (Q / Y) (Y / Phi): the class's Q per unit flux.
            const double expected = class_flux[h] > 0.0 ? class_q[j] / class_flux[h] * flux3 : 0.0;
            sun_[i] += pooled[i];
            sun_q_[i] += share * share * kg2 * std::max(q3, expected);
        }
    }
}

void AnnualCoefficients::pool_gathered(const std::vector<double>& own, std::vector<double>& sun) const {
    for (std::size_t s = 0; s < pool_.size(); ++s) {
        const double share = pool_share_[s];
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            double x = 0.0;
            for (const std::size_t r : pool_[s]) x += own[r * cells_ + cell];
            sun[s * cells_ + cell] += share * x;
        }
    }
}

void AnnualCoefficients::pool(const std::vector<double>& indirect, const std::vector<double>& direct,
                              std::vector<double>& sun) const {
    const std::size_t suns = pool_.size();
    sun.assign(suns * cells_, 0.0);
    for (std::size_t s = 0; s < suns; ++s) {
        const double c = pool_share_[s];
        double* out = &sun[s * cells_];
        for (const std::size_t r : pool_[s]) {
            const double* x = &indirect[r * cells_];
            for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] += x[cell];
        }
        const double* d = &direct[s * cells_];
        for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] = d[cell] + c * out[cell];
    }
}

namespace {

// row[c] = sum over the entries with weight > 0 of w^power x[e * cells + c], for the cells
// c in [first, cells), the entries in order, each term added by a fused multiply-add (one
// rounding, IEEE's fma): the same sums whatever the vector width and the CPU.
template <int kPower>
inline void sky_sum_from(const double* weight, const std::size_t* entries, std::size_t n, const double* x,
                         std::size_t cells, std::size_t first, double* row) {
    std::fill(row + first, row + cells, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t e = entries[i];
        if (!(weight[e] > 0.0)) continue;
        const double w = kPower == 1 ? weight[e] : weight[e] * weight[e];
        const double* c = &x[e * cells];
        for (std::size_t cell = first; cell < cells; ++cell) row[cell] = std::fma(w, c[cell], row[cell]);
    }
}

template <int kPower>
void sky_sum(const double* weight, const std::size_t* entries, std::size_t n, const double* x, std::size_t cells,
             double* row) {
    sky_sum_from<kPower>(weight, entries, n, x, cells, 0, row);
}

// The same sums, 4 x kVectors cells at a time in AVX2 registers over the entries (a sum
// that stays in a register is not stored and reloaded per entry, and eight independent
// sums keep both FMA units busy); the rest as above.
template <int kPower, int kVectors>
__attribute__((target("avx2,fma"), always_inline)) inline void sky_sum_lanes(const double* weight,
                                                                             const std::size_t* entries, std::size_t n,
                                                                             const double* x, std::size_t cells,
                                                                             std::size_t first, double* row) {
    __m256d sum[kVectors];
    for (int v = 0; v < kVectors; ++v) sum[v] = _mm256_setzero_pd();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t e = entries[i];
        if (!(weight[e] > 0.0)) continue;
        const __m256d w = _mm256_set1_pd(kPower == 1 ? weight[e] : weight[e] * weight[e]);
        const double* c = &x[e * cells + first];
        for (int v = 0; v < kVectors; ++v) sum[v] = _mm256_fmadd_pd(w, _mm256_loadu_pd(c + 4 * v), sum[v]);
    }
    for (int v = 0; v < kVectors; ++v) _mm256_storeu_pd(row + first + 4 * v, sum[v]);
}

template <int kPower>
__attribute__((target("avx2,fma"))) void sky_sum_avx2(const double* weight, const std::size_t* entries, std::size_t n,
                                                      const double* x, std::size_t cells, double* row) {
    std::size_t first = 0;
    for (; first + 32 <= cells; first += 32) sky_sum_lanes<kPower, 8>(weight, entries, n, x, cells, first, row);
    for (; first + 16 <= cells; first += 16) sky_sum_lanes<kPower, 4>(weight, entries, n, x, cells, first, row);
    for (; first + 4 <= cells; first += 4) sky_sum_lanes<kPower, 1>(weight, entries, n, x, cells, first, row);
    if (first < cells) sky_sum_from<kPower>(weight, entries, n, x, cells, first, row);  // the last few
}

}  // namespace

void AnnualCoefficients::sky_row(const AnnualHour& hour, const std::vector<double>& x, int power,
                                 std::vector<double>& row) const {
    // Most of the post-processing's time: AVX2's four lanes where the CPU has them.
    static const bool avx2 = __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("fma") != 0;
    const double* weight = annual_.sky->sky_weights(hour.row);
    auto f = power == 1 ? (avx2 ? sky_sum_avx2<1> : sky_sum<1>) : (avx2 ? sky_sum_avx2<2> : sky_sum<2>);
    f(weight, entries_.data(), entries_.size(), x.data(), cells_, row.data());
}

void AnnualCoefficients::combine(const std::vector<double>& sky, const std::vector<double>& sun,
                                 const std::vector<double>& direct, AnnualSeries& out) const {
    const AnnualSky& s = *annual_.sky;
    const std::size_t hours = s.hours().size();
    // The rows written below are the same in every series this makes (the daylit hours, and
    // their direct where the hour has a sun): the others stay the zeros they were made with,
    // so a series of this block's size is not cleared again (a replicate year's 4.5 MB).
    if (out.hours != hours || out.sensors != cells_ || out.total_lx.size() != hours * cells_ ||
        out.direct_lx.size() != hours * cells_) {
        out.hours = hours;
        out.sensors = cells_;
        out.total_lx.assign(hours * cells_, 0.0);
        out.direct_lx.assign(hours * cells_, 0.0);
    }
    std::vector<double> row(cells_);
    for (std::size_t h = 0; h < hours; ++h) {
        const AnnualHour& hour = s.hours()[h];
        if (!hour.daylit) continue;
        sky_row(hour, sky, 1, row);
        double* total = &out.total_lx[h * cells_];
        if (hour.sun >= 0) {
            const double* c = &sun[static_cast<std::size_t>(hour.sun) * cells_];
            const double* d = &direct[static_cast<std::size_t>(hour.sun) * cells_];
            double* dir = &out.direct_lx[h * cells_];
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                row[cell] += c[cell];
                dir[cell] = d[cell];
            }
        }
        for (std::size_t cell = 0; cell < cells_; ++cell) total[cell] = row[cell];
    }
}

void AnnualCoefficients::series(AnnualSeries& estimate, AnnualSeries& sigma) const {
    this->estimate(estimate);
    // Sum of w^2 k^2 q over the groups (the weights squared: lum^2 / yearly^2), minus E^2 / N.
    const AnnualSky& s = *annual_.sky;
    sigma.hours = estimate.hours;
    sigma.sensors = cells_;
    sigma.total_lx.assign(estimate.total_lx.size(), 0.0);
    sigma.direct_lx.assign(estimate.direct_lx.size(), 0.0);
    std::vector<double> row(cells_), direct, direct_var, gathered;
    if (shadow_) direct.resize(cells_), direct_var.resize(cells_);
    if (!gather_rel_var_.empty()) gathered.resize(cells_);
    for (std::size_t h = 0; h < s.hours().size(); ++h) {
        const AnnualHour& hour = s.hours()[h];
        if (!hour.daylit) continue;
        sky_row(hour, sky_q_, 2, row);
        const double* e_h = &estimate.total_lx[h * cells_];
        double* sig = &sigma.total_lx[h * cells_];
        if (hour.sun >= 0) {
            const std::size_t sun = static_cast<std::size_t>(hour.sun);
            double* dsig = &sigma.direct_lx[h * cells_];
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                row[cell] += sun_q_[sun * cells_ + cell];
                dsig[cell] = (std::sqrt(direct_var_[sun * cells_ + cell]));
            }
        }
        if (!shadow_) {
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                const double e = e_h[cell];
                sig[cell] = (std::sqrt(std::max(0.0, row[cell] - e * e * inv_photons_)));
            }
            continue;
        }
        // The photons' part (the estimate less the shadow rays' direct), plus the shadow
        // rays' own variance, and the gather's rays' (relative, on the gathered part).
        direct_hour(hour, false, direct);
        direct_hour(hour, true, direct_var);
        if (!gathered.empty()) {
            sky_row(hour, sky_gather_, 1, gathered);
            const double* sun = hour.sun >= 0 ? &sun_gather_pooled_[static_cast<std::size_t>(hour.sun) * cells_]
                                              : nullptr;
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                const double g = gathered[cell] + (sun != nullptr ? sun[cell] : 0.0);
                direct_var[cell] += gather_rel_var_[cell] * g * g;
            }
        }
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double e = e_h[cell] - direct[cell];
            sig[cell] = std::sqrt(std::max(0.0, row[cell] - e * e * inv_photons_) + direct_var[cell]);
        }
    }
}

void AnnualCoefficients::direct_hour(const AnnualHour& hour, bool variance, std::vector<double>& out) const {
    sky_row(hour, variance ? shadow_sky_var_ : shadow_sky_lx_, variance ? 2 : 1, out);
    if (hour.sun < 0) return;
    const std::size_t s = static_cast<std::size_t>(hour.sun) * cells_;
    const std::vector<double>& sun = variance ? shadow_sun_var_ : shadow_sun_lx_;
    for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] += sun[s + cell];
}

void AnnualCoefficients::estimate(AnnualSeries& out) const {
    if (!have_estimate_) {
        combine(sky_, sun_, direct_, estimate_);
        have_estimate_ = true;
    }
    out = estimate_;
}

void AnnualCoefficients::centre(AnnualSeries& out) const {
    // The sky and ground at their counts; a sun's direct count at its pooled mean and its
    // rows' indirect counts at their centres, pooled as the estimate pools them.
    std::vector<double> indirect(rep_indirect_mu_.size()), direct(direct_.size()), sun;
    for (std::size_t i = 0; i < indirect.size(); ++i) indirect[i] = per_count_ * rep_indirect_mu_[i];
    for (std::size_t i = 0; i < direct.size(); ++i)
        direct[i] = shadow_ ? shadow_sun_lx_[i] : per_count_ * rep_direct_mu_[i];
    pool(indirect, direct, sun);
    if (!sun_gather_.empty()) pool_gathered(sun_gather_, sun);
    combine(sky_, sun, direct, out);
}

void AnnualCoefficients::replicate(std::uint64_t seed, std::uint64_t replicate, AnnualSeries& out) const {
    // A fresh run's coefficients: each count redrawn as a Poisson count of its variance,
    // mu = var / k^2, around its centre: a few-count sun hour is mostly nothing and now and
    // then a whole count, as a run's noise is, not a small normal wobble that crosses a
    // threshold every time. Large counts are drawn as normal (the same to 1/sqrt(mu)).
    const double k = per_count_, k2 = k * k;
    std::vector<double> sky(sky_), indirect(rep_indirect_mu_.size(), 0.0), direct(direct_.size(), 0.0), sun;
    std::vector<double> gathered(sun_gather_.size(), 0.0);
    const std::size_t suns = pool_.size(), rows = row_clock_.size();
    // The gathered light's common draws, per sky entry and sun row: one stream per
    // replicate, the same for every block.
    std::vector<double> common_sky, common_sun;
    if (!sun_gather_.empty()) {
        PhiloxBits bits(seed ^ kGatherFactorKey, replicate);
        for (std::size_t e = 0; e < annual_.sky->sky_entries() * kGatherRegions; ++e)
            common_sky.push_back(standard_normal(bits));
        for (std::size_t r = 0; r < rows * kGatherRegions; ++r) common_sun.push_back(standard_normal(bits));
    }
    std::vector<ReplicateStream> streams;
    streams.reserve(cells_);
    for (std::size_t cell = 0; cell < cells_; ++cell) {
        streams.emplace_back(seed, (replicate << 40) | (first_ + cell), k);
        if (!gather_rel_var_.empty()) streams.back().rays = std::sqrt(gather_rel_var_[cell]) * streams.back().unit();
    }
    for (const std::size_t e : entries_)
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            ReplicateStream& c = streams[cell];
            const std::size_t i = e * cells_ + cell;
            sky[i] += c.count(sky_var_[i]);
            if (shadow_) sky[i] += c.normal_noise(shadow_sky_var_[i]);
            if (!sky_gather_var_.empty())
                sky[i] += c.rays * sky_gather_[i] + c.gathered(sky_gather_var_[i], &sky_loading_[i * kGatherRegions],
                                                               &common_sky[e * kGatherRegions]);
        }
    // Sun s: its direct count around its pooled mean; row s: its gathered light (its
    // indirect counts: below). A cell draws them in this order whatever the rows.
    for (std::size_t s = 0; s < std::max(suns, rows); ++s)
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            ReplicateStream& c = streams[cell];
            const std::size_t i = s * cells_ + cell;
            if (s < suns) {
                const double mu_d = rep_direct_mu_[i];
                if (shadow_) direct[i] = shadow_sun_lx_[i] + c.normal_noise(shadow_sun_var_[i]);
                else if (mu_d > 0.0) direct[i] = k * mu_d + c.count(k2 * mu_d);
            }
            if (s < rows && !sun_gather_.empty())
                gathered[i] = (1.0 + c.rays) * sun_gather_[i] + c.gathered(sun_gather_var_[i],
                                                                           &sun_loading_[i * kGatherRegions],
                                                                           &common_sun[s * kGatherRegions]);
        }
    draw_sun_indirect(seed, replicate, indirect);
    pool(indirect, direct, sun);
    if (!gathered.empty()) pool_gathered(gathered, sun);
    combine(sky, sun, direct, out);
}

// A sun's interreflected counts over the block's cells, each Poisson of its variance v_c
// around its centre: independent Poisson counts are a Poisson total of mean V = sum v_c
// shared out among the cells in proportion to v_c (multinomially), which costs one draw
// per sun and one per count instead of one per cell, most of them 0 (a few-count sun
// hour's cells). Where V is large the cells are drawn one by one. The block's own stream:
// (seed, replicate, its first cell), the blocks being the same however the work is shared.
void AnnualCoefficients::draw_sun_indirect(std::uint64_t seed, std::uint64_t replicate,
                                           std::vector<double>& indirect) const {
    const double k = per_count_;
    if (!(k > 0.0)) return;
    PhiloxBits bits(seed, (replicate << 40) | kSunDrawStream | first_);
    std::normal_distribution<double> normal;
    std::vector<double> cumulative(cells_);
    for (std::size_t r = 0; r < row_clock_.size(); ++r) {
        const std::size_t row = r * cells_;
        double total = 0.0;
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double mu = rep_indirect_mu_[row + cell], var = rep_indirect_var_[row + cell];
            if (mu != 0.0 || var > 0.0) indirect[row + cell] = k * (mu - var);
            total += std::max(0.0, var);
            cumulative[cell] = total;
        }
        if (!(total > 0.0)) continue;
        if (total > kSharedSunDrawMean) {
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                const double var = rep_indirect_var_[row + cell];
                if (!(var > 0.0)) continue;
                indirect[row + cell] += var > 1000.0 ? k * (var + std::sqrt(var) * normal(bits))
                                                     : k * static_cast<double>(
                                                               std::poisson_distribution<std::int64_t>(var)(bits));
            }
            continue;
        }
        const std::int64_t counts = std::poisson_distribution<std::int64_t>(total)(bits);
        for (std::int64_t n = 0; n < counts; ++n) {
            const double u = std::generate_canonical<double, 53>(bits) * total;
            const std::size_t cell = static_cast<std::size_t>(
                std::min<std::ptrdiff_t>(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
                                         static_cast<std::ptrdiff_t>(cells_) - 1));
            indirect[row + cell] += k;
        }
    }
}

}  // namespace luxtrace
