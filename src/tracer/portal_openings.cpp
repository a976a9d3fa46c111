#include "luxtrace/tracer/portal_openings.hpp"

#include "luxtrace/light/light.hpp"
#include "luxtrace/light/portal_light.hpp"
#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace luxtrace {

PortalOpenings::PortalOpenings(const Scene& scene) : triangles_(scene.triangle_material.size(), 0) {
    std::set<const Portal*> seen;
    for (const Light& l : scene.lights.lights()) {
        const auto* through = std::get_if<PortalLight>(&l.kind);
        if (through == nullptr || !through->portal || !seen.insert(through->portal.get()).second) continue;
        const Portal& p = *through->portal;
        const EmitterSurface& s = p.surface;
        Opening o;
        o.origin = s.centroid();
        o.frame = Frame::around(p.outward);
        o.t_lo = o.b_lo = std::numeric_limits<double>::infinity();
        o.t_hi = o.b_hi = -std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < s.p0.size(); ++i) {
            for (const Vec3& corner : {s.p0[i], s.p0[i] + s.e1[i], s.p0[i] + s.e2[i]}) {
                const Vec3 local = o.frame.to_local(corner - o.origin);
                o.t_lo = std::min(o.t_lo, local.x);
                o.t_hi = std::max(o.t_hi, local.x);
                o.b_lo = std::min(o.b_lo, local.y);
                o.b_hi = std::max(o.b_hi, local.y);
            }
            triangles_[static_cast<std::size_t>(s.scene_triangle[i])] = 1;
        }
        openings_.push_back(o);
    }
}

bool PortalOpenings::may_pass(std::span<const Vec3> from, const Vec3& d, double cos_half) const {
    if (!(cos_half > 0.0)) return true;  // a cone wider than a hemisphere: in doubt
    const double sin_half = std::sqrt(std::max(0.0, 1.0 - cos_half * cos_half));
    const double half = std::asin(std::min(1.0, sin_half));
    for (const Opening& o : openings_) {
        const double cos_d = glm::dot(d, o.frame.n);
        // The cone's steepest ray towards the plane, at least this steep (the cosine of its
        // angle to n): a cone grazing the plane is in doubt.
        const double steep = cos_d - sin_half;
        if (steep < 1e-3) return true;
        double lo_t = std::numeric_limits<double>::infinity(), hi_t = -lo_t, lo_b = lo_t, hi_b = -lo_t, spread = 0.0;
        std::size_t ahead = 0;
        for (const Vec3& x : from) {
            // The point's distance to the plane along n: a point beyond it sends nothing out
            // through it; points on both sides are in doubt.
            const double s = glm::dot(o.origin - x, o.frame.n);
            if (s >= 0.0) ++ahead;
            // Where the axis ray meets the plane, in the opening's frame.
            const Vec3 q = o.frame.to_local(x + (s / cos_d) * d - o.origin);
            lo_t = std::min(lo_t, q.x);
            hi_t = std::max(hi_t, q.x);
            lo_b = std::min(lo_b, q.y);
            hi_b = std::max(hi_b, q.y);
            // A ray of the cone meets the plane within s half / steep^2 of the axis ray's
            // point (the plane's point moves by s / cos^2 per radian of direction); twice
            // that, and a rounding's worth, for margin.
            spread = std::max(spread, 2.0 * std::abs(s) * half / (steep * steep) + 1e-9 * (1.0 + std::abs(s)));
        }
        if (ahead == 0) continue;               // all beyond this opening
        if (ahead != from.size()) return true;  // astride its plane
        if (hi_t + spread >= o.t_lo && lo_t - spread <= o.t_hi && hi_b + spread >= o.b_lo && lo_b - spread <= o.b_hi)
            return true;
    }
    return false;
}

}  // namespace luxtrace
