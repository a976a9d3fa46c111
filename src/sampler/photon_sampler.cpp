#include "luxtrace/sampler/photon_sampler.hpp"

#include "luxtrace/core/error.hpp"


namespace luxtrace {

PhotonSampler::PhotonSampler(SamplerKind kind, std::uint64_t seed, std::uint32_t replicates)
    : kind_(kind), seed_(seed), replicates_(replicates), philox_(seed) {
    if (kind_ != SamplerKind::sobol) return;
    if (const std::string why = replicates_invalid(replicates_); !why.empty()) throw InputError("replicates: " + why);
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
        const std::uint64_t stream = stream_of(k[i]), index = index_in_stream(k[i]);
        const auto point = static_cast<std::uint32_t>(index);
        if ((index >> 32) != 0) {
            out[i] = far_block(stream, index, bi);
            continue;
        }
        const std::uint32_t* scramble = &scrambles_[stream * kSobolDimensions];
        done[i] = false;
        if (bi >= 2) {
            const std::uint32_t d = 6 + 3 * (bi - 2);
            w[0] = reversed_point(point, d), sd[0] = scramble[d];
            w[1] = reversed_point(point, d + 1), sd[1] = scramble[d + 1];
            w[2] = reversed_point(point, d + 2), sd[2] = scramble[d + 2];
        } else if (bi == 0) {
            w[0] = reversed_point(point, 0), sd[0] = scramble[0];
            w[1] = reversed_point(point, 1), sd[1] = scramble[1];
            w[2] = reversed_point(point, 4), sd[2] = scramble[4];
            w[3] = reversed_point(point, 5), sd[3] = scramble[5];
        } else {
            w[0] = reversed_point(point, 2), sd[0] = scramble[2];
            w[1] = reversed_point(point, 3), sd[1] = scramble[3];
        }
    }
    SobolSequence::scramble_reversed(words, seeds, 4 * n);
    for (std::size_t i = 0; i < n; ++i)
        if (!done[i]) out[i] = {words[4 * i], words[4 * i + 1], words[4 * i + 2], words[4 * i + 3]};
}

// A stream's 32-bit index runs out after 2^32 points (2^35 photons at R = 8): its next
// 2^32 points are a fresh scramble (stream number raised by R per epoch), computed here,
// off the common path.
PhotonSampler::Block PhotonSampler::far_block(std::uint64_t stream, std::uint64_t index, std::uint32_t b) {
    const auto id = static_cast<std::uint32_t>(stream + replicates_ * (index >> 32));
    const auto point = static_cast<std::uint32_t>(index);
    auto word = [&](std::uint32_t d) {
        return SobolSequence::scramble_reversed(reversed_point(point, d), SobolSequence::scramble_seed(seed_, id, d));
    };
    if (b == 0) return {word(0), word(1), word(4), word(5)};
    if (b == 1) return {word(2), word(3), 0u, 0u};
    const std::uint32_t d = 6 + 3 * (b - 2);
    return {word(d), word(d + 1), word(d + 2), 0u};
}

namespace {
struct NamedSampler {
    const char* name;
    SamplerKind kind;
};
constexpr NamedSampler kSamplers[] = {{"random", SamplerKind::random}, {"sobol", SamplerKind::sobol}};
}  // namespace

SamplerKind sampler_kind(const std::string& name) {
    for (const NamedSampler& s : kSamplers)
        if (name == s.name) return s.kind;
    throw InputError(sampler_unavailable(name));
}

std::string sampler_unavailable(const std::string& name) {
    std::string have;
    for (const NamedSampler& s : kSamplers) {
        if (name == s.name) return {};
        have += (have.empty() ? "" : ", ") + std::string(s.name);
    }
    return "unknown sampler '" + name + "' (this build has: " + have + ")";
}

std::string replicates_invalid(std::int64_t replicates) {
    if (replicates >= 2 && replicates <= 1024 && replicates % 2 == 0) return {};
    return "must be an even number from 2 to 1024 (sobol's independent randomisations), not " +
           std::to_string(replicates);
}

}  // namespace luxtrace
