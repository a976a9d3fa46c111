// `luxtrace export-xdmf`: the ParaView/VisIt companion of a result (in lean builds too).
#include "commands.hpp"

#include "luxtrace/io/xdmf.hpp"

#include <filesystem>

namespace luxtrace {

int cmd_export_xdmf(const std::string& result, const std::string& output) {
    write_xdmf(result, output.empty() ? std::filesystem::path(result).replace_extension(".xdmf")
                                      : std::filesystem::path(output));
    return 0;
}

}  // namespace luxtrace
