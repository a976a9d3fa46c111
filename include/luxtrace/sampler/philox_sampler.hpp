#pragma once
// Random numbers for photon k as a pure function of (seed, k, block): Philox4x32-10
// (Salmon et al., SC'11, via Random123), counter = (k, block, "luxt"), key = seed. Each
// block is four 32-bit words. The tracer draws one block per decision group (the photon
// layout in tracer.hpp), so tallies do not depend on which rank or thread traced a
// photon, and no call per number is made on the tracing path.
#include <Random123/philox.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace luxtrace {

class PhiloxSampler {
public:
    using Block = std::array<std::uint32_t, 4>;
    // Blocks computed together by `blocks` (one AVX2 lane each).
    static constexpr std::size_t kBatch = 8;
    // The counter's fourth word: "luxt".
    static constexpr std::uint32_t kCounterTag = 0x6c757874u;

    explicit PhiloxSampler(std::uint64_t seed);

    // The four words of block `b` of photon `k`.
    Block block(std::uint64_t k, std::uint32_t b) const {
        const r123::Philox4x32::ctr_type ctr = {
            {static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(k >> 32), b, kCounterTag}};
        const r123::Philox4x32::key_type key = {
            {static_cast<std::uint32_t>(seed_), static_cast<std::uint32_t>(seed_ >> 32)}};
        const auto out = r123::Philox4x32()(ctr, key);
        return {out.v[0], out.v[1], out.v[2], out.v[3]};
    }
    // out[i] = block(k[i], b[i]) for i < n <= kBatch, the same words, computed eight
    // lanes at a time where the CPU has AVX2 (the tracer's photons in flight ask
    // together), one by one otherwise.
    void blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out) const;
    // Whether `blocks` uses the AVX2 lanes on this CPU.
    bool vectorised() const { return avx2_; }
    // 32 random bits, centred in their interval: strictly inside (0, 1).
    static double uniform(std::uint32_t w) { return (static_cast<double>(w) + 0.5) * 0x1p-32; }

    // Sequential use (tests, probes): dimension d is word d % 4 of block d / 4.
    void start_photon(std::uint64_t k) {
        photon_ = k;
        dim_ = 0;
        block_ = UINT32_MAX;
    }
    void set_dimension(std::uint32_t d) { dim_ = d; }
    double next() {
        if (dim_ / 4u != block_) {
            block_ = dim_ / 4u;
            words_ = block(photon_, block_);
        }
        return uniform(words_[dim_++ % 4u]);
    }

private:
    std::uint64_t seed_;
    bool avx2_ = false;
    std::uint64_t photon_ = 0;
    std::uint32_t dim_ = 0;
    std::uint32_t block_ = UINT32_MAX;
    std::array<std::uint32_t, 4> words_{};
};

}  // namespace luxtrace
