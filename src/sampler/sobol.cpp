#include "luxtrace/sampler/sobol.hpp"

#include <Random123/philox.h>
#include <boost/random/sobol.hpp>

#include <stdexcept>
#include <string>

namespace luxtrace {

SobolSequence::SobolSequence(std::uint32_t dimensions) : dimensions_(dimensions) {
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
    const r123::Philox4x32::key_type key = {{static_cast<std::uint32_t>(run_seed), static_cast<std::uint32_t>(run_seed >> 32)}};
    return r123::Philox4x32()(ctr, key).v[0];
}

}  // namespace luxtrace
