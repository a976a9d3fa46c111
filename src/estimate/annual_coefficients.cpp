#include "luxtrace/estimate/annual_coefficients.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace luxtrace {

AnnualCoefficients::AnnualCoefficients(const AnnualSetup& annual, const TallyLayout& layout,
                                       std::span<const std::uint64_t> data, std::size_t det, std::size_t cells,
                                       double per_count, std::uint64_t photons, std::span<const double> group_flux_lm)
    : annual_(annual), cells_(cells), inv_photons_(photons > 0 ? 1.0 / static_cast<double>(photons) : 0.0),
      per_count_(per_count) {
    const AnnualSky& sky = *annual.sky;
    const std::size_t entries = sky.sky_entries(), suns = sky.suns().size();
    const double k2 = per_count * per_count;
    auto flux = [&](std::size_t group) { return group < group_flux_lm.size() ? group_flux_lm[group] : 0.0; };
    auto n_of = [&](std::size_t cell, std::size_t group) {
        return static_cast<double>(data[layout.detector_n(det, cell, 0, group)]);
    };
    auto direct_of = [&](std::size_t cell, std::size_t group) {
        return layout.direct_scores() ? static_cast<double>(data[layout.detector_direct(det, cell, group)]) : 0.0;
    };
    std::vector<std::size_t> sky_groups, sun_groups;
    for (std::size_t e = 0; e < entries; ++e)
        sky_groups.push_back(e == sky.ground_entry() ? annual.ground_group : annual.first_patch_group + e);
    for (std::size_t s = 0; s < suns; ++s) sun_groups.push_back(annual.first_sun_group + s);
    // In an hour's error, a cell that no photon of an emitting group reached is not exact:
    // its expected count lambda is small but not zero, and its variance is k^2 lambda. The
    // sky patches and the ground: lambda from the cell's indirect registrations pooled over
    // all of them, shared out by the groups' fluxes (which decide their photons), lambda =
    // (I_c + 1/2) Phi_g / Phi_sky, the 1/2 Jeffreys' prior for a Poisson count seen as 0. A
    // sun: its counts pooled with those of the same hour on the day before and after, for
    // the total and for the direct count alike; where all read 0, the mean over all such
    // dark (sun, cell) pairs of the detector.
    sky_.assign(entries * cells, 0.0);
    sky_q_ = sky_var_ = sky_;
    {
        double sky_flux = 0.0;
        for (std::size_t g : sky_groups) sky_flux += flux(g);
        std::vector<double> indirect(cells, 0.5);
        for (std::size_t g : sky_groups)
            if (flux(g) > 0.0)
                for (std::size_t cell = 0; cell < cells; ++cell) indirect[cell] += n_of(cell, g) - direct_of(cell, g);
        for (std::size_t e = 0; e < entries; ++e) {
            const std::size_t g = sky_groups[e];
            if (!(flux(g) > 0.0)) continue;  // emits nothing: exactly zero
            entries_.push_back(e);
            const double share = flux(g) / sky_flux;
            for (std::size_t cell = 0; cell < cells; ++cell) {
                const double n = n_of(cell, g);
                const double qq = static_cast<double>(data[layout.detector_q(det, cell, 0, g)]);
                const std::size_t i = e * cells + cell;
                sky_[i] = per_count * n;
                sky_q_[i] = n > 0.0 ? k2 * qq : k2 * indirect[cell] * share;
                // The replicates' variance: the plain counts' (no floor: see the suns below).
                sky_var_[i] = n > 0.0 ? std::max(0.0, k2 * (qq - n * n * inv_photons_)) : 0.0;
            }
        }
    }
    sun_.assign(suns * cells, 0.0);
    sun_q_ = direct_ = direct_var_ = sun_;
    rep_direct_mu_.assign(suns * cells, 0.0f);
    rep_indirect_mu_ = rep_indirect_var_ = rep_direct_mu_;
    std::vector<int> sun_at_hour(sky.hours().size(), -1);
    for (std::size_t s = 0; s < suns; ++s) sun_at_hour[sky.suns()[s]] = static_cast<int>(s);
    // Per sun: the emitting suns of the same hour on the day before and after (their
    // positions within half a degree: the same shadows and nearly the same reflections), and
    // this sun's share of the photons of the three, pool_share_ = Phi_s / (Phi_s + sum Phi_o)
    // (the groups' fluxes decide their photons); share: of the neighbours' photons alone.
    pool_.assign(suns, {});
    pool_share_.assign(suns, 1.0);
    std::vector<double> share(suns, 0.0);
    for (std::size_t s = 0; s < suns; ++s) {
        if (!(flux(sun_groups[s]) > 0.0)) continue;
        const std::size_t h = sky.suns()[s];
        double near_flux = 0.0;
        for (const std::size_t other : {h - 24, h + 24})  // h - 24 wraps past the end when h < 24
            if (other < sun_at_hour.size() && sun_at_hour[other] >= 0) {
                const std::size_t o = static_cast<std::size_t>(sun_at_hour[other]);
                if (flux(sun_groups[o]) > 0.0) {
                    pool_[s].push_back(o);
                    near_flux += flux(sun_groups[o]);
                }
            }
        share[s] = near_flux > 0.0 ? flux(sun_groups[s]) / near_flux : 0.0;
        pool_share_[s] = flux(sun_groups[s]) / (flux(sun_groups[s]) + near_flux);
    }
    auto near_sum = [&](std::size_t s, std::size_t cell, bool direct) {
        double m = 0.0;
        for (const std::size_t o : pool_[s]) m += direct ? direct_of(cell, sun_groups[o]) : n_of(cell, sun_groups[o]);
        return m;
    };
    // Where the neighbours read nothing either (a shadow, or light too rare to show), the
    // expected count is the mean count of all such (sun, cell) pairs of the detector, with
    // half a count of prior: most are true shadows, and their few counts say how rare.
    // The rate per unit of photon share, as a ratio of sums (a mean of ratios would weigh
    // a weak sun's rare count by its tiny share).
    double dark_n = 0.5, dark_d = 0.5, dark_share = 0.0, dark_share_d = 0.0;
    for (std::size_t s = 0; s < suns; ++s) {
        if (!(flux(sun_groups[s]) > 0.0) || pool_[s].empty()) continue;
        const double weight = share[s] * static_cast<double>(pool_[s].size());
        for (std::size_t cell = 0; cell < cells; ++cell) {
            if (near_sum(s, cell, false) == 0.0) {
                dark_n += n_of(cell, sun_groups[s]);
                dark_share += weight;
            }
            if (near_sum(s, cell, true) == 0.0) {
                dark_d += direct_of(cell, sun_groups[s]);
                dark_share_d += weight;
            }
        }
    }
    // Per neighbour and unit share.
    const double dark_lambda_n = dark_share > 0.0 ? dark_n / dark_share : 0.5;
    const double dark_lambda_d = dark_share_d > 0.0 ? dark_d / dark_share_d : 0.5;
    // Per (sun, cell): the direct count d, the other (interreflected) registrations
    // i = n - d and their second moment v = q - d (a photon's direct count in a cell is 0 or
    // 1, its square itself, tally.hpp; a photon registering a cell both directly and after a
    // reflection is taken as rare).
    auto direct_count = [&](std::size_t s, std::size_t cell) { return direct_of(cell, sun_groups[s]); };
    auto indirect_count = [&](std::size_t s, std::size_t cell) {
        return n_of(cell, sun_groups[s]) - direct_of(cell, sun_groups[s]);
    };
    auto indirect_moment = [&](std::size_t s, std::size_t cell) {
        return static_cast<double>(data[layout.detector_q(det, cell, 0, sun_groups[s])]) -
               direct_of(cell, sun_groups[s]);
    };
    // The replicates' centre for a sun's interreflected count (empirical Bayes): light too
    // rare to have been seen on any of the three days (a deep cell's rare sun reflection)
    // must still be drawn now and then, or the bootstrap cannot see the bias it causes. The
    // suns of one clock hour (similar positions over the year) share a prior per cell: a
    // Gamma distribution of the count per unit flux, its mean rho the class's ratio of sums
    // and its shape alpha by the method of moments (Var n = mu + mu^2 / alpha for a
    // Poisson-Gamma count of mean mu = Phi rho). Each sun's centre is its posterior mean
    // given the three days' counts N3 over their flux E3: Phi (N3 + alpha) / (E3 + alpha / rho).
    constexpr std::size_t kClockHours = 24;
    std::vector<double> eb_rho(kClockHours * cells, 0.0), eb_alpha(kClockHours * cells, 0.0);
    {
        std::vector<double> class_flux(kClockHours, 0.0), sum_mu2(kClockHours * cells, 0.0),
            excess(kClockHours * cells, 0.0);
        auto clock = [&](std::size_t s) { return sky.suns()[s] % kClockHours; };
        for (std::size_t s = 0; s < suns; ++s) {
            if (!(flux(sun_groups[s]) > 0.0)) continue;
            class_flux[clock(s)] += flux(sun_groups[s]);
            for (std::size_t cell = 0; cell < cells; ++cell) eb_rho[clock(s) * cells + cell] += indirect_count(s, cell);
        }
        for (std::size_t h = 0; h < kClockHours; ++h)
            for (std::size_t cell = 0; cell < cells; ++cell)
                eb_rho[h * cells + cell] = class_flux[h] > 0.0 ? eb_rho[h * cells + cell] / class_flux[h] : 0.0;
        for (std::size_t s = 0; s < suns; ++s) {
            if (!(flux(sun_groups[s]) > 0.0)) continue;
            for (std::size_t cell = 0; cell < cells; ++cell) {
                const std::size_t j = clock(s) * cells + cell;
                const double mu = flux(sun_groups[s]) * eb_rho[j], n = indirect_count(s, cell);
                sum_mu2[j] += mu * mu;
                excess[j] += (n - mu) * (n - mu) - n;
            }
        }
        // No excess over Poisson: the suns of the class share one rate (alpha infinite).
        for (std::size_t j = 0; j < eb_alpha.size(); ++j)
            eb_alpha[j] = excess[j] > 0.0 ? sum_mu2[j] / excess[j] : std::numeric_limits<double>::infinity();
    }
    for (std::size_t s = 0; s < suns; ++s) {
        if (!(flux(sun_groups[s]) > 0.0)) continue;
        const double dark_scale = pool_[s].empty() ? 1.0 : static_cast<double>(pool_[s].size()) * share[s];
        const double c = pool_share_[s];
        for (std::size_t cell = 0; cell < cells; ++cell) {
            // Pooled over the three days per unit of flux (a ratio of sums: a weak
            // neighbour's few photons count for little), for this sun's photons.
            double d_sum = direct_count(s, cell), i_sum = indirect_count(s, cell), v_sum = indirect_moment(s, cell);
            for (const std::size_t o : pool_[s]) {
                d_sum += direct_count(o, cell);
                i_sum += indirect_count(o, cell);
                v_sum += indirect_moment(o, cell);
            }
            const double d = direct_count(s, cell);
            const double m_d = c * d_sum, m_i = c * i_sum, m_v = c * v_sum;  // pooled means
            const std::size_t i = s * cells + cell;
            // The estimate: the hour's own direct sun (a shadow's edge moves between days:
            // ASE's direct sun stays the hour's own), plus the interreflected sun pooled over
            // the three days. The sun moves at most 0.4 degrees a day at a given hour, which
            // hardly moves its reflections, and the pooled count has a third of the lumps:
            // at 10 M photons one count is 1,000-3,600 lx on the example's sensors, more
            // than every threshold, so the lumps decide the threshold figures' noise bias
            // (docs/VALIDATION.md "Annual daylight": UDI useful's halved).
            sun_[i] = per_count * (d + m_i);
            direct_[i] = per_count * d;
            // The hour's errors. Direct: its count's variance, taken from the pooled mean (a
            // few-count cell's own count is a poor guess of it: 0 says "never"). Total: that
            // plus the pooled indirect's exact variance c^2 sum v. Where the cell and its
            // neighbours all read nothing, the detector's dark mean (never a variance of 0 for
            // a count that might have been 1).
            direct_var_[i] = k2 * (m_d > 0.0 ? m_d : dark_lambda_d * dark_scale);
            const double total_var = m_d + c * m_v;
            sun_q_[i] = k2 * (total_var > 0.0 ? total_var : dark_lambda_n * dark_scale);
            // A fresh run (replicate()): the direct count Poisson of mean m_d; the indirect
            // count around its empirical-Bayes centre (above), pooled like the estimate. No
            // dark floor here: over many hours the plain counts are an unbiased variance,
            // and a floor on every unreached (group, cell) would add a variance the counts
            // already hold (docs/VALIDATION.md "Annual daylight": the floor made DA's sigma
            // twice, continuous DA's 16 times the scatter); the posterior mean adds none on
            // average over the class.
            const std::size_t j = (sky.suns()[s] % kClockHours) * cells + cell;
            const double rho = eb_rho[j], alpha = eb_alpha[j];
            const double e3 = flux(sun_groups[s]) / c;  // the three days' flux
            const double centre_i = !(rho > 0.0)        ? 0.0
                                    : std::isinf(alpha) ? flux(sun_groups[s]) * rho
                                                        : flux(sun_groups[s]) * (i_sum + alpha) / (e3 + alpha / rho);
            rep_direct_mu_[i] = static_cast<float>(m_d);
            rep_indirect_mu_[i] = static_cast<float>(centre_i);
            // Its variance in the pooled counts' proportion of second moment to count (a
            // photon may register a cell more than once).
            rep_indirect_var_[i] = static_cast<float>(centre_i * (i_sum > 0.0 ? std::max(1.0, v_sum / i_sum) : 1.0));
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
        const double* own = &indirect[s * cells_];
        for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] = own[cell];
        for (const std::size_t o : pool_[s]) {
            const double* x = &indirect[o * cells_];
            for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] += x[cell];
        }
        const double* d = &direct[s * cells_];
        for (std::size_t cell = 0; cell < cells_; ++cell) out[cell] = d[cell] + c * out[cell];
    }
}

