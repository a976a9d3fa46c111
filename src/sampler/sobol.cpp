#include "luxtrace/sampler/sobol.hpp"

#include <Random123/philox.h>
#include <boost/random/sobol.hpp>

#include <stdexcept>
#include <string>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define LUXTRACE_SOBOL_AVX2 1
#endif

namespace luxtrace {

namespace {

#ifdef LUXTRACE_SOBOL_AVX2
// scramble_reversed on eight lanes: the same multiplications and additions modulo 2^32,
// then the bits of each lane reversed: each byte's bits through a nibble table
// (vpshufb), then the byte order of each lane. The tables are bytes packed little-endian
// into 32-bit words, both 128-bit halves alike, as vpshufb looks up within each half.
__attribute__((target("avx2"), always_inline)) inline __m256i table(std::uint32_t w0, std::uint32_t w1,
                                                                    std::uint32_t w2, std::uint32_t w3) {
    return _mm256_setr_epi32(static_cast<int>(w0), static_cast<int>(w1), static_cast<int>(w2), static_cast<int>(w3),
                             static_cast<int>(w0), static_cast<int>(w1), static_cast<int>(w2), static_cast<int>(w3));
}

__attribute__((target("avx2"))) void scramble_x8(std::uint32_t* words, const std::uint32_t* seeds) {
    __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(words));
    const __m256i seed = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(seeds));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x3d20adea)));
    x = _mm256_add_epi32(x, seed);
    x = _mm256_mullo_epi32(x, _mm256_or_si256(_mm256_srli_epi32(seed, 16), _mm256_set1_epi32(1)));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x05526c56)));
    x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(0x53a22864)));
    // rev4[n]: the 4 bits of n reversed; the byte's reversal is rev4[low] << 4 | rev4[high].
    const __m256i rev_lo = table(0xc0408000u, 0xe060a020u, 0xd0509010u, 0xf070b030u);  // rev4[n] << 4
    const __m256i rev_hi = table(0x0c040800u, 0x0e060a02u, 0x0d050901u, 0x0f070b03u);  // rev4[n]
    const __m256i nibble = _mm256_set1_epi8(0x0f);
    const __m256i lo = _mm256_and_si256(x, nibble), hi = _mm256_and_si256(_mm256_srli_epi16(x, 4), nibble);
    x = _mm256_or_si256(_mm256_shuffle_epi8(rev_lo, lo), _mm256_shuffle_epi8(rev_hi, hi));
    const __m256i bswap = table(0x00010203u, 0x04050607u, 0x08090a0bu, 0x0c0d0e0fu);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(words), _mm256_shuffle_epi8(x, bswap));
}
#endif

}  // namespace

void SobolSequence::scramble_reversed(std::uint32_t* words, const std::uint32_t* seeds, std::size_t n) {
    std::size_t i = 0;
#ifdef LUXTRACE_SOBOL_AVX2
    if (__builtin_cpu_supports("avx2"))
        for (; i + 8 <= n; i += 8) scramble_x8(words + i, seeds + i);
#endif
    for (; i < n; ++i) words[i] = scramble_reversed(words[i], seeds[i]);
}

SobolSequence::SobolSequence(std::uint32_t dimensions) {
    if (dimensions < 1 || dimensions > kMaxDimensions)
        throw std::invalid_argument("Sobol sequence: " + std::to_string(dimensions) + " dimensions (1 to " +
                                    std::to_string(kMaxDimensions) + ")");
    // Boost's engine yields the points in Gray-code order: after seed(n) its next point is
    // x(g(n + 1)), g(m) = m ^ (m >> 1). The direction number v_j of every dimension is the
    // point x(2^j), and g(2^(j+1) - 1) = 2^j, so it follows seed(2^(j+1) - 2).
    directions_.assign(static_cast<std::size_t>(dimensions) * 32u, 0u);
    boost::random::sobol_engine<std::uint32_t, 32> engine(dimensions);
    for (std::uint32_t j = 0; j < 32; ++j) {
        engine.seed(static_cast<std::uint32_t>((std::uint64_t{2} << j) - 2u));
        for (std::uint32_t d = 0; d < dimensions; ++d) directions_[static_cast<std::size_t>(d) * 32u + j] = engine();
    }
}

std::uint32_t SobolSequence::scramble_seed(std::uint64_t run_seed, std::uint32_t stream, std::uint32_t dim) {
    const r123::Philox4x32::ctr_type ctr = {{stream, dim, 0x736f626cu /* "sobl" */, 0u}};
    const r123::Philox4x32::key_type key = {
        {static_cast<std::uint32_t>(run_seed), static_cast<std::uint32_t>(run_seed >> 32)}};
    return r123::Philox4x32()(ctr, key).v[0];
}

}  // namespace luxtrace
