#pragma once
// Annual illuminance written as the results folder of the Ladybug Tools annual daylight
// recipe, so that honeybee-radiance-postprocess (its Results / AnnualDaylight classes and
// command line) computes DA, UDI, sDA, ASE and EN 17037 from it unchanged. The layout,
// as that package reads it, is in docs/LADYBUG.md:
//
//   FOLDER/grids_info.json      one object per grid: count, name, identifier, group,
//                               full_id, light_path [["__static_apertures__"]]
//   FOLDER/grid_states.json     {"<full_id>": {}} (static apertures only)
//   FOLDER/sun-up-hours.txt     one hour of the year a line (e.g. 7.5: 7:00-8:00)
//   FOLDER/__static_apertures__/default/total/<full_id>.npy    sensors x sun-up hours
//   FOLDER/__static_apertures__/default/direct/<full_id>.npy   float32, C order
//
// HDF5 stays the primary record (with the errors); this folder holds values only.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace luxtrace {

struct LadybugGrid {
    std::string name;        // display name ("name" in grids_info.json)
    std::string identifier;  // file name of the arrays, "identifier" and "full_id"
    std::size_t sensors = 0;
    // Row per sensor, column per sun-up hour (sensors x hours, row-major). "direct" is
    // the direct sun alone, no sky and no reflection (what ASE counts), as the recipe's.
    std::vector<float> total_lx;
    std::vector<float> direct_lx;
    // Where both are empty: sensors [first, first + count)'s rows (count x hours,
    // row-major) of the total (`direct` false) or the direct sun, a few at a time, so that a
    // whole building's arrays never sit in memory.
    std::function<void(bool direct, std::size_t first, std::size_t count, std::span<float> out)> rows;
};

// Writes the folder so that readers see the old folder or the new one, never a part:
// everything goes to a hidden `.NAME.tmp.PID` beside it first and is swapped in whole
// (an existing folder is replaced only after the new one is complete). Bad arguments
// (an identifier that is not a plain file name, duplicate identifiers, array sizes that
// are not sensors x hours, fewer than 2 sun-up hours, hours not in increasing whole
// hours within [0, 8760), values not finite)
// throw InputError naming the grid; write failures throw IoError; nothing is then left.
void write_ladybug_results(const std::filesystem::path& folder, const std::vector<LadybugGrid>& grids,
                           const std::vector<double>& sun_up_hours);

// The bytes of a NumPy .npy file (format version 1.0) holding a rows x cols float32
// array, little-endian ('<f4'), C order: the header is padded with spaces and a newline
// so that the data start at a multiple of 64 bytes.
std::string npy_float32(std::span<const float> values, std::size_t rows, std::size_t cols);
// Its header alone (the data follow it).
std::string npy_float32_header(std::size_t rows, std::size_t cols);

}  // namespace luxtrace
