#include "luxtrace/io/file_seal.hpp"

#include "luxtrace/core/error.hpp"

#include <zlib.h>

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace luxtrace {

namespace {

constexpr char kMagic[] = "luxtrace-seal v1 ";

std::uint32_t crc_update(std::uint32_t crc, const char* data, std::size_t n) {
    return static_cast<std::uint32_t>(crc32_z(crc, reinterpret_cast<const Bytef*>(data), n));
}

}  // namespace

void seal_image(std::vector<char>& image) {
    const std::size_t body = image.size() - kSealBytes;
    const std::uint32_t crc = crc_update(static_cast<std::uint32_t>(crc32_z(0, nullptr, 0)), image.data() + kSealBytes,
                                         body);
    char line[kSealBytes] = {};
    std::snprintf(line, sizeof line, "%scrc32 %08" PRIx32 " length %zu\n", kMagic, crc, body);
    std::memcpy(image.data(), line, kSealBytes);
}

bool check_seal(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    char head[kSealBytes] = {};
    in.read(head, kSealBytes);
    if (in.gcount() < static_cast<std::streamsize>(sizeof kMagic - 1) ||
        std::memcmp(head, kMagic, sizeof kMagic - 1) != 0) {
        // luxtrace 0.1 wrote unsealed files, whose HDF5 signature is at byte 0. Anything else
        // without a seal is a sealed file whose seal line was damaged (HDF5 would still find
        // the superblock at byte 512 and trust the unchecked rest), or not a result at all.
        if (in.gcount() >= 8 && std::memcmp(head, kHdf5Signature, 8) == 0) return false;
        throw InputError(path.string() +
                         ": damaged file: it does not begin with a luxtrace seal "
                         "(a result or checkpoint whose first bytes were changed, or not a luxtrace file)");
    }
    std::uint32_t want_crc = 0;
    std::size_t want_length = 0;
    if (std::sscanf(head + sizeof kMagic - 1, "crc32 %8" SCNx32 " length %zu", &want_crc, &want_length) != 2)
        throw InputError(path.string() + ": damaged file: its luxtrace seal cannot be read");
    std::uint32_t crc = static_cast<std::uint32_t>(crc32_z(0, nullptr, 0));
    std::size_t length = 0;
    std::vector<char> buf(std::size_t{1} << 20);
    while (in) {
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        const auto n = static_cast<std::size_t>(in.gcount());
        crc = crc_update(crc, buf.data(), n);
        length += n;
    }
    if (length != want_length)
        throw InputError(path.string() + ": damaged file: it has " + std::to_string(length) +
                         " bytes after its seal, " + std::to_string(want_length) +
                         " when luxtrace wrote it (cut short, or appended to)");
    if (crc != want_crc)
        throw InputError(path.string() + ": damaged file: its content differs from what luxtrace wrote (checksum "
                                         "mismatch: a bad disk or copy, or changed by another program since)");
    return true;
}

}  // namespace luxtrace
