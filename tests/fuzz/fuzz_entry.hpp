#pragma once
// Entry functions of the fuzz targets (tests/fuzz/README.md). Each takes one input, writes
// it to a private temporary file (the readers take paths), reads it the way the command
// line would and returns 0. Bad input must end in luxtrace::InputError, which the entry
// swallows; anything else propagates (another exception), aborts (a broken invariant of
// what was accepted, reported on stderr) or crashes. The same functions are called by
// libFuzzer (fuzz_main.cpp, clang) and by the replay test (replay_main.cpp, any compiler).
#include <cstddef>
#include <cstdint>
#include <string>

namespace luxtrace::fuzz {

// A whole scene file (TOML). Relative paths in it resolve into a fixed folder holding a
// few valid small files: cube.obj (+ cube.mtl), tri.ply, light.ies (see fuzz_entry.cpp).
int fuzz_scene(const std::uint8_t* data, std::size_t size);
// An IES LM-63 file; accepted photometry is also integrated and sampled.
int fuzz_ies(const std::uint8_t* data, std::size_t size);
// A mesh file loaded through a fixed scene's [[mesh]]: the first byte chooses the
// extension (even: .obj, odd: .ply), the rest is the file.
int fuzz_mesh(const std::uint8_t* data, std::size_t size);
// A result or checkpoint file (HDF5) read as `luxtrace info`, `run --restart` and
// `render` (views and detector pictures) would.
int fuzz_result(const std::uint8_t* data, std::size_t size);

// A weather file: the first byte chooses the extension (even: .epw, odd: .wea), the rest
// is the file, read by luxtrace::weather::read_weather_file.
int fuzz_weather(const std::uint8_t* data, std::size_t size);

// A Radiance sensor-point file (.pts), read by luxtrace::read_pts, and the points
// detector's plane lookup built on what it read.
int fuzz_pts(const std::uint8_t* data, std::size_t size);

// A Radiance scene file (.rad), read by luxtrace::read_radiance; its `!xform` lines may
// name part.rad, a valid small file beside it (see fuzz_entry.cpp).
int fuzz_radiance(const std::uint8_t* data, std::size_t size);

using Entry = int (*)(const std::uint8_t*, std::size_t);
// "scene", "ies", "mesh", "result", "weather", "pts", "radiance" -> the entry function, or nullptr.
Entry entry_by_name(const std::string& name);

}  // namespace luxtrace::fuzz
