#pragma once
// Portals (docs/DAYLIGHT.md, "Portals"): with `[[portal]]`, sky and sun photons start on a
// room's openings instead of a disk covering the whole scene, so none is spent on the
// outside of the building. A photon starts uniformly over the opening's area, just outside
// it, heading inward with the sky's distribution as seen through the opening: for a sky of
// luminance L(w), directions w over the opening's outward hemisphere with density
// proportional to L(w) cos(theta) (theta from the outward normal), and each photon of the
// opening carries an equal share of A x integral of L cos over that hemisphere, the flux
// the unobstructed sky sends through area A; for the sun, the solar disc, with flux
// E_n A cos(theta_sun). The tracer casts a ray back out towards the sampled sky direction
// and drops the photon if it hits anything (tracer.cpp).
//
// The table is a DirectionTable in the portal's own frame: pole = outward normal, so the
// portal's horizon is the table's 90-degree row boundary; azimuth 0 along the sky's up
// direction projected on the opening (north for a horizontal one), so for a vertical
// opening the sky's horizon runs along the 90- and 270-degree column boundaries. Cells
// that the sky's horizon crosses (tilted openings) are integrated over 8 x 8 sub-cells.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/direction_table.hpp"
#include "luxtrace/light/emitter_surface.hpp"
#include "luxtrace/light/sky_directions.hpp"

#include <memory>
#include <string>

namespace luxtrace {

// An opening: the triangles of a planar [[shape]] and which side is outside.
struct Portal {
    std::string name;             // the shape's name, for messages
    EmitterSurface surface;       // triangles, area, scene triangles
    Vec3 outward{0.0, 0.0, 1.0};  // unit normal pointing out of the room
    int side = 1;                 // +1: outward is the triangles' front normal; -1: their back
    Frame frame;                  // n = outward, b = azimuth 0 of its direction tables
    // The frame of an opening with this outward normal in a scene whose sky frame is
    // `horizon` (site.hpp: n = up, b = north).
    static Frame frame_for(const Vec3& outward, const Frame& horizon);
};

// The directions a sky light sends through an opening, in the scene (towards the sky).
class PortalSky {
public:
    PortalSky(const SkyLuminance& luminance, const Frame& horizon, const Frame& portal);
    // Integral of L cos(theta) over the outward hemisphere (lx): the flux per unit area of
    // the opening. 0 when nothing there emits (then sample() must not be called).
    double illuminance_lx() const { return illuminance_lx_; }
    Vec3 sample(double u1, double u2) const { return portal_.to_world(table_.sample(u1, u2)); }

private:
    Frame portal_;
    DirectionTable table_;
    double illuminance_lx_ = 0.0;
};

}  // namespace luxtrace
