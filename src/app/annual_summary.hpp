#pragma once
// The annual daylight part of `luxtrace info` and the end-of-run summary (docs/ANNUAL.md):
// the year the weather file gave, and per sensor grid its metrics with their errors, read
// from /annual.
#include <iosfwd>
#include <string>

namespace luxtrace {
class ResultReader;

// The year: weather file, daylit and sun hours, sky, patches, occupied and EN 17037 hours.
// Prints nothing for a result without /annual.
void print_annual_year(const ResultReader& r, std::ostream& out);

// Sensor grid NAME: sDA, ASE, mean DA and cDA, UDI and EN 17037's levels, each with its
// error (and bias where it is not negligible). Prints nothing without /annual/detectors/NAME.
void print_annual_grid(const ResultReader& r, const std::string& name, std::ostream& out);

}  // namespace luxtrace
