#pragma once
// IES LM-63 photometric data (type C) and sampling of emission directions from it.
//
// Angles follow the type C convention: gamma (vertical angle) is measured from the
// photometric nadir (0 = straight down out of the luminaire, 180 = straight up), and
// c (horizontal angle) is the C-plane angle around the nadir axis. In the luminaire
// frame used here local +z is the nadir and local +x is the plane C = 0, so a direction
// is (sin g cos c, sin g sin c, cos g); the light places this frame along its `aim`.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/alias_table.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {

// How the file's C-planes cover the full circle (LM-63 rules for type C, keyed on the
// first and last horizontal angle).
enum class IesSymmetry {
    Rotational,   // a single plane (0): the same in every C-plane
    Quadrant,     // 0..90: mirrored about the 0-180 and the 90-270 planes
    Bilateral,    // 0..180: mirrored about the 0-180 plane
    Bilateral90,  // 90..270 (LM-63-1995): mirrored about the 90-270 plane
    Full,         // 0..360: no symmetry, plane 360 is plane 0
};

// IES LM-63 (1995/2002) type C photometry, as read from the file.
struct IesPhotometry {
    std::vector<double> vertical_deg;             // gamma angles, 0 = photometric nadir
    std::vector<double> horizontal_deg;           // C-plane angles as in the file
    std::vector<std::vector<double>> candela_cd;  // [horizontal][vertical], already times the
                                                  // file's candela multiplier and ballast factor
    // Header data kept for reports; none of it changes the intensities above.
    std::vector<std::pair<std::string, std::string>> keywords;  // "[TEST] x" -> {"TEST", "x"}
    int num_lamps = 1;
    double lumens_per_lamp = -1.0;  // -1 means absolute photometry
    double input_watts = 0.0;

    // Symmetry implied by horizontal_deg; throws std::logic_error if it fits no LM-63 rule
    // (load_ies never returns such data).
    IesSymmetry symmetry() const;

    // Intensity in cd toward (gamma, c) in radians, gamma in [0,pi] from nadir, c in
    // [0,2pi) (other c are wrapped): bilinear in the file's angles, unfolded by the file's
    // symmetry; zero outside the vertical range.
    double intensity_cd(double gamma_rad, double c_rad) const;

    // Luminous flux in lm: the integral of intensity_cd over the sphere, computed exactly
    // for the bilinear interpolant.
    double flux_lm() const;
};

// Reads an LM-63-1986/1995/2002 file with TILT=NONE and photometric type 1 (C).
// Throws InputError "<file>:<line>: <what is wrong>" for anything it cannot use.
IesPhotometry load_ies(const std::filesystem::path& file);

// Sampling emission directions proportional to the intensity: a piecewise-constant 2D
// distribution built on a fine regular (gamma, c) grid from intensity_cd, sampled by
// alias tables (marginal in gamma, conditional in c), uniform in cos(gamma)
// and c within a cell. The grid has the cell size of n_gamma x n_c cells over the whole
// sphere but covers only the file's vertical range and one copy of its C-planes under
// its symmetry (the copy is chosen by the leading part of u2).
class IesDistribution {
public:
    // Throws std::invalid_argument if a grid size is < 1 or the distribution has no flux.
    explicit IesDistribution(const IesPhotometry& p, int n_gamma = 360, int n_c = 360);

    // Two uniforms in [0,1) -> unit direction in the luminaire frame:
    // (sin g cos c, sin g sin c, cos g), i.e. local +z is the photometric nadir and local
    // +x is C = 0.
    Vec3 sample(double u1, double u2) const;

    // Integral of the tabulated distribution (equals p.flux_lm() to ~1e-3 at 360x360).
    double flux_lm() const { return flux_lm_; }

private:
    int n_gamma_ = 1, n_c_ = 1;           // cells of the table (over the ranges below)
    double gamma0_ = 0.0;                 // the table's first gamma (the file's first angle)
    double c0_ = 0.0, c_span_ = 0.0;      // the C range one copy covers
    int copies_ = 1;                      // copies of it around the circle (symmetry)
    IesSymmetry symmetry_ = IesSymmetry::Full;
    double flux_lm_ = 0.0;
    std::vector<double> cos_edge_;        // cos of the gamma cell edges, n_gamma + 1
    AliasTable marginal_;                 // over gamma rows
    std::vector<AliasTable> rows_;        // per row over its c cells
};

}  // namespace luxtrace
