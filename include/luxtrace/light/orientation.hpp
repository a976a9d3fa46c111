#pragma once
// Placing a luminaire's photometric frame in the scene (docs/PHOTOMETRY.md, "Placing a
// luminaire"). The frame's n is the photometric axis (type C nadir, type B/A beam axis),
// t the C0 direction (B/A: +H) and b = t x n the C90 direction (B/A: +V), so that C
// angles turn counter-clockwise seen from above a downlight, as LM-63 type C, CIE/EN
// C-planes and Radiance (since 2008) have them.
//
// At rest a luminaire hangs straight down (axis -z) with C0 along scene +x (east), so C90
// points along +y (north). Then, in this order, each about the luminaire's own axes as
// left by the previous step (IES LM-72 "counter-clockwise from east", as AGi32 has it):
//  1. `aim`: the axis is turned to point along `aim` by the smallest rotation (C0 stays
//     in the vertical plane through aim and +x; an uplight keeps C0 along +x);
//  2. `rotation_deg` (LM-72 orient) spins it about its axis, C0 turning counter-clockwise
//     seen from above a downlight; or `c0` names the direction C0 points to (projected
//     normal to the axis);
//  3. `tilt_deg` tilts it about its C90-C270 axis, the axis swinging toward C0 (its
//     front: LM-72 tilt);
//  4. `roll_deg` about its C0-C180 axis, the axis swinging toward C90;
//  5. `spin_deg` about the resulting axis, like rotation_deg.
#include "luxtrace/core/math.hpp"

#include <optional>

namespace luxtrace {

struct LuminairePlacement {
    Vec3 aim{0.0, 0.0, -1.0};  // non-zero
    double rotation_deg = 0.0;
    std::optional<Vec3> c0;  // instead of rotation_deg; not parallel to aim
    double tilt_deg = 0.0, roll_deg = 0.0, spin_deg = 0.0;
};

// Throws std::invalid_argument if c0 is (nearly) parallel to aim.
Frame luminaire_frame(const LuminairePlacement& p);

// Angle in degrees between a frame's photometric axis and straight down: the tilt at
// which a TILT table's lamp multiplier is read.
double tilt_from_nadir_deg(const Frame& f);

}  // namespace luxtrace
