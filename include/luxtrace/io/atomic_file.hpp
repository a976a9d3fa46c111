#pragma once
// Writing a whole file so that readers see either the old file or the new one, never a
// part: the bytes go to a hidden temporary beside the target (`.NAME.tmp.PID`, on the
// same file system), are synced, and the temporary is renamed over the target.
// Failures throw IoError naming the file and the operating system's reason; the old
// file and the directory are then as they were (the temporary is removed).
#include <filesystem>
#include <span>
#include <string>

namespace luxtrace {

void write_file_atomically(const std::filesystem::path& path, std::span<const char> bytes);

// Temporaries `.NAME.tmp.PID` left beside `path` by writers that died (kill -9, a
// crash) before their rename: removed when their PID is no longer a live process.
// Only that exact pattern for this NAME is touched; returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& path);

// Throws IoError unless a file can be created in `path`'s directory and an existing
// `path` may be replaced (a file without any write permission bit is kept as the
// user's wish, even for root). Creates and removes one probe file.
void check_writable(const std::filesystem::path& path, const std::string& what);

}  // namespace luxtrace
