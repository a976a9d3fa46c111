#pragma once
// Exact sky components for the CIE 171:2006 daylight test cases (§5.9-5.14; docs/VALIDATION.md,
// "CIE 171:2006 daylight test cases"): a test-support library that integrates the sky's
// luminance over the directions a point sees through a planar opening, without running
// luxtrace, so that both the report's tables and luxtrace's runs can be judged against it.
//
//   SC = (1 / E_h,ext) * integral over the opening of L(w) cos(theta_n) T(theta_o) dw,
//
// with w the direction from the point towards the sky, theta_n its angle to the point's
// normal, theta_o its angle to the opening's normal, T the glazing's transmittance (1 for an
// unglazed opening) and E_h,ext the sky's unobstructed horizontal illuminance. The opening
// is cut at the point's horizon and at its own plane, then opaque obstructions (overhangs,
// walls beyond the opening) are cut out of it as the cones they subtend; each visible convex
// piece is fanned into triangles around the sun's image (the CIE indicatrix has a cone-shaped
// kink there) and integrated by nested adaptive Gauss-Kronrod quadrature over dA:
// dw = cos(theta_o) dA / r^2.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/sky_model.hpp"

#include <functional>
#include <vector>

namespace luxtrace::daylight_reference {

// A planar convex polygon, vertices in order (either winding).
using Polygon = std::vector<Vec3>;

// T against the cosine of the angle of incidence on the pane.
using Transmittance = std::function<double(double cos_incidence)>;

struct SkyComponentQuery {
    Vec3 point;                         // where the illuminance is taken
    Vec3 normal;                        // of the receiving surface (unit)
    Polygon opening;                    // the aperture the sky is seen through
    std::vector<Polygon> obstructions;  // opaque, convex, all beyond the opening's plane
    Transmittance transmittance;        // empty: unglazed
};

// The sky component as a fraction (not %), to a relative accuracy of about `rel_tol`.
double sky_component(const SkyModel& sky, const SkyComponentQuery& q, double rel_tol = 1e-10);

// The same integral without the division by E_h,ext: E / L_z in sr.
double illuminance_per_zenith_luminance_sr(const SkyModel& sky, const SkyComponentQuery& q, double rel_tol = 1e-10);

// The pieces of `opening` that `point` sees past `obstructions` (convex polygons), after
// cutting at the horizontal plane through the point and at the plane of `normal`.
std::vector<Polygon> visible_pieces(const Vec3& point, const Vec3& normal, const Polygon& opening,
                                    const std::vector<Polygon>& obstructions);

// A thin pane with two Fresnel interfaces (unpolarised light, the s and p parts summed
// separately), bulk absorption along the refracted path and the internal reflections summed:
// per polarisation T = (1 - r)^2 tau / (1 - r^2 tau^2), tau = tau_0^(1 / cos theta_t), with
// tau_0 chosen so that T(0) = normal_transmittance (Radiance's `glass` and the issue's
// `[[material]] type = "glazing"` follow the same physics).
double pane_transmittance(double cos_incidence, double normal_transmittance, double refractive_index);

// The 6 mm clear glass of CIE 171:2006 §5.5 as this library models it (docs/VALIDATION.md):
// normal transmittance 0.88, refractive index 1.52.
inline constexpr double kClearGlassNormalTransmittance = 0.88;
inline constexpr double kClearGlassRefractiveIndex = 1.52;
Transmittance clear_glass_6mm();

// An axis-aligned rectangle as a polygon: centre, two half-extent vectors.
Polygon rectangle(const Vec3& center, const Vec3& half_u, const Vec3& half_v);

}  // namespace luxtrace::daylight_reference
