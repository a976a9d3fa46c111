#include "luxtrace/io/xdmf.hpp"

#include "luxtrace/core/error.hpp"

namespace luxtrace {

void write_xdmf(const std::filesystem::path& result, const std::filesystem::path&) {
    throw InputError(result.string() + ": XDMF export is not implemented yet");
}

}  // namespace luxtrace
