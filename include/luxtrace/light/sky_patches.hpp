#pragma once
// The sky dome cut into patches for daylight coefficients (docs/DAYLIGHT.md, "Sky
// patches"): Tregenza's 145 patches and Reinhart's subdivisions of them by a factor MF
// (MF 1 = Tregenza; 577 patches for MF 2, 2,305 for MF 4: 144 MF^2 + 1), cut, ordered and
// centred exactly as Radiance's reinhart.cal / reinsrc.cal and gendaymtx's rh_init do, so
// that a coefficient row lines up with a Radiance sky vector.
//
// Rows: the altitude step is alpha = 90 / (7 MF + 0.5) degrees (12 degrees for MF 1). Rows
// r = 0 .. 7 MF - 1 span altitudes [r alpha, (r + 1) alpha] and hold MF n(r / MF) patches,
// n = 30, 30, 24, 24, 18, 12, 6; the last row (r = 7 MF) is one cap around the zenith,
// altitudes [90 - alpha / 2, 90].
// Order: row by row from the horizon up; within a row, the column c = 0 .. n - 1 is centred
// on azimuth c w (w = 360 / n, the row's width), starting at north and going clockwise
// seen from above (north, then towards east).
// Radiance's bins: Radiance numbers the ground 0 and the sky 1 .. 144 MF^2 + 1; our sky
// patch i is Radiance's bin i + 1, and the ground is not a patch here (index_of gives
// count() below the horizon; radiance_bin maps both).
// Azimuths: reinhart.cal takes azi = atan2(Dx, Dy) for the direction D towards the sky, and
// reinsrc.cal / gendaymtx build D = (cos alt sin azi, cos alt cos azi, sin alt), with +y
// north and +x east: the same as ours (sky_model.hpp: clockwise from north seen from
// above, east 90 degrees), so azimuths carry over unchanged. (gendaymtx's manual page says
// the second patch lies west of the first; its code and reinhart.cal put it east, and the
// code is what fills the matrices.)
//
// Directions are in the sky frame of sky_model.hpp: z up, north +y, east +x.
#include "luxtrace/core/math.hpp"

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace luxtrace {

class SkyPatches {
public:
    static constexpr int kMaxMf = 64;  // 589,825 patches

    // Throws std::invalid_argument for mf < 1 or mf > kMaxMf.
    explicit SkyPatches(int mf);

    // Sky patches only: 144 mf^2 + 1.
    std::size_t count() const { return patches_.size(); }
    // Altitude rows, 7 mf + 1 (the last is the zenith cap).
    int rows() const { return static_cast<int>(row_first_.size()) - 1; }
    // The first patch of `row` and how many patches it holds.
    std::size_t row_first(int row) const { return row_first_[static_cast<std::size_t>(row)]; }
    std::size_t row_count(int row) const;
    // The altitude step alpha in degrees.
    double row_step_deg() const { return alpha_deg_; }

    // Bounds in degrees. Azimuths in our convention; column 0 of a row straddles north, so
    // its az_lo_deg is negative (-w / 2): a direction of azimuth a in [0, 360) lies in a
    // patch when a or a - 360 lies in [az_lo_deg, az_hi_deg]. The zenith cap spans
    // azimuths [0, 360].
    struct Patch {
        double alt_lo_deg, alt_hi_deg, az_lo_deg, az_hi_deg;
        int row, column;
    };
    const Patch& patch(std::size_t i) const { return patches_[i]; }

    // Radiance's bin number of our patch i (i + 1), and 0 for the ground (i == count()).
    std::size_t radiance_bin(std::size_t i) const { return i < count() ? i + 1 : 0; }

    // Exact solid angle (sr): (sin alt_hi - sin alt_lo) times the azimuth width in radians.
    double solid_angle_sr(std::size_t i) const;
    // Exact integral of cos Z over the patch (sr): the horizontal illuminance (lx) a patch
    // of unit luminance (cd/m2) gives, (sin^2 alt_hi - sin^2 alt_lo) / 2 times the width.
    double projected_solid_angle_sr(std::size_t i) const;
    // The unit direction Radiance takes as the patch's centre (gendaymtx's rh_palt/rh_pazi,
    // reinsrc.cal at x1 = x2 = 0.5): mid-altitude and mid-azimuth; the zenith for the cap.
    Vec3 center(std::size_t i) const;
    // The patch holding direction `dir` (need not be unit): each direction above the
    // horizon (z >= 0) lies in exactly one patch, with lower bounds inclusive (the bins of
    // reinhart.cal); count() for z < 0 (the ground).
    std::size_t index_of(const Vec3& dir) const;
    // A unit direction uniform in solid angle over patch i (uniform in sin altitude and in
    // azimuth); u1 (altitude), u2 (azimuth) in [0, 1).
    Vec3 sample(std::size_t i, double u1, double u2) const;

    // Per patch, the cosine-weighted mean of luminance function L (of a unit direction):
    // integral_p L cos Z dw / integral_p cos Z dw, so that sum_i mean_i projected_i is the
    // horizontal illuminance of the sky L; and the plain mean over solid angle. Both by a
    // `nodes` x `nodes` Gauss-Legendre product rule (nodes 1 to 64, else
    // std::invalid_argument):
    // - row patches in (sin altitude, azimuth), where dw = d(sin alt) d(azimuth): exact for
    //   L polynomial of degree up to 2 nodes - 2 in sin alt (cosine-weighted; 2 nodes - 1
    //   plain) and 2 nodes - 1 in azimuth;
    // - the zenith cap in (zenith angle, azimuth), in 6 MF azimuth sectors (the row
    //   below's patches), as directions are not smooth in sin altitude at the zenith;
    //   converges exponentially for a smooth L (1e-13 for a polynomial in cos Z at 8 nodes);
    // - `cusp`: a direction where L has a kink (the sun of the CIE general and Perez skies,
    //   whose luminance goes as exp(d chi) in the angle chi to the sun): the piece of the
    //   patch holding it is cut there into four, so the kink lies on their corners.
    // Accuracy at 8 nodes with the sun as cusp, CIE skies 7 and 12, sun at 10-88 degrees:
    // each patch's mean within 3e-5, the horizontal illuminance within 2e-7; without the
    // cusp the sun's patch is only within 4e-4 (docs/DAYLIGHT.md, "Sky patches").
    // Radiance's gendaymtx does neither: it takes L at each patch's centre, and rescales
    // the sky so that sum_i L(centre_i) sin(alt_i) omega_i is the diffuse horizontal
    // illuminance.
    std::vector<double> cosine_weighted_means(const std::function<double(const Vec3&)>& L, int nodes = 8,
                                              const std::optional<Vec3>& cusp = std::nullopt) const;
    std::vector<double> solid_angle_means(const std::function<double(const Vec3&)>& L, int nodes = 8,
                                          const std::optional<Vec3>& cusp = std::nullopt) const;

    // The nodes and weights of those rules, every patch's, made once for many luminance
    // functions (a year's skies: the directions are the same every hour but at the sun's
    // patch, which means() still cuts at its cusp). means() with them gives the same
    // values, to the bit, as the functions above.
    struct Quadrature {
        int nodes = 0;
        bool cosine_weighted = false;
        std::vector<std::size_t> first;  // per patch, its first node; count() + 1 entries
        std::vector<Vec3> direction;
        std::vector<double> weight;
        std::vector<double> total;  // per patch, the sum of its weights
    };
    Quadrature quadrature(int nodes, bool cosine_weighted) const;
    std::vector<double> means(const Quadrature& q, const std::function<double(const Vec3&)>& L,
                              const std::optional<Vec3>& cusp = std::nullopt) const;

private:
    // (sin alt, azimuth in radians) bounds of patch i.
    struct Box {
        double s_lo, s_hi, phi_lo, phi_hi;
    };
    Box box(std::size_t i) const;
    // Cuts the piece holding `cusp` (if any) at it.
    static void cut_at(std::vector<Box>& pieces, const Vec3& cusp);
    std::vector<double> means(const std::function<double(const Vec3&)>& L, int nodes, const std::optional<Vec3>& cusp,
                              bool cosine_weighted) const;
    // Patch i's pieces (the cap's sectors; cut at `cusp` when it lies in the patch).
    void pieces_of(std::size_t i, const std::optional<Vec3>& cusp, std::vector<Box>& pieces) const;
    // Calls node(direction, weight) for each node of the product rule over `b`.
    template <class Node>
    static void box_nodes(const std::vector<double>& x, const std::vector<double>& w, const Box& b, bool polar,
                          bool cosine_weighted, Node node);
    double alpha_deg_;
    std::vector<double> row_sin_;         // sin of each row's lower altitude, and 1 at the end
    std::vector<std::size_t> row_first_;  // first patch of each row, and count() at the end
    std::vector<Patch> patches_;
};

}  // namespace luxtrace
