#include "luxtrace/stats/global_sums.hpp"

#include "side_terms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxtrace {

using namespace side_terms;

void GlobalSums::add(const GlobalSums& o) {
    area_m2 += o.area_m2;
    d2 += o.d2;
    e += o.e;
    e2 += o.e2;
    var += o.var;
    rep_var += o.rep_var;
    lit_sides += o.lit_sides;
}

void GlobalSums::to_words(double* out) const {
    const double w[kWords] = {area_m2, d2, e, e2, var, rep_var, lit_sides};
    std::copy(w, w + kWords, out);
}

GlobalSums GlobalSums::from_words(const double* in) { return {in[0], in[1], in[2], in[3], in[4], in[5], in[6]}; }

GlobalSums global_sums(const WeightedTallies& w, std::span<const double> area, double e0, std::uint64_t photons,
                       std::size_t side_begin, std::size_t side_end, std::span<const std::uint64_t> lit) {
    // Eqs. (4)-(5) on the band-summed map of the lit sides: E_odd,t = 2 n_odd E0 / A_t,
    // likewise even; and each side's variance from its second moment or its replicates.
    const TallyLayout& L = w.layout();
    const double n_photons = static_cast<double>(photons);
    const std::vector<std::uint64_t> rep_photons = replicate_photons(w);
    std::vector<double> sums(L.replicates());
    GlobalSums g;
    for (std::size_t i = side_begin; i < side_end; ++i) {
        if (!lit.empty() && ((lit[i / 64] >> (i % 64)) & 1u) == 0) {
            // Step over the rest of an empty mask word at once.
            if (lit[i / 64] >> (i % 64) == 0) i = std::min(side_end, (i / 64 + 1) * 64) - 1;
            continue;
        }
        const double odd = side_sum(w, i, TallyLayout::kCountOdd);
        const double even = side_sum(w, i, TallyLayout::kCountEven);
        if (odd + even == 0.0) continue;
        const double a = area[L.triangle_of(i)];
        const double k = e0 / a;
        const double e_odd = 2.0 * odd * k;
        const double e_even = 2.0 * even * k;
        const double e = (odd + even) * k;
        g.area_m2 += a;
        g.lit_sides += 1.0;
        g.d2 += a * (e_odd - e_even) * (e_odd - e_even);
        g.e += a * e;
        g.e2 += a * e * e;
        if (photons > 0) {
            const double sigma = side_sigma_counts(odd + even, side_sumsq(w, i), n_photons) * k;
            g.var += a * sigma * sigma;
            if (L.replicates() > 0) {
                const double rs = side_replicate_sigma_counts(w, i, sums, rep_photons, n_photons) * k;
                g.rep_var += a * rs * rs;
            }
        }
    }
    return g;
}

std::vector<GlobalSums> chunk_sums(const WeightedTallies& w, std::span<const double> area, double e0,
                                   std::uint64_t photons, ChunkRange chunks, std::span<const std::uint64_t> lit) {
    std::vector<GlobalSums> out;
    out.reserve(chunks.size());
    for (std::size_t c = chunks.begin; c < chunks.end; ++c) {
        const auto [begin, end] = chunk_sides(w.layout(), c);
        out.push_back(global_sums(w, area, e0, photons, begin, end, lit));
    }
    return out;
}

GlobalEstimate global_estimate(std::span<const GlobalSums> chunks, bool replicates) {
    GlobalSums t;
    for (const GlobalSums& c : chunks) t.add(c);
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    GlobalEstimate g;
    g.primary = replicates ? GlobalEstimate::Estimator::replicate_spread : GlobalEstimate::Estimator::second_moment;
    g.lit_area_m2 = t.area_m2;
    g.lit_sides = static_cast<std::uint64_t>(t.lit_sides);
    const double s = t.area_m2;
    if (s <= 0.0) return g;
    g.odd_even_rms_lx = std::sqrt(t.d2 / s);
    g.sigma_lx = 0.5 * g.odd_even_rms_lx;
    g.moment_sigma_lx = std::sqrt(t.var / s);
    g.replicate_sigma_lx = replicates ? std::sqrt(t.rep_var / s) : kNaN;
    g.mean_arithmetic_lx = t.e / s;
    g.mean_quadratic_lx = std::sqrt(t.e2 / s);
    auto rel = [&](double sigma, double mean) { return mean > 0.0 ? sigma / mean : kNaN; };
    g.sigma_rel_arithmetic = rel(g.sigma_lx, g.mean_arithmetic_lx);
    g.sigma_rel_quadratic = rel(g.sigma_lx, g.mean_quadratic_lx);
    g.moment_sigma_rel_arithmetic = rel(g.moment_sigma_lx, g.mean_arithmetic_lx);
    g.moment_sigma_rel_quadratic = rel(g.moment_sigma_lx, g.mean_quadratic_lx);
    g.replicate_sigma_rel_arithmetic = rel(g.replicate_sigma_lx, g.mean_arithmetic_lx);
    g.replicate_sigma_rel_quadratic = rel(g.replicate_sigma_lx, g.mean_quadratic_lx);
    return g;
}

}  // namespace luxtrace
