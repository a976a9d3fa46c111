#pragma once
// IES LM-63 photometric files (1986, 1991, 1995, 2002 and 2019 layouts).
#include "luxtrace/light/photometry.hpp"

#include <filesystem>

namespace luxtrace {

// Reads an IES LM-63 file of photometric type C, B or A, with TILT=NONE, TILT=INCLUDE or
// TILT=<file>. Candela values come out with the candela multiplier, the ballast factor
// and (in files before LM-63-2002, which had it) the ballast-lamp photometric factor
// applied. Throws InputError "<file>:<line>: <what is wrong>" for anything it cannot use.
Photometry load_ies(const std::filesystem::path& file);

}  // namespace luxtrace
