#pragma once
// Random numbers for photon k as a pure function of (seed, k, dimension).
// The tracer positions the sampler at a photon and then draws dimensions in a fixed
// order (see tracer.hpp), so tallies do not depend on which rank or thread traced a
// photon, and a quasi-random sampler can replace this one without touching the tracer.
#include <cstdint>
#include <memory>
#include <string>

namespace luxtrace {

class Sampler {
public:
    virtual ~Sampler() = default;
    // Position at photon k, dimension 0.
    virtual void start_photon(std::uint64_t k) = 0;
    // Next dimension, uniform in [0, 1).
    virtual double next() = 0;
    // Jump to dimension d of the current photon (used to give each bounce fixed dimensions).
    virtual void set_dimension(std::uint32_t d) = 0;
};

// Philox4x32-10 (Salmon et al., SC'11, via Random123): counter = (k, dimension block),
// key = seed. Each counter yields four 32-bit words, i.e. four dimensions.
class PhiloxSampler final : public Sampler {
public:
    explicit PhiloxSampler(std::uint64_t seed);
    void start_photon(std::uint64_t k) override;
    double next() override;
    void set_dimension(std::uint32_t d) override;

private:
    void refill();
    std::uint64_t seed_;
    std::uint64_t photon_ = 0;
    std::uint32_t dim_ = 0;
    std::uint32_t block_ = UINT32_MAX;  // dimension block held in words_
    std::uint32_t words_[4] = {};
};

// Samplers this build has, by the name used in the scene file and on the command line.
// Empty if `kind` is available, otherwise what to tell the user ("'sobol' is not
// available in this build (it has: random)"). The loader and the CLI check with it, so
// that make_sampler never fails inside a tracing thread.
std::string sampler_unavailable(const std::string& kind);

// Factory by that name; throws InputError for a name sampler_unavailable() rejects.
std::unique_ptr<Sampler> make_sampler(const std::string& kind, std::uint64_t seed);

}  // namespace luxtrace
