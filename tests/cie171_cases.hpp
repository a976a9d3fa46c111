#pragma once
// The CIE 171:2006 daylight test cases §5.9-5.14 (sky components through roof and facade
// openings, unglazed and glazed, with an overhang and with an obstructing wall) as geometry
// for the exact integration of daylight_reference.hpp, with the report's published values
// for sky types 1, 5, 12 and 16 (docs/VALIDATION.md, "CIE 171:2006 daylight test cases").
//
// Frame: the 4 m x 4 m x 3 m room spans x, y in [0, 4], z in [0, 3]; z up, north +y, so the
// facade openings (in the wall y = 0) face south, towards the sun of the general skies
// (altitude 60 deg, azimuth 180 deg, as the report fixes it).
#include "daylight_reference.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace::cie171 {

inline constexpr double kSunAltitudeDeg = 60.0;
inline constexpr double kSunAzimuthDeg = 180.0;
inline constexpr int kSkyTypes[] = {1, 5, 12, 16};

// The sky of one CIE type with the report's sun.
SkyModel report_sky(int cie_type);

struct Point {
    std::string label;
    Vec3 position, normal;
};

struct Case {
    std::string id;     // "5.9 1x1", ...
    std::string title;  // the geometry in words
    std::string table;  // the report's table(s)
    daylight_reference::Polygon opening;
    std::vector<daylight_reference::Polygon> obstructions;
    bool glazed = false;
    bool published_includes_erc = false;  // the report's value is SC + ERC of reflecting masks
    std::vector<Point> points;
    // Published values in %, one row per entry of kSkyTypes, one column per point.
    std::vector<std::vector<double>> published;
};

// Every case in the report's geometry (overhang and wall as wide as the report's values imply).
std::vector<Case> report_cases();

// The exact sky component at one point of a case, in %.
double exact_sc_percent(const Case& c, const Point& p, int cie_type);

// The luxtrace runs (tests/data/cie171/*.toml; the geometry here must match the scene
// files): a detector strip of cells 0.5 m long, one per report point along a line, and
// `width_m` across it (wider than the report's points so that enough sky photons land:
// they start on a disc covering the whole scene, and the openings pass a few per mille).
inline constexpr double kDiffuseHorizontalLx = 10000.0;

struct Strip {
    std::string name;
    Vec3 first_center, step, normal, across;  // across: the cell's other side (unit)
    double width_m;                           // the cell's extent along `across`
    int cells;
};

struct RunCase {
    std::string scene;
    std::string section;
    int cie_type;
    bool glazed;
    daylight_reference::Polygon opening;
    std::vector<daylight_reference::Polygon> obstructions;
    std::vector<Strip> strips;
    std::uint64_t photons, seed;
};

std::vector<RunCase> run_cases();

// The exact illuminance (lx) averaged over cell k of a strip: 4 x 4 Gauss-Legendre points on
// each 1 m (across) x 0.5 m (along) part of the cell.
double exact_cell_lx(const RunCase& rc, const Strip& s, int k);

}  // namespace luxtrace::cie171
