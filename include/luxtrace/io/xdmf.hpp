#pragma once
// The XDMF companion of a result file: lets ParaView or VisIt open the mesh with the
// illuminance maps as cell data read straight from the HDF5 datasets (no copy).
#include <filesystem>

namespace luxtrace {

// Writes `xdmf` (atomically) describing `result`; the HDF5 path inside it is relative
// when both files share a folder. Throws InputError if `result` is not a result file.
void write_xdmf(const std::filesystem::path& result, const std::filesystem::path& xdmf);

}  // namespace luxtrace
