#pragma once
// The small cylinder of a cylindrical or semi-cylindrical illuminance detector point.
//
// Mean cylindrical illuminance at a point (CIE S 017 ILV; EN 12464-1, where the ratio of
// cylindrical to horizontal illuminance at a point is the "modelling"): the flux falling
// on the curved surface of a very small cylinder there, divided by that surface's area;
// the axis is vertical unless stated otherwise. Semi-cylindrical illuminance (EN 13201-3,
// pedestrian areas) counts the curved half facing a given horizontal direction only. A
// photon counts when its free flight enters the curved (lateral) surface from outside;
// light through the flat caps never reaches the outside of that surface, so it does not.
#include "luxtrace/core/math.hpp"

namespace luxtrace {

// A cylinder in its own frame: centred on the origin, axis +z, |z| <= height_m / 2.
struct CylinderShape {
    double radius_m = 0.01;
    double height_m = 0.2;
    bool half = false;                      // only the half whose outward normal n has n . facing >= 0
    double facing_x = 1.0, facing_y = 0.0;  // unit, across the axis
};

// The t at which the ray o + t d (in the cylinder's frame, d of any non-zero length)
// enters the lateral surface from outside for 0 < t <= t_max, or -1. A ray that starts
// inside (or on) the infinite cylinder never enters it; a tangent ray only touches it.
double lateral_entry(const CylinderShape& c, const Vec3& o, const Vec3& d, double t_max);

}  // namespace luxtrace