void AnnualCoefficients::sky_row(const AnnualHour& hour, const std::vector<double>& x, int power,
                                 std::vector<double>& row) const {
    const AnnualSky& s = *annual_.sky;
    const std::vector<double>& yearly = s.yearly_luminance();
    const double* lum = s.sky_vector(hour.row);
    std::fill(row.begin(), row.end(), 0.0);
    for (const std::size_t e : entries_) {
        if (!(lum[e] > 0.0 && yearly[e] > 0.0)) continue;
        const double w = power == 1 ? lum[e] / yearly[e] : (lum[e] / yearly[e]) * (lum[e] / yearly[e]);
        const double* c = &x[e * cells_];
        for (std::size_t cell = 0; cell < cells_; ++cell) row[cell] += w * c[cell];
    }
}

void AnnualCoefficients::combine(const std::vector<double>& sky, const std::vector<double>& sun,
                                 const std::vector<double>& direct, AnnualSeries& out) const {
    const AnnualSky& s = *annual_.sky;
    const std::size_t hours = s.hours().size();
    out.hours = hours;
    out.sensors = cells_;
    out.total_lx.assign(hours * cells_, 0.0);
    out.direct_lx.assign(hours * cells_, 0.0);
    // The hours are independent rows: spread over the cores (the same sums, in the same
    // order within each row, whatever the split).
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, hours, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<double> row(cells_);
        for (std::size_t h = r.begin(); h < r.end(); ++h) {
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
    });
}

