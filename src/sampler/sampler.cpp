#include "luxtrace/sampler/sampler.hpp"

namespace luxtrace {

std::string sampler_unavailable(const std::string& kind) {
    if (kind == "random") return {};
    if (kind == "sobol") return "'sobol' is not available in this build (it has: random)";
    return "unknown sampler '" + kind + "' (this build has: random)";
}

}  // namespace luxtrace
