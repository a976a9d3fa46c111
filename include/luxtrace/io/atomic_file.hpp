#pragma once
// Writing a whole file so that readers see either the old file or the new one, never a
// part: the bytes go to a hidden temporary beside the target (`.NAME.tmp.PID`, on the
// same file system), are synced, and the temporary is renamed over the target.
// Failures throw IoError naming the file and the operating system's reason; the old
// file and the directory are then as they were (the temporary is removed). Both calls
// first remove the temporaries of writers that died before their rename.
#include <filesystem>
#include <functional>
#include <span>
#include <string>

namespace luxtrace {

// `before_rename`, if given, runs when the temporary is complete and synced, just before
// the rename (tests throw from it to fail the rename's step: docs/RELIABILITY.md).
void write_file_atomically(const std::filesystem::path& path, std::span<const char> bytes,
                           const std::function<void()>& before_rename = {});

// Writes all of `bytes` to the open descriptor (again where a write is cut short or
// interrupted); 0, or the operating system's error number (EIO for a write of nothing).
int write_all(int fd, std::span<const char> bytes);

// Throws IoError unless a file can be created in `path`'s directory and an existing
// `path` may be replaced (a file without any write permission bit is kept as the
// user's wish, even for root). Creates and removes one probe file.
void check_writable(const std::filesystem::path& path, const std::string& what);

}  // namespace luxtrace
