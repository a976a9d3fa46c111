#pragma once
// The directions sky photons come from: the sky's luminance (sky_model.hpp) above the
// horizon and a uniform ground glow below it, tabulated over the whole sphere in cells of
// 1 degree of zenith angle by 1 degree of azimuth (docs/DAYLIGHT.md, "Sky and sun lights").
//
// A photon from an infinitely distant source of luminance L(w), started on a disc of
// area A perpendicular to its direction, carries the flux A L(w) dw: so directions are
// drawn with density proportional to L (not L cos), and the source's flux through the
// disc is A times the integral of L over the sphere. The table is a DirectionTable
// (direction_table.hpp): each cell's weight is that integral over the cell (good to 1e-8
// of the sky's integral), so the cells carry the sky's flux and its horizontal illuminance
// exactly (to the rule's accuracy). The flux per photon is exact.
//
// Directions are in the sky frame of sky_model.hpp: z up, north +y, east +x.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/direction_table.hpp"
#include "luxtrace/light/sky_model.hpp"

#include <optional>

namespace luxtrace {

// The luminance a sky light's directions come from (cd/m2), in the sky frame: the sky
// model scaled by its zenith luminance above the horizon, a uniform ground glow below.
struct SkyLuminance {
    std::optional<SkyModel> sky;
    double zenith_cd_m2 = 0.0, ground_cd_m2 = 0.0;
    double operator()(const Vec3& dir) const {
        if (dir.z < 0.0) return ground_cd_m2;
        return sky ? zenith_cd_m2 * sky->relative_luminance(dir) : 0.0;
    }
};

class SkyDirections {
public:
    static constexpr int kRows = 180;     // zenith angle 0..180 degrees, 1 degree each
    static constexpr int kColumns = 360;  // azimuth 0..360 degrees clockwise from north

    // `sky` (if any) scaled by its zenith luminance above the horizon; a uniform
    // `ground_luminance_cd_m2` below it. Throws std::invalid_argument when nothing emits.
    SkyDirections(const std::optional<SkyModel>& sky, double zenith_luminance_cd_m2, double ground_luminance_cd_m2);

    // The unit direction towards the emitting element (the photon travels the other way);
    // u1, u2 in [0, 1).
    Vec3 sample(double u1, double u2) const { return table_.sample(u1, u2); }

    // Integral of L over the sphere (cd/m2 sr = lm/m2): the flux per unit area of a disc
    // perpendicular to every direction in turn.
    double luminance_integral_cd_m2_sr() const { return table_.total(); }
    // The illuminance the tabulated sky (above the horizon only) gives an unobstructed
    // horizontal plane, as the photons deliver it: each cell's integral of L times the
    // mean cos Z over the cell.
    double horizontal_illuminance_lx() const { return horizontal_lx_; }
    // The probability of cell (row, column), for tests.
    double cell_probability(int row, int column) const { return table_.cell_probability(row, column); }
    // The luminance the table was made from (portals tabulate it again in their own frame).
    const SkyLuminance& luminance() const { return luminance_; }
    // The luminance towards unit `dir` (sky frame), from the model itself (for pictures).
    double luminance_cd_m2(const Vec3& dir) const { return luminance_(dir); }

private:
    DirectionTable table_;
    SkyLuminance luminance_;
    double horizontal_lx_ = 0.0;
};

}  // namespace luxtrace
