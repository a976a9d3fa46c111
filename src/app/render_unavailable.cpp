// `luxtrace render` in a build made with -DLUXTRACE_RENDER=OFF (a compute-node binary
// without Cairo and OpenEXR): refuse with a message instead of a missing subcommand, so
// scripts get the usual bad-input exit code and a reason.
#include "commands.hpp"

#include "luxtrace/core/error.hpp"

namespace luxtrace {

int cmd_render(const RenderArgs& args) {
    throw InputError("render " + args.result +
                     ": this luxtrace was built without rendering (-DLUXTRACE_RENDER=OFF); render the result with a "
                     "luxtrace built with the default options");
}

}  // namespace luxtrace
