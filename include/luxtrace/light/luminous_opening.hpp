#pragma once
// Where on a luminaire's luminous opening a photon leaves from. The opening is taken to be
// of uniform luminance in each direction (as LM-63 and Radiance's ies2rad assume), so a
// photon bound in direction d starts at a point spread uniformly over the opening's
// projection seen from d: on a flat opening, uniformly over its area; on a solid one,
// over the faces turned toward d in proportion to their projected area (dA times n.d).
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/photometry.hpp"

namespace luxtrace {

// A point of the opening (luminaire frame, relative to the photometric centre) for a
// photon leaving in unit direction `d` (luminaire frame), from two uniforms in [0,1).
Vec3 sample_opening_point(const LuminousOpening& o, const Vec3& d, double u1, double u2);

// The opening's area projected onto the plane normal to unit direction `d` (m^2): the
// intensity toward d divided by it is the opening's luminance.
double projected_area_m2(const LuminousOpening& o, const Vec3& d);

}  // namespace luxtrace
