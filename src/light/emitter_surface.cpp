#include "luxtrace/light/emitter_surface.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>

namespace luxtrace {

Vec3 EmitterSurface::centroid() const {
    Vec3 c(0.0);
    for (std::size_t i = 0; i < p0.size(); ++i) {
        const double share = cdf[i] - (i == 0 ? 0.0 : cdf[i - 1]);
        c += share * (p0[i] + (e1[i] + e2[i]) / 3.0);
    }
    return c;
}

double EmitterSurface::radius_around(const Vec3& centre) const {
    double radius = 0.0;
    for (std::size_t i = 0; i < p0.size(); ++i)
        for (const Vec3& v : {p0[i], p0[i] + e1[i], p0[i] + e2[i]}) radius = std::max(radius, glm::length(v - centre));
    return radius;
}

SurfacePick surface_point(const EmitterSurface& surface, double u1, double u2) {
    // Pick a triangle by area, then a uniform point in it (folded square sampling).
    const std::size_t i = sample_cdf(surface.cdf, u1);
    const double lo = i == 0 ? 0.0 : surface.cdf[i - 1];
    const double width = surface.cdf[i] - lo;
    double a = width > 0.0 ? std::clamp((u1 - lo) / width, 0.0, 1.0) : 0.5;
    double b = u2;
    if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    const Vec3 p = surface.p0[i] + a * surface.e1[i] + b * surface.e2[i];
    return {i, a, b, p};
}

std::optional<SurfacePick> locate_on_surface(const EmitterSurface& s, const Vec3& x) {
    for (std::size_t i = 0; i < s.p0.size(); ++i) {
        // x = p0 + a e1 + b e2 in the triangle's plane.
        const Vec3 w = x - s.p0[i];
        const double d11 = glm::dot(s.e1[i], s.e1[i]), d12 = glm::dot(s.e1[i], s.e2[i]);
        const double d22 = glm::dot(s.e2[i], s.e2[i]);
        const double w1 = glm::dot(w, s.e1[i]), w2 = glm::dot(w, s.e2[i]);
        const double det = d11 * d22 - d12 * d12;
        if (!(det > 0.0)) continue;
        const double a = (w1 * d22 - w2 * d12) / det, b = (w2 * d11 - w1 * d12) / det;
        if (a >= 0.0 && b >= 0.0 && a + b <= 1.0) return SurfacePick{i, a, b, x};
    }
    return std::nullopt;
}

}  // namespace luxtrace
