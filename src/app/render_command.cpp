#include "commands.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/xdmf.hpp"

namespace luxtrace {

int cmd_render(const RenderArgs& args) {
    throw InputError(args.result + ": rendering is not implemented yet");
}

int cmd_export_xdmf(const std::string& result, const std::string& output) {
    write_xdmf(result, output.empty() ? std::filesystem::path(result).replace_extension(".xdmf")
                                      : std::filesystem::path(output));
    return 0;
}

}  // namespace luxtrace