void AnnualCoefficients::series(AnnualSeries& estimate, AnnualSeries& sigma) const {
    this->estimate(estimate);
    // Sum of w^2 k^2 q over the groups (the weights squared: lum^2 / yearly^2), minus E^2 / N.
    const AnnualSky& s = *annual_.sky;
    sigma.hours = estimate.hours;
    sigma.sensors = cells_;
    sigma.total_lx.assign(estimate.total_lx.size(), 0.0);
    sigma.direct_lx.assign(estimate.direct_lx.size(), 0.0);
    std::vector<double> row(cells_);
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
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const double e = e_h[cell];
            sig[cell] = (std::sqrt(std::max(0.0, row[cell] - e * e * inv_photons_)));
        }
    }
}

void AnnualCoefficients::estimate(AnnualSeries& out) const {
    if (!have_estimate_) {
        combine(sky_, sun_, direct_, estimate_);
        have_estimate_ = true;
    }
    out = estimate_;
}

void AnnualCoefficients::centre(AnnualSeries& out) const {
    // The sky and ground at their counts; a sun's direct and indirect counts at their pooled
    // means, the indirect pooled again as the estimate pools it.
    std::vector<double> indirect(sun_.size()), direct(direct_.size()), sun;
    for (std::size_t i = 0; i < sun_.size(); ++i) {
        indirect[i] = per_count_ * rep_indirect_mu_[i];
        direct[i] = per_count_ * rep_direct_mu_[i];
    }
    pool(indirect, direct, sun);
    combine(sky_, sun, direct, out);
}

