#pragma once
// The random numbers of photon k, in the blocks of the photon layout (tracer.hpp), from
// either sampler:
//   random - Philox4x32-10 blocks (philox_sampler.hpp);
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
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/sampler/sobol.hpp"

#include <array>
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
    static constexpr std::uint32_t kSobolBlocks = 2 + kSobolBounces;
    // The dimensions of block b's four words (kNoDimension: the word is unused, 0).
    static constexpr std::uint32_t kNoDimension = UINT32_MAX;
    static std::array<std::uint32_t, 4> block_dimensions(std::uint32_t b) {
        if (b == 0) return {0, 1, 4, 5};
        if (b == 1) return {2, 3, kNoDimension, kNoDimension};
        const std::uint32_t d = 6 + 3 * (b - 2);
        return {d, d + 1, d + 2, kNoDimension};
    }

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
    // Not const: sobol keeps the last point of each block to step from (one sampler per
    // tracing thread).
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
    // The words of a block are the dimensions of block_dimensions, 0 where unused. Each block
    // keeps the bit-reversed, unscrambled words of the last point asked for. The Sobol
    // points are linear in the bits of the index over GF(2), x(i) = x(j) ^ x(i ^ j), so a
    // new point is stepped from it, four words at a time: photons in flight are close in
    // index (the R photons of a round share theirs), and i ^ j has a bit or two where i has
    // a dozen.
    struct Cached {
        std::uint32_t index = 0;
        Block reversed{};  // x(0) = 0
    };
    const Block& reversed_block(std::uint32_t index, std::uint32_t b) {
        Cached& c = cached_[b];
        if (c.index != index) {
            const Block* v = &reversed_directions_[static_cast<std::size_t>(b) * 32u];
            for (std::uint32_t diff = index ^ c.index; diff != 0; diff &= diff - 1) {
                const Block& vj = v[__builtin_ctz(diff)];
                for (int w = 0; w < 4; ++w) c.reversed[w] ^= vj[w];
            }
            c.index = index;
        }
        return c.reversed;
    }

    SamplerKind kind_;
    std::uint64_t seed_;
    std::uint32_t replicates_;
    int replicate_shift_ = -1;  // log2(R) when R is a power of two
    PhiloxSampler philox_;
    std::vector<Block> reversed_directions_;  // [block * 32 + j]: v_j of the block's dimensions, bit-reversed
    std::vector<Block> scrambles_;            // [stream * kSobolBlocks + block]: their scramble seeds, 0 where unused
    std::vector<Cached> cached_;              // [block]
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
