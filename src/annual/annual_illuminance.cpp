#include "luxtrace/annual/annual_illuminance.hpp"

#include <algorithm>
#include <cmath>
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
    // A cell that no photon of an emitting group reached is not exact: its expected count
    // lambda is small but not zero, and its variance is k^2 lambda. The sky patches and the
    // ground: lambda from the cell's indirect registrations pooled over all of them, shared
    // out by the groups' fluxes (which decide their photons), lambda = (I_c + 1/2) Phi_g /
    // Phi_sky, the 1/2 Jeffreys' prior for a Poisson count seen as 0. A sun: from the same
    // cell's registrations of the suns of the same hour on the day before and after (their
    // positions within half a degree: the same shadows), lambda = n_c' Phi_s / Phi', for the
    // total and for the direct count alike; where those read 0 too, the mean over all such
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
                sky_var_[i] = n > 0.0 ? std::max(0.0, k2 * (qq - n * n * inv_photons_)) : sky_q_[i];
            }
        }
    }
    sun_.assign(suns * cells, 0.0);
    sun_q_ = sun_var_ = direct_ = direct_var_ = sun_;
    std::vector<int> sun_at_hour(sky.hours().size(), -1);
    for (std::size_t s = 0; s < suns; ++s) sun_at_hour[sky.suns()[s]] = static_cast<int>(s);
    // Per sun: the emitting suns of the same hour on the day before and after, and the share
    // of their photons this sun has.
    std::vector<std::vector<std::size_t>> near(suns);
    std::vector<double> share(suns, 0.0);
    for (std::size_t s = 0; s < suns; ++s) {
        if (!(flux(sun_groups[s]) > 0.0)) continue;
        const std::size_t h = sky.suns()[s];
        double near_flux = 0.0;
        for (const std::size_t other : {h - 24, h + 24})  // h - 24 wraps past the end when h < 24
            if (other < sun_at_hour.size() && sun_at_hour[other] >= 0) {
                const std::size_t o = sun_groups[static_cast<std::size_t>(sun_at_hour[other])];
                if (flux(o) > 0.0) {
                    near[s].push_back(o);
                    near_flux += flux(o);
                }
            }
        share[s] = near_flux > 0.0 ? flux(sun_groups[s]) / near_flux : 0.0;
    }
    auto near_sum = [&](std::size_t s, std::size_t cell, bool direct) {
        double m = 0.0;
        for (std::size_t o : near[s]) m += direct ? direct_of(cell, o) : n_of(cell, o);
        return m;
    };
    // Where the neighbours read nothing either (a shadow, or light too rare to show), the
    // expected count is the mean count of all such (sun, cell) pairs of the detector, with
    // half a count of prior: most are true shadows, and their few counts say how rare.
    // The rate per unit of photon share, as a ratio of sums (a mean of ratios would weigh
    // a weak sun's rare count by its tiny share).
    double dark_n = 0.5, dark_d = 0.5, dark_share = 0.0, dark_share_d = 0.0;
    for (std::size_t s = 0; s < suns; ++s) {
        if (!(flux(sun_groups[s]) > 0.0) || near[s].empty()) continue;
        const double weight = share[s] * static_cast<double>(near[s].size());
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
    for (std::size_t s = 0; s < suns; ++s) {
        const std::size_t g = sun_groups[s];
        if (!(flux(g) > 0.0)) continue;
        for (std::size_t cell = 0; cell < cells; ++cell) {
            const double n = n_of(cell, g), qq = static_cast<double>(data[layout.detector_q(det, cell, 0, g)]);
            // A photon's direct count in a cell is 0 or 1: its square is itself (tally.hpp).
            const double d = direct_of(cell, g);
            // The expected count of an unreached cell: the neighbours' counts times this
            // sun's share of their photons, or the detector's dark mean.
            auto lambda = [&](bool direct) {
                if (near[s].empty()) return 0.5;
                const double m = near_sum(s, cell, direct);
                const double dark = direct ? dark_lambda_d : dark_lambda_n;
                return (m > 0.0 ? m : dark * static_cast<double>(near[s].size())) * share[s];
            };
            const std::size_t i = s * cells + cell;
            sun_[i] = per_count * n;
            sun_q_[i] = n > 0.0 ? k2 * qq : k2 * lambda(false);
            sun_var_[i] = n > 0.0 ? std::max(0.0, k2 * (qq - n * n * inv_photons_)) : sun_q_[i];
            direct_[i] = per_count * d;
            direct_var_[i] = d > 0.0 ? std::max(0.0, k2 * (d - d * d * inv_photons_)) : k2 * lambda(true);
        }
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
    replicate(0.0, 0, 0, estimate);  // the estimate, kept for the replicates
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

void AnnualCoefficients::replicate(double noise_scale, std::uint64_t seed, std::uint64_t replicate,
                                   AnnualSeries& out) const {
    if (!have_estimate_) {
        combine(sky_, sun_, direct_, estimate_);
        have_estimate_ = true;
    }
    if (noise_scale == 0.0) {
        out = estimate_;
        return;
    }
    if (replicate != noise_replicate_ || seed != noise_seed_) {
        // The noise: each coefficient's count redrawn as a Poisson count of its own
        // variance, mu = var / k^2 (the count itself, or an unreached cell's expected count),
        // from (seed, replicate): a few-count sun hour is mostly nothing and now and then a
        // whole count, as a run's noise is, not a small normal wobble that crosses a
        // threshold every time. Large counts are drawn as normal (the same to 1/sqrt(mu)).
        std::mt19937_64 rng(seed ^ (0x9E3779B97F4A7C15ull * (replicate + 1)));
        std::normal_distribution<double> normal;
        const double k = per_count_, k2 = k * k;
        auto draw = [&](double var) {
            if (!(var > 0.0) || !(k2 > 0.0)) return 0.0;
            const double mu = var / k2;
            if (mu > 1000.0) return k * std::sqrt(mu) * normal(rng);
            return k * (static_cast<double>(std::poisson_distribution<std::int64_t>(mu)(rng)) - mu);
        };
        std::vector<double> sky(sky_.size(), 0.0);
        for (const std::size_t e : entries_)
            for (std::size_t cell = 0; cell < cells_; ++cell) {
                const std::size_t i = e * cells_ + cell;
                sky[i] = draw(sky_var_[i]);
            }
        // The direct registrations are part of the sun's: their noise is shared, the rest of
        // the sun's variance gets its own.
        std::vector<double> sun(sun_.size(), 0.0), direct(direct_.size(), 0.0);
        for (std::size_t i = 0; i < sun_.size(); ++i) {
            if (!(sun_var_[i] > 0.0)) continue;
            direct[i] = draw(direct_var_[i]);
            sun[i] = direct[i] + draw(std::max(0.0, sun_var_[i] - direct_var_[i]));
        }
        combine(sky, sun, direct, noise_);
        noise_replicate_ = replicate;
        noise_seed_ = seed;
    }
    out.hours = estimate_.hours;
    out.sensors = estimate_.sensors;
    out.total_lx.resize(estimate_.total_lx.size());
    out.direct_lx.resize(estimate_.direct_lx.size());
    for (std::size_t i = 0; i < out.total_lx.size(); ++i) {
        out.total_lx[i] = estimate_.total_lx[i] + noise_scale * noise_.total_lx[i];
        out.direct_lx[i] = estimate_.direct_lx[i] + noise_scale * noise_.direct_lx[i];
    }
}

}  // namespace luxtrace