void AnnualCoefficients::replicate(std::uint64_t seed, std::uint64_t replicate, AnnualSeries& out) const {
    // A fresh run's coefficients: each count redrawn as a Poisson count of its variance,
    // mu = var / k^2, around its centre, from (seed, replicate): a few-count sun hour is
    // mostly nothing and now and then a whole count, as a run's noise is, not a small normal
    // wobble that crosses a threshold every time. Large counts are drawn as normal (the same
    // to 1/sqrt(mu)).
    std::mt19937_64 rng(seed ^ (0x9E3779B97F4A7C15ull * (replicate + 1)));
    std::normal_distribution<double> normal;
    const double k = per_count_, k2 = k * k;
    auto draw = [&](double var) {  // zero-mean noise of variance var
        if (!(var > 0.0) || !(k2 > 0.0)) return 0.0;
        const double mu = var / k2;
        if (mu > 1000.0) return k * std::sqrt(mu) * normal(rng);
        return k * (static_cast<double>(std::poisson_distribution<std::int64_t>(mu)(rng)) - mu);
    };
    std::vector<double> sky(sky_);
    for (const std::size_t e : entries_)
        for (std::size_t cell = 0; cell < cells_; ++cell) {
            const std::size_t i = e * cells_ + cell;
            sky[i] += draw(sky_var_[i]);
        }
    // A sun: its direct count around its pooled mean, its indirect count too, then pooled
    // over the days as the estimate is.
    std::vector<double> indirect(sun_.size(), 0.0), direct(direct_.size(), 0.0), sun;
    for (std::size_t i = 0; i < sun_.size(); ++i) {
        const double mu_d = rep_direct_mu_[i], mu_i = rep_indirect_mu_[i], var_i = rep_indirect_var_[i];
        if (mu_d > 0.0) direct[i] = k * mu_d + draw(k2 * mu_d);
        if (mu_i != 0.0 || var_i > 0.0) indirect[i] = k * mu_i + draw(k2 * var_i);
    }
    pool(indirect, direct, sun);
    combine(sky, sun, direct, out);
}

}  // namespace luxtrace
