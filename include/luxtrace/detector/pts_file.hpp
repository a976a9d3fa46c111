#pragma once
// Radiance sensor-point files (.pts): one sensor a line, "x y z dx dy dz", the position
// and the direction the sensor faces (rtrace -I's input, what Honeybee writes for a
// sensor grid). rtrace itself reads whitespace-separated words regardless of lines and
// stops at the first word that is not a number; Honeybee reads line by line and skips
// lines starting with '#'. This reader takes the stricter, line-based form plus Honeybee's
// comments: blank lines and lines whose first non-blank character is '#' are skipped;
// every other line holds exactly six finite numbers, the position within +-1e9 m, the
// direction not zero (rtrace would take a zero direction as "flush output", not as a
// sensor). docs/REFERENCE.md §2.
#include "luxtrace/core/math.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace luxtrace {

struct SensorPointList {
    std::vector<Vec3> positions;   // m, scene coordinates
    std::vector<Vec3> directions;  // unit vectors (normalised on reading)
    std::vector<int> lines;        // the 1-based line each sensor came from
};

// Throws InputError naming `file_name`, the line and what is wrong; an empty file (no
// sensor) is an error too.
SensorPointList parse_pts(std::string_view text, const std::string& file_name);
// Reads the file at `path` (InputError if it cannot be opened).
SensorPointList read_pts(const std::string& path);

}  // namespace luxtrace
