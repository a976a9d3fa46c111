#pragma once
// The random numbers of photon k, in the blocks of the photon layout (tracer.hpp), from
// either sampler:
//   random - Philox4x32-10 blocks (sampler.hpp);
//   sobol  - Owen-scrambled Sobol points (sobol.hpp). Photon k belongs to stream
//            r = k mod R and is point i = k / R of that stream; each stream is its own
//            independent scramble of the sequence, so the R streams are R independent
//            randomisations (replicates) interleaved by photon index. R is even, so odd
//            photons (the odd map, SPEC §3) come from the odd streams only and even photons
//            from the even ones: the two half-maps are independent randomisations, never
//            alternate points of one sequence. Dimensions in the order of the photon's
//            decisions: 0 light, 1 band, 2-3 emission position, 4-5 emission direction,
//            then 6 + 3b .. 8 + 3b event and direction at arrival b, for the first
//            kSobolBounces arrivals; arrivals after those draw Philox blocks (padding),
//            independent of everything else.
// Either way a photon's numbers depend only on (seed, k): tallies are bit-identical for
// any ranks x threads, and a restart continues the same streams.
#include "luxtrace/sampler/sampler.hpp"
#include "luxtrace/sampler/sobol.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

enum class SamplerKind { random, sobol };

class PhotonSampler {
public:
    using Block = PhiloxSampler::Block;
    static constexpr std::uint32_t kSobolBounces = 64;
    static constexpr std::uint32_t kSobolDimensions = 6 + 3 * kSobolBounces;
    static constexpr std::uint32_t kDefaultReplicates = 8;

    // `replicates` (R) matters for sobol only: even, 2 .. 1024.
    PhotonSampler(SamplerKind kind, std::uint64_t seed, std::uint32_t replicates = kDefaultReplicates);

    SamplerKind kind() const { return kind_; }
    std::uint32_t replicates() const { return replicates_; }
    // sobol: the stream (replicate) of photon k, k mod R, and its point in the stream,
    // k / R (R a power of two, as the default 8: a mask and a shift, not a division).
    std::uint64_t stream_of(std::uint64_t k) const {
        return replicate_shift_ >= 0 ? k & (replicates_ - 1) : k % replicates_;
    }
    std::uint64_t index_in_stream(std::uint64_t k) const {
        return replicate_shift_ >= 0 ? k >> replicate_shift_ : k / replicates_;
    }
    // out[i] = the words of block b[i] of photon k[i], for i < n <= PhiloxSampler::kBatch.
    // Not const: sobol keeps the last point of each dimension to step from (one sampler
    // per tracing thread).
    void blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out) {
        if (kind_ == SamplerKind::random) {
            philox_.blocks(k, b, n, out);
        } else {
            sobol_blocks(k, b, n, out);
        }
    }
    Block block(std::uint64_t k, std::uint32_t b) {
        if (kind_ == SamplerKind::random) return philox_.block(k, b);
        Block out;
        sobol_blocks(&k, &b, 1, &out);
        return out;
    }

private:
    void sobol_blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out);
    Block far_block(std::uint64_t stream, std::uint64_t index, std::uint32_t b);
    // Scrambled point `index` of dimension d with scramble s. The Sobol points are linear
    // in the bits of the index over GF(2), x(i) = x(j) ^ x(i ^ j), so the point is stepped
    // from the last one asked for in that dimension: photons in flight are close in index,
    // and i ^ j has a bit or two where i has a dozen.
    // Returns the point bit-reversed, unscrambled.
    std::uint32_t reversed_point(std::uint32_t index, std::uint32_t d) {
        Last& last = last_[d];
        const std::uint32_t* v = &reversed_directions_[static_cast<std::size_t>(d) * 32u];
        std::uint32_t r = last.reversed;
        for (std::uint32_t diff = index ^ last.index; diff != 0; diff &= diff - 1) r ^= v[__builtin_ctz(diff)];
        last = {index, r};
        return r;
    }
    struct Last {
        std::uint32_t index = 0, reversed = 0;  // x(0) = 0
    };

    SamplerKind kind_;
    std::uint64_t seed_;
    std::uint32_t replicates_;
    int replicate_shift_ = -1;  // log2(R) when R is a power of two
    PhiloxSampler philox_;
    std::vector<std::uint32_t> reversed_directions_;  // [dim * 32 + j]: v_j bit-reversed
    std::vector<std::uint32_t> scrambles_;            // [stream * kSobolDimensions + dim]
    std::vector<Last> last_;                          // [dim]
};

// Samplers by the name used in the scene file and on the command line: "random" or
// "sobol"; throws InputError with sampler_unavailable's message otherwise.
SamplerKind sampler_kind(const std::string& name);
// Empty if `name` is a sampler, otherwise what to tell the user ("unknown sampler
// 'halton' (this build has: random, sobol)"). The loader and the CLI check with it.
std::string sampler_unavailable(const std::string& name);
// Empty if `replicates` is a valid R for sobol (even, 2 .. 1024), otherwise why not. The
// loader, the CLI and PhotonSampler check with it.
std::string replicates_invalid(std::int64_t replicates);

}  // namespace luxtrace
