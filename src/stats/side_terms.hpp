#pragma once
// The per-side terms the surface map's estimates share (estimates.cpp, global_sums.cpp):
// band sums of a side's slots and its standard error in counts.
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/stats/weighted_tallies.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace::side_terms {

// Band sums of one side's slot.
inline double side_sum(const WeightedTallies& w, std::size_t i, TallyLayout::SurfaceSlot slot) {
    double n = 0.0;
    for (std::size_t b = 0; b < w.layout().bands(); ++b) n += w.side(i, b, slot);
    return n;
}
inline double side_count(const WeightedTallies& w, std::size_t i) {
    return side_sum(w, i, TallyLayout::kCountOdd) + side_sum(w, i, TallyLayout::kCountEven);
}
inline double side_sumsq(const WeightedTallies& w, std::size_t i) {
    double q = 0.0;
    for (std::size_t b = 0; b < w.layout().bands(); ++b) q += w.side_sumsq(i, b);
    return q;
}

// sqrt(Q - S^2 / N) of one side in counts, from its arrivals S and second moment Q.
inline double side_sigma_counts(double s, double q, double n) { return std::sqrt(std::max(0.0, q - s * s / n)); }

// sobol: the standard error of side i's band-summed count from its R replicate maps, in
// counts (the count's own scale: N times the per-photon mean's error).
inline double side_replicate_sigma_counts(const WeightedTallies& w, std::size_t i, std::vector<double>& sums,
                                          std::span<const std::uint64_t> rep_photons, double n) {
    const TallyLayout& L = w.layout();
    for (std::size_t r = 0; r < L.replicates(); ++r) {
        sums[r] = 0.0;
        for (std::size_t b = 0; b < L.bands(); ++b) sums[r] += w.side_replicate(i, b, r);
    }
    return replicate_estimate(sums, rep_photons).sigma * n;
}

inline std::vector<std::uint64_t> replicate_photons(const WeightedTallies& w) {
    std::vector<std::uint64_t> photons(w.layout().replicates());
    for (std::size_t r = 0; r < photons.size(); ++r) photons[r] = w.replicate_photons(r);
    return photons;
}

}  // namespace luxtrace::side_terms
