#pragma once
// A scene's portals as a shadow ray from inside sees them (docs/DAYLIGHT.md "Portals"):
// with portals, daylight enters only through them, so the direct daylight by shadow rays
// (direct_daylight.hpp) counts a ray only where it crosses an opening (ShadowRay's
// `openings`), as the photons do. And a bundle of rays (from a cell's corners, within a
// cone) that cannot reach any opening is dark without tracing it: most of a side-lit
// room's sun hours at most cells.
#include "luxtrace/core/math.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

class PortalOpenings {
public:
    // The portals of the scene's lights (none: empty()).
    explicit PortalOpenings(const Scene& scene);

    bool empty() const { return openings_.empty(); }
    // Per scene triangle, 1 for an opening's triangle: ShadowRay's `openings`.
    const std::vector<std::uint8_t>& triangles() const { return triangles_; }

    // Whether some ray from the convex hull of `from`, with a direction within the cone of
    // axis `d` (unit) and cosine `cos_half`, may cross an opening outward. Conservative: true
    // where in doubt (a cone grazing an opening's plane, points on both sides of it); false
    // only where no such ray meets any opening's bounding rectangle in its plane.
    bool may_pass(std::span<const Vec3> from, const Vec3& d, double cos_half) const;

private:
    // An opening in its own plane: origin, frame (n outward) and the bounds of its
    // triangles' corners along t and b.
    struct Opening {
        Vec3 origin{0.0};
        Frame frame{};
        double t_lo = 0.0, t_hi = 0.0, b_lo = 0.0, b_hi = 0.0;
    };
    std::vector<Opening> openings_;
    std::vector<std::uint8_t> triangles_;
};

}  // namespace luxtrace
