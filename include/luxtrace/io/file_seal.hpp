#pragma once
// The seal at the head of every HDF5 file luxtrace writes: the file's first 512 bytes
// (an HDF5 "user block", which HDF5 itself and h5py skip) hold a line
//     luxtrace-seal v1 crc32 <8 hex digits> length <bytes>
// over the rest of the file. Readers check it before HDF5 parses anything: HDF5 1.10
// can crash or hang on damaged bytes its own checksums do not cover (variable-length
// strings in its global heap, small unchunked datasets), and a file that was cut short
// or changed since luxtrace wrote it is refused with a message instead.
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

inline constexpr std::size_t kSealBytes = 512;
// HDF5's 8-byte format signature: at byte kSealBytes of a sealed file, at byte 0 of an
// unsealed one (HDF5 File Format Specification, superblock).
inline constexpr char kHdf5Signature[] = "\x89HDF\r\n\x1a\n";

// Writes the seal into image[0, kSealBytes) over image[kSealBytes, end).
void seal_image(std::vector<char>& image);

// Throws InputError naming `path` if it carries a seal that does not match its bytes.
// Returns false for a file without a seal (written by luxtrace before 0.2, or by
// another program), which is read unchecked.
bool check_seal(const std::filesystem::path& path);

}  // namespace luxtrace
