#pragma once
// A stream of random 32-bit words as a pure function of (seed, stream): Philox4x32-10
// (Random123), counter = (stream, block, "bits"), key = seed, four words a block. A
// UniformRandomBitGenerator, for the standard library's distributions where a draw must
// not depend on which thread or block made it (the annual replicates: one stream per
// replicate and sensor). Header only.
#include <Random123/philox.h>

#include <cstdint>
#include <limits>

namespace luxtrace {

class PhiloxBits {
public:
    using result_type = std::uint32_t;
    // The counter's fourth word: "bits" (the tracer's streams have "luxt").
    static constexpr std::uint32_t kCounterTag = 0x62697473u;

    PhiloxBits(std::uint64_t seed, std::uint64_t stream)
        : key_{{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}}, stream_(stream) {}

    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

    result_type operator()() {
        if (word_ == 4) {
            const r123::Philox4x32::ctr_type ctr = {{static_cast<std::uint32_t>(stream_),
                                                     static_cast<std::uint32_t>(stream_ >> 32), block_++, kCounterTag}};
            words_ = r123::Philox4x32()(ctr, key_);
            word_ = 0;
        }
        return words_.v[word_++];
    }

private:
    r123::Philox4x32::key_type key_;
    std::uint64_t stream_;
    std::uint32_t block_ = 0;
    unsigned word_ = 4;
    r123::Philox4x32::ctr_type words_{};
};

}  // namespace luxtrace
