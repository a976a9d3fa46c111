#pragma once
// The `!xform` lines of a Radiance scene, read and never run (docs/RADIANCE.md). The
// options follow Radiance's xform(1) and xf.c: -t x y z, -rx/-ry/-rz degrees, -s factor,
// -mx/-my/-mz act in the order given on the included objects; -i n repeats the following
// run of options n times, -a n makes n copies, copy k stepping by k applications of the run
// after it (several -a give a grid). -n prefixes the surfaces' names ("a0", "a0.1" for
// unnamed arrays as xform names them), -m gives every surface one modifier, -I turns
// surfaces inside out, -c and -e are accepted and change nothing here.
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace luxtrace::radiance {

struct XformCopy {
    glm::dmat4 matrix{1.0};   // object -> including file's coordinates (column vectors)
    std::string name_prefix;  // "" when none
};

struct XformCommand {
    std::vector<XformCopy> copies;   // one unless -a
    std::string new_modifier;        // -m, "" when none
    bool invert = false;             // -I
    std::vector<std::string> files;  // as written, relative to the including file
};

// The words of a command line ("xform" first), split as a shell would for plain words and
// quotes. Throws InputError "<where>: ..." on shell syntax (pipes, redirection,
// substitution): a scene file never runs a program.
std::vector<std::string> split_command(const std::string& line, const std::string& where);

// `words` are the command's words after "xform". Throws InputError "<where>: ..." for a
// malformed or unsupported option, or no file.
XformCommand parse_xform(const std::vector<std::string>& words, const std::string& where);

}  // namespace luxtrace::radiance
