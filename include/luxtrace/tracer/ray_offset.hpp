#pragma once
// Where a ray leaving a surface starts. Embree intersects in float; a new ray that
// starts exactly at the float hit point may hit the surface it leaves again, or start a
// hair behind it. Instead of one scene-wide epsilon, the hit point is computed from the
// triangle's barycentrics together with a bound on its rounding error, and the origin is
// moved along the normal just past that bound (pbrt-v4, "Robust Spawned Rays": the
// interpolation error is at most gamma(7) |b_i p_i| summed per axis, and the offset
// point is rounded away from the surface). The bound scales with the coordinates, so it
// holds wherever the triangle lies; EmbreeScene keeps coordinates small by centring.
#include "luxtrace/core/math.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace luxtrace {

// The next float above / below a finite v (std::nextafter without the library call).
inline float next_float_up(float v) {
    if (v == 0.0f) return std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(v);
    return std::bit_cast<float>(v > 0.0f ? bits + 1 : bits - 1);
}
inline float next_float_down(float v) { return -next_float_up(-v); }

// A point on a triangle in float coordinates and a per-axis bound on its error.
struct SurfacePoint {
    Vec3f p;
    Vec3f error;
};

// gamma(n) = n u / (1 - n u), u = 2^-24 (unit roundoff of float): the bound on the
// relative error of n float operations (Higham).
constexpr float float_gamma(int n) {
    constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
    return (n * u) / (1.0f - n * u);
}

// The point at barycentrics (b1, b2) as Embree reports them (p = (1 - b1 - b2) p0 +
// b1 p1 + b2 p2), kept off the triangle's edges: a point on an edge may lie on the plane
// of the neighbouring face (the floor meeting a wall), and a ray starting on a plane is
// hit by it at t = 0 whichever way it goes. So the point is moved toward the centroid by
// twice its error bound plus `margin` (the largest error Embree's test makes on this
// triangle, see self_hit_margin), a few micrometres at most: the same triangle, and
// strictly inside the room.
// `min_height`, the triangle's smallest height (0 if unknown), lets a point that is
// farther than that from every edge skip the move (b_i times the height from vertex i is
// the distance to the opposite edge).
inline SurfacePoint point_on_triangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, float b1, float b2,
                                      float margin, float min_height = 0.0f) {
    b1 = std::clamp(b1, 0.0f, 1.0f);
    b2 = std::clamp(b2, 0.0f, 1.0f - b1);
    const float b0 = std::max(0.0f, (1.0f - b1) - b2);
    const Vec3f p = b0 * p0 + b1 * p1 + b2 * p2;
    Vec3f error = float_gamma(7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
    const float inset = 2.0f * (std::max({error.x, error.y, error.z}) + margin);
    if (std::min({b0, b1, b2}) * min_height > 2.0f * inset) return {p, error};
    const Vec3f to_centroid = (p0 + p1 + p2) * (1.0f / 3.0f) - p;
    const float l = glm::length(to_centroid);
    SurfacePoint s;
    s.p = l > inset ? p + to_centroid * (inset / l) : p + to_centroid;
    // The step lies in the plane up to its own rounding (the centroid's and the sum's).
    s.error = error + float_gamma(5) * (glm::abs(s.p) + glm::abs(to_centroid));
    return s;
}

// How far from its triangle's plane a ray origin must be for Embree to see on which
// side it lies. Embree's test shifts the triangle to the ray origin (v_i - o) and takes
// the sign of dot(v0 - o, N) with N = cross of the shifted edges: a handful of float
// operations on lengths up to the triangle's longest edge L, so its error is below
// gamma(8) L |N|, while the true value is |N| times the distance to the plane.
inline float self_hit_margin(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2) {
    const float l = std::max({glm::length(p1 - p0), glm::length(p2 - p1), glm::length(p0 - p2)});
    return float_gamma(8) * l;
}

// The origin of a ray leaving `s` to the side of the unit normal `n`: offset along n by
// the error bound projected on n plus the triangle's `margin`, then rounded one float
// further away along every axis n has a component on.
inline Vec3f spawn_origin(const SurfacePoint& s, const Vec3f& n, float margin) {
    const float d = glm::dot(glm::abs(n), s.error) + margin;
    Vec3f o = s.p + d * n;
    for (int i = 0; i < 3; ++i) {
        if (n[i] > 0.0f) o[i] = next_float_up(o[i]);
        else if (n[i] < 0.0f) o[i] = next_float_down(o[i]);
    }
    return o;
}

}  // namespace luxtrace
