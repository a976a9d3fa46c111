#pragma once
// A luminaire's photometric file in either format, told apart by its content: an IES
// LM-63 file has a "TILT=" line before its numbers, an EULUMDAT file has numbers on its
// lines 2 to 7 (Ityp, Isym, Mc, Dc, Ng, Dg). The file's extension is not consulted.
#include "luxtrace/light/photometry.hpp"

#include <filesystem>

namespace luxtrace {

enum class PhotometryFormat { ies, eulumdat };

// Throws InputError naming the file if it is neither.
PhotometryFormat detect_photometry_format(const std::filesystem::path& file);

// load_ies or load_eulumdat by content. `lamp_set` (1-based) applies to EULUMDAT files;
// for an IES file anything but 1 is an InputError.
Photometry load_photometry(const std::filesystem::path& file, int lamp_set = 1);

}  // namespace luxtrace
