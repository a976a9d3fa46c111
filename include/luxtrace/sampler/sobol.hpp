#pragma once
// Owen-scrambled Sobol points (issue 11): the Sobol sequence with the Joe-Kuo direction
// numbers of Boost.Random (S. Joe and F. Y. Kuo, SIAM J. Sci. Comput. 30, 2635-2654,
// 2008; Boost has 3,667 dimensions), randomised by hash-based nested uniform scrambling
// (B. Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020: a Laine-Karras
// style permutation applied to the bit-reversed value). Every output bit is flipped by a
// function of the bits above it only, so a scrambled sequence keeps the stratification of
// the original: the first 2^m points of one dimension fall one into each interval of
// length 2^-m, and a 2-D projection keeps its t-value. Different seeds give independent
// randomisations, and each point is uniform on [0, 1): the estimates stay unbiased and
// independent scrambles give honest error bars (replicates).
//
// Points are addressed by index, not generated in sequence: photon tracing asks for
// point i of dimension d of scramble s in any order, on any thread.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace luxtrace {

class SobolSequence {
public:
    // The first `dimensions` dimensions (1 .. kMaxDimensions).
    explicit SobolSequence(std::uint32_t dimensions);
    static constexpr std::uint32_t kMaxDimensions = 3667;  // Boost.Random's table

    // Point `index` of dimension `dim`, unscrambled, as 32 bits (value = bits / 2^32).
    std::uint32_t point(std::uint32_t index, std::uint32_t dim) const {
        const std::uint32_t* v = &directions_[static_cast<std::size_t>(dim) * 32u];
        std::uint32_t x = 0;
        for (; index != 0; index &= index - 1) x ^= v[__builtin_ctz(index)];
        return x;
    }
    // The same, scrambled with the 32-bit seed `scramble`.
    std::uint32_t scrambled(std::uint32_t index, std::uint32_t dim, std::uint32_t scramble) const {
        return owen_scramble(point(index, dim), scramble);
    }

    // The scramble of dimension `dim` of randomisation `stream` of a run: a Philox4x32-10
    // word with the run seed as key and counter (stream, dim, "sobl", 0), so every
    // (stream, dimension) has its own independent scramble and none shares a counter with
    // the photons' Philox blocks (tag "luxt", philox_sampler.hpp).
    static std::uint32_t scramble_seed(std::uint64_t run_seed, std::uint32_t stream, std::uint32_t dim);

    // Nested uniform scrambling of a 32-bit fraction (Burley 2020, eq. for the
    // Laine-Karras permutation with his improved constants, on the reversed bits).
    static std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
        return scramble_reversed(reverse_bits(x), seed);
    }
    // The same from the bit-reversed point (a caller that keeps its points reversed
    // saves one reversal).
    static std::uint32_t scramble_reversed(std::uint32_t r, std::uint32_t seed) {
        r ^= r * 0x3d20adeau;
        r += seed;
        r *= (seed >> 16) | 1u;
        r ^= r * 0x05526c56u;
        r ^= r * 0x53a22864u;
        return reverse_bits(r);
    }
    // scramble_reversed on n words at once: words[i] = scramble_reversed(words[i], seeds[i]);
    // eight AVX2 lanes at a time where the CPU has them.
    static void scramble_reversed(std::uint32_t* words, const std::uint32_t* seeds, std::size_t n);
    static std::uint32_t reverse_bits(std::uint32_t x) {
        x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
        x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
        x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
        return __builtin_bswap32(x);
    }

private:
    std::vector<std::uint32_t> directions_;  // 32 per dimension: v_j = x(2^j)
};

}  // namespace luxtrace
