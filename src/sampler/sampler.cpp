#include "luxtrace/sampler/sampler.hpp"

#include "luxtrace/core/error.hpp"

#include <Random123/philox.h>

namespace luxtrace {

PhiloxSampler::PhiloxSampler(std::uint64_t seed) : seed_(seed) {}

void PhiloxSampler::start_photon(std::uint64_t k) {
    photon_ = k;
    dim_ = 0;
    block_ = UINT32_MAX;
}

void PhiloxSampler::set_dimension(std::uint32_t d) { dim_ = d; }

void PhiloxSampler::refill() {
    r123::Philox4x32 rng;
    const r123::Philox4x32::ctr_type ctr = {{static_cast<std::uint32_t>(photon_),
                                             static_cast<std::uint32_t>(photon_ >> 32),
                                             dim_ / 4u, 0x6c757874u /* "luxt" */}};
    const r123::Philox4x32::key_type key = {{static_cast<std::uint32_t>(seed_),
                                             static_cast<std::uint32_t>(seed_ >> 32)}};
    const auto out = rng(ctr, key);
    for (int i = 0; i < 4; ++i) words_[i] = out.v[i];
    block_ = dim_ / 4u;
}

double PhiloxSampler::next() {
    if (dim_ / 4u != block_) refill();
    const std::uint32_t w = words_[dim_ % 4u];
    ++dim_;
    // 32 random bits, centred in their interval: strictly inside (0, 1).
    return (static_cast<double>(w) + 0.5) * 0x1p-32;
}

std::string sampler_unavailable(const std::string& kind) {
    if (kind == "random") return {};
    if (kind == "sobol") return "'sobol' is not available in this build (it has: random)";
    return "unknown sampler '" + kind + "' (this build has: random)";
}

std::unique_ptr<Sampler> make_sampler(const std::string& kind, std::uint64_t seed) {
    if (const std::string why = sampler_unavailable(kind); !why.empty()) throw InputError("sampler: " + why);
    return std::make_unique<PhiloxSampler>(seed);
}

}  // namespace luxtrace
