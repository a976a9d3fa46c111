#pragma once
// Sampling emission directions in proportion to a luminaire's intensity: a
// piecewise-constant 2D distribution on a fine regular grid over the file's own angles,
// sampled by alias tables (marginal over the latitude-like angle, conditional over the
// other), uniform in solid angle within a cell.
//  - Type C: rows over gamma (uniform in cos gamma within a row), columns over C. The
//    grid has the cell size of n_lat x n_lon cells over the whole sphere but covers only
//    the file's vertical range and one copy of its C-planes under its symmetry (the copy
//    is chosen by the leading part of u2): a quadrant-symmetric downlight needs an eighth
//    of the full grid, which stays in the core's cache.
//  - Types B and A: rows over the latitude (H for B, V for A; uniform in its sine), columns
//    over the angle about the polar axis, both over the table's ranges at the same cell size.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/alias_table.hpp"
#include "luxtrace/light/photometry.hpp"

#include <vector>

namespace luxtrace {

class PhotometryDistribution {
public:
    // Throws std::invalid_argument if a grid size is < 1 or the distribution has no flux.
    explicit PhotometryDistribution(const Photometry& p, int n_lat = 360, int n_lon = 360);

    // Two uniforms in [0,1) -> unit direction in the luminaire frame (photometry.hpp).
    Vec3 sample(double u1, double u2) const;

    // Integral of the tabulated distribution (equals p.flux_lm() to ~1e-3 at 360x360).
    double flux_lm() const { return flux_lm_; }

private:
    PhotometricType type_ = PhotometricType::C;
    int n_lat_ = 1, n_lon_ = 1;           // cells of the table (over the ranges below)
    double lon0_ = 0.0, lon_span_ = 0.0;  // the angle range about the axis one copy covers
    int copies_ = 1;                      // copies of it around the circle (type C symmetry)
    CPlaneSymmetry symmetry_ = CPlaneSymmetry::Full;
    double flux_lm_ = 0.0;
    std::vector<double> edge_;      // cos gamma (C) or sin latitude (B, A) at row edges
    AliasTable marginal_;           // over rows
    std::vector<AliasTable> rows_;  // per row over its cells
};

}  // namespace luxtrace
