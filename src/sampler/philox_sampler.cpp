#include "luxtrace/sampler/philox_sampler.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define LUXTRACE_PHILOX_AVX2 1
#endif

namespace luxtrace {

namespace {

#ifdef LUXTRACE_PHILOX_AVX2
// Philox4x32-10 (Salmon et al., SC'11, as Random123 defines it) on eight counters at
// once, word j of counter i in lane i of c[j]; the key is the same for every lane.
// A round: (lo0, hi0) = M0 * c0, (lo1, hi1) = M1 * c2, c = (hi1^c1^k0, lo1, hi0^c3^k1, lo0);
// the key is bumped by the Weyl constants before rounds 2-10. _mm256_mul_epu32 multiplies
// the even 32-bit lanes into 64-bit products, so the odd lanes go through a shifted copy.
__attribute__((target("avx2"), always_inline)) inline void mulhilo(__m256i a, __m256i m, __m256i& lo, __m256i& hi) {
    const __m256i even = _mm256_mul_epu32(a, m);
    const __m256i odd = _mm256_mul_epu32(_mm256_srli_epi64(a, 32), m);
    lo = _mm256_blend_epi32(even, _mm256_slli_epi64(odd, 32), 0xAA);
    hi = _mm256_blend_epi32(_mm256_srli_epi64(even, 32), odd, 0xAA);
}

__attribute__((target("avx2"))) void philox_x8(const std::uint32_t (&in)[4][PhiloxSampler::kBatch], std::uint32_t key0,
                                               std::uint32_t key1, std::uint32_t (&out)[4][PhiloxSampler::kBatch]) {
    __m256i c0 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in[0]));
    __m256i c1 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in[1]));
    __m256i c2 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in[2]));
    __m256i c3 = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in[3]));
    const __m256i m0 = _mm256_set1_epi64x(0xD2511F53);
    const __m256i m1 = _mm256_set1_epi64x(0xCD9E8D57);
    for (int round = 0; round < 10; ++round) {
        if (round > 0) {
            key0 += 0x9E3779B9u;
            key1 += 0xBB67AE85u;
        }
        __m256i lo0, hi0, lo1, hi1;
        mulhilo(c0, m0, lo0, hi0);
        mulhilo(c2, m1, lo1, hi1);
        const __m256i n0 = _mm256_xor_si256(_mm256_xor_si256(hi1, c1), _mm256_set1_epi32(static_cast<int>(key0)));
        const __m256i n2 = _mm256_xor_si256(_mm256_xor_si256(hi0, c3), _mm256_set1_epi32(static_cast<int>(key1)));
        c0 = n0;
        c1 = lo1;
        c2 = n2;
        c3 = lo0;
    }
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out[0]), c0);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out[1]), c1);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out[2]), c2);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out[3]), c3);
}
#endif

}  // namespace

PhiloxSampler::PhiloxSampler(std::uint64_t seed) : seed_(seed) {
#ifdef LUXTRACE_PHILOX_AVX2
    avx2_ = __builtin_cpu_supports("avx2") != 0;
#endif
}

void PhiloxSampler::blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out) const {
#ifdef LUXTRACE_PHILOX_AVX2
    if (avx2_ && n > 1) {
        std::uint32_t in[4][kBatch] = {}, res[4][kBatch];
        for (std::size_t i = 0; i < n; ++i) {
            in[0][i] = static_cast<std::uint32_t>(k[i]);
            in[1][i] = static_cast<std::uint32_t>(k[i] >> 32);
            in[2][i] = b[i];
            in[3][i] = kCounterTag;
        }
        philox_x8(in, static_cast<std::uint32_t>(seed_), static_cast<std::uint32_t>(seed_ >> 32), res);
        for (std::size_t i = 0; i < n; ++i) out[i] = {res[0][i], res[1][i], res[2][i], res[3][i]};
        return;
    }
#endif
    for (std::size_t i = 0; i < n; ++i) out[i] = block(k[i], b[i]);
}

}  // namespace luxtrace
