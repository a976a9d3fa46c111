#pragma once
// The directions sky photons come from: the sky's luminance (sky_model.hpp) above the
// horizon and a uniform ground glow below it, tabulated over the whole sphere in cells of
// 1 degree of zenith angle by 1 degree of azimuth (docs/DAYLIGHT.md, "Sky and sun lights").
//
// A photon from an infinitely distant source of luminance L(w), started on a disc of
// area A perpendicular to its direction, carries the flux A L(w) dw: so directions are
// drawn with density proportional to L (not L cos), and the source's flux through the
// disc is A times the integral of L over the sphere. Each cell's weight is that integral
// over the cell (a 4 x 4 Gauss-Legendre rule in cos Z and azimuth, good to 1e-8 of the
// sky's integral). Within a cell, cos Z and the azimuth are drawn from densities linear in
// each, with the means of the sky's own over the cell: so the cells carry the sky's flux
// and its horizontal illuminance exactly (to the rule's accuracy), and what remains is of
// second order in the cell's size. The flux per photon is exact.
//
// Directions are in the sky frame of sky_model.hpp: z up, north +y, east +x.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/alias_table.hpp"
#include "luxtrace/light/sky_model.hpp"

#include <array>
#include <optional>

namespace luxtrace {

class SkyDirections {
public:
    static constexpr int kRows = 180;     // zenith angle 0..180 degrees, 1 degree each
    static constexpr int kColumns = 360;  // azimuth 0..360 degrees clockwise from north

    // `sky` (if any) scaled by its zenith luminance above the horizon; a uniform
    // `ground_luminance_cd_m2` below it. Throws std::invalid_argument when nothing emits.
    SkyDirections(const std::optional<SkyModel>& sky, double zenith_luminance_cd_m2, double ground_luminance_cd_m2);

    // The unit direction towards the emitting element (the photon travels the other way);
    // u1, u2 in [0, 1).
    Vec3 sample(double u1, double u2) const;

    // Integral of L over the sphere (cd/m2 sr = lm/m2): the flux per unit area of a disc
    // perpendicular to every direction in turn.
    double luminance_integral_cd_m2_sr() const { return total_; }
    // The illuminance the tabulated sky (above the horizon only) gives an unobstructed
    // horizontal plane, as the photons deliver it: each cell's integral of L times the
    // mean cos Z over the cell.
    double horizontal_illuminance_lx() const { return horizontal_lx_; }
    // The probability of cell (row, column), for tests.
    double cell_probability(int row, int column) const;

private:
    AliasTable cells_;
    double total_ = 0.0, horizontal_lx_ = 0.0;
    std::vector<double> weight_;  // per cell, normalised
    std::vector<float> slope_s_, slope_a_;
    std::array<double, kRows + 1> mu_{};  // cos Z at the rows' edges
    std::array<double, kColumns> sin_edge_{},
        cos_edge_{};  // of the columns' first azimuths  // per cell: the linear densities' slopes in cos Z and azimuth
};

}  // namespace luxtrace
