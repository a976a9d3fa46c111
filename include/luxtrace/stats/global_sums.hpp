#pragma once
// The global estimate (estimates.hpp, eqs. 4-5 and the second moment) as partial sums
// over chunks of sides (message_packing.hpp), so that each rank of a distributed reduction sums the sides it
// owns and only the chunks' sums travel to rank 0 (docs/RUN_CONTROL.md). The chunks are
// fixed by the layout, not by the rank count, and rank 0 adds them in
// chunk order: the estimate has the same bits on any number of ranks, and the same as
// estimate_global on the whole map.
#include "luxtrace/stats/estimates.hpp"
#include "luxtrace/stats/weighted_tallies.hpp"
#include "luxtrace/tally/message_packing.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

// Area-weighted sums over the lit sides of a run of sides (A_t the side's area, E_t its
// band-summed illuminance, E_odd/even,t its half-maps', sigma_t its standard error).
struct GlobalSums {
    double area_m2 = 0.0;  // sum A_t
    double d2 = 0.0;       // sum A_t (E_odd,t - E_even,t)^2, eq. (5)
    double e = 0.0;        // sum A_t E_t, eq. (4)
    double e2 = 0.0;       // sum A_t E_t^2
    double var = 0.0;      // sum A_t sigma_t^2, second moment
    double rep_var = 0.0;  // sum A_t sigma_t^2, replicate spread (sobol)
    double lit_sides = 0.0;
    static constexpr std::size_t kWords = 7;
    void add(const GlobalSums& o);
    void to_words(double* out) const;
    static GlobalSums from_words(const double* in);
};

// The sums of sides [side_begin, side_end); E0 = flux per photon (lm), photons = N. With
// `lit` (one bit per side, message_packing.hpp's mask), only the sides marked are read:
// the others must have no counts (the sums are the same, a closed model's backs are skipped).
GlobalSums global_sums(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                       std::uint64_t photons, std::size_t side_begin, std::size_t side_end,
                       std::span<const std::uint64_t> lit = {});
// One GlobalSums per chunk of sides (message_packing.hpp's chunks), in chunk order.
std::vector<GlobalSums> chunk_sums(const WeightedTallies& tallies, std::span<const double> area_m2, double e0,
                                   std::uint64_t photons, ChunkRange chunks, std::span<const std::uint64_t> lit = {});
// The estimate from every chunk's sums, added in chunk order; `replicates`: the layout
// has replicate maps (sobol), whose spread is then the primary estimate.
GlobalEstimate global_estimate(std::span<const GlobalSums> chunks, bool replicates);

}  // namespace luxtrace
