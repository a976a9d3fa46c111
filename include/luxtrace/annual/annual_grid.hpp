#pragma once
// The sensor grids of an annual run (docs/ANNUAL.md): the detectors whose every hour is
// estimated from the daylight coefficients and whose annual metrics a target may name.
namespace luxtrace {

struct Detector;

// Illuminance and points detectors that count every photon (an eye detector counts only
// the indirect light).
bool annual_grid(const Detector& d);

}  // namespace luxtrace
