#pragma once
// EULUMDAT (.ldt) photometric files, the European interchange format.
#include "luxtrace/light/photometry.hpp"

#include <filesystem>

namespace luxtrace {

// Reads an EULUMDAT file of any symmetry (Isym 0-4). Intensities, stored in cd per
// 1000 lm of lamp flux, come out in cd for lamp set `lamp_set` (1-based; the file's first
// set is its standard one) times the file's conversion factor. stated_flux_lm is that
// set's lamp flux times the light output ratio (LORL). Throws InputError
// "<file>:<line>: <what is wrong>" for anything it cannot use.
Photometry load_eulumdat(const std::filesystem::path& file, int lamp_set = 1);

}  // namespace luxtrace
