#include "luxtrace/sampler/photon_sampler.hpp"

#include "luxtrace/core/error.hpp"

namespace luxtrace {

PhotonSampler::PhotonSampler(SamplerKind kind, std::uint64_t seed, std::uint32_t replicates)
    : kind_(kind), seed_(seed), replicates_(replicates), philox_(seed) {
    if (kind_ != SamplerKind::sobol) return;
    if (const std::string why = replicates_invalid(replicates_); !why.empty()) throw InputError("replicates: " + why);
    if ((replicates_ & (replicates_ - 1)) == 0) replicate_shift_ = __builtin_ctz(replicates_);
    const SobolSequence sobol(kSobolDimensions);
    reversed_directions_.assign(static_cast<std::size_t>(kSobolBlocks) * 32u, Block{});
    scrambles_.assign(static_cast<std::size_t>(replicates_) * kSobolBlocks, Block{});
    for (std::uint32_t b = 0; b < kSobolBlocks; ++b) {
        const std::array<std::uint32_t, 4> dims = block_dimensions(b);
        for (int w = 0; w < 4; ++w) {
            if (dims[w] == kNoDimension) continue;
            for (std::uint32_t j = 0; j < 32; ++j)
                reversed_directions_[static_cast<std::size_t>(b) * 32u + j][w] = SobolSequence::reverse_bits(
                    sobol.point(1u << j, dims[w]));
            for (std::uint32_t r = 0; r < replicates_; ++r)
                scrambles_[static_cast<std::size_t>(r) * kSobolBlocks + b][w] = SobolSequence::scramble_seed(seed_, r,
                                                                                                             dims[w]);
        }
    }
    cached_.assign(kSobolBlocks, Cached{});
}

void PhotonSampler::sobol_blocks(const std::uint64_t* k, const std::uint32_t* b, std::size_t n, Block* out) {
    // The words of the n blocks side by side, four per block, gathered as reversed points
    // with their scrambles, then scrambled together. A word a block leaves unused is 0
    // with scramble 0, which scrambles to 0.
    Block words[PhiloxSampler::kBatch], seeds[PhiloxSampler::kBatch];
    bool done[PhiloxSampler::kBatch];  // written to `out` already
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t bi = b[i];
        done[i] = true;
        if (bi >= kSobolBlocks) {  // past the Sobol dimensions: Philox padding
            out[i] = philox_.block(k[i], bi);
            words[i] = seeds[i] = Block{};
            continue;
        }
        const std::uint64_t stream = stream_of(k[i]), index = index_in_stream(k[i]);
        if ((index >> 32) != 0) {
            out[i] = far_block(stream, index, bi);
            words[i] = seeds[i] = Block{};
            continue;
        }
        done[i] = false;
        words[i] = reversed_block(static_cast<std::uint32_t>(index), bi);
        seeds[i] = scrambles_[stream * kSobolBlocks + bi];
    }
    SobolSequence::scramble_reversed(words[0].data(), seeds[0].data(), 4 * n);
    for (std::size_t i = 0; i < n; ++i)
        if (!done[i]) out[i] = words[i];
}

// A stream's 32-bit index runs out after 2^32 points (2^35 photons at R = 8): its next
// 2^32 points are a fresh scramble (stream number raised by R per epoch), computed here,
// off the common path.
PhotonSampler::Block PhotonSampler::far_block(std::uint64_t stream, std::uint64_t index, std::uint32_t b) {
    const auto id = static_cast<std::uint32_t>(stream + replicates_ * (index >> 32));
    const Block& reversed = reversed_block(static_cast<std::uint32_t>(index), b);
    const std::array<std::uint32_t, 4> dims = block_dimensions(b);
    Block out{};
    for (int w = 0; w < 4; ++w)
        if (dims[w] != kNoDimension)
            out[w] = SobolSequence::scramble_reversed(reversed[w], SobolSequence::scramble_seed(seed_, id, dims[w]));
    return out;
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
