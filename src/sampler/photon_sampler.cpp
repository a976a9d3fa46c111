#include "luxtrace/sampler/photon_sampler.hpp"

#include "luxtrace/core/error.hpp"

#include <algorithm>

namespace luxtrace {

PhotonSampler::PhotonSampler(SamplerKind kind, std::uint64_t seed, std::uint32_t replicates)
    : kind_(kind), seed_(seed), replicates_(replicates), philox_(seed) {
    if (kind_ != SamplerKind::sobol) return;
    if (replicates_ < 2 || replicates_ > 1024 || replicates_ % 2 != 0)
        throw InputError("replicates: " + std::to_string(replicates_) + " (an even number from 2 to 1024)");
    if ((replicates_ & (replicates_ - 1)) == 0) replicate_shift_ = __builtin_ctz(replicates_);
    const SobolSequence sobol(kSobolDimensions);
    reversed_directions_.resize(static_cast<std::size_t>(kSobolDimensions) * 32u);
    for (std::uint32_t d = 0; d < kSobolDimensions; ++d)
        for (std::uint32_t j = 0; j < 32; ++j)
            reversed_directions_[static_cast<std::size_t>(d) * 32u + j] = SobolSequence::reverse_bits(sobol.point(1u << j, d));
    last_.assign(kSobolDimensions, Last{});
    scrambles_.resize(static_cast<std::size_t>(replicates_) * kSobolDimensions);
    for (std::uint32_t r = 0; r < replicates_; ++r)
        for (std::uint32_t d = 0; d < kSobolDimensions; ++d)
            scrambles_[static_cast<std::size_t>(r) * kSobolDimensions + d] = SobolSequence::scramble_seed(seed_, r, d);
}

void PhotonSampler::sobol_blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out) {
    // The words of the n blocks side by side, four per block, gathered as reversed points
    // with their scrambles, then scrambled together. A word a block leaves unused is 0
    // with scramble 0, which scrambles to 0.
    std::uint32_t words[PhiloxSampler::kBatch * 4] = {}, seeds[PhiloxSampler::kBatch * 4] = {};
    bool done[PhiloxSampler::kBatch];  // written to `out` already
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t bi = b[i];
        std::uint32_t* w = words + 4 * i;
        std::uint32_t* sd = seeds + 4 * i;
        done[i] = true;
        if (bi >= 2 + kSobolBounces) {  // past the Sobol dimensions: Philox padding
            out[i] = philox_.block(k[i], bi);
            continue;
        }
        // (R a power of two, as the default 8: a mask and a shift instead of a division.)
        const std::uint64_t stream = replicate_shift_ >= 0 ? k[i] & (replicates_ - 1) : k[i] % replicates_;
        const std::uint64_t index = replicate_shift_ >= 0 ? k[i] >> replicate_shift_ : k[i] / replicates_;
        const auto point = static_cast<std::uint32_t>(index);
        std::uint32_t dims[3];
        int used = 3;
        if (bi == 0) {
            dims[0] = 0, dims[1] = 1, dims[2] = 4;
            w[3] = reversed_point(point, 5);  // the fourth word: dimension 5
            used = 4;
        } else if (bi == 1) {
            dims[0] = 2, dims[1] = 3;
            used = 2;
        } else {
            dims[0] = 6 + 3 * (bi - 2), dims[1] = dims[0] + 1, dims[2] = dims[0] + 2;
        }
        for (int j = 0; j < std::min(used, 3); ++j) w[j] = reversed_point(point, dims[j]);
        if ((index >> 32) == 0) {
            const std::uint32_t* scramble = &scrambles_[stream * kSobolDimensions];
            for (int j = 0; j < std::min(used, 3); ++j) sd[j] = scramble[dims[j]];
            if (used == 4) sd[3] = scramble[5];
            done[i] = false;
        } else {
            // A stream's 32-bit index runs out after 2^32 points (2^35 photons at R = 8):
            // its next 2^32 points are a fresh scramble (stream number raised by R per epoch).
            const auto id = static_cast<std::uint32_t>(stream + replicates_ * (index >> 32));
            for (int j = 0; j < used; ++j)
                out[i][j] = SobolSequence::scramble_reversed(w[j], SobolSequence::scramble_seed(seed_, id, j < 3 ? dims[j] : 5));
            for (int j = used; j < 4; ++j) out[i][j] = 0;
        }
    }
    SobolSequence::scramble_reversed(words, seeds, 4 * n);
    for (std::size_t i = 0; i < n; ++i)
        if (!done[i]) out[i] = {words[4 * i], words[4 * i + 1], words[4 * i + 2], words[4 * i + 3]};
}

SamplerKind sampler_kind(const std::string& name) {
    if (name == "random") return SamplerKind::random;
    if (name == "sobol") return SamplerKind::sobol;
    throw InputError("unknown sampler '" + name + "' (random or sobol)");
}

}  // namespace luxtrace
