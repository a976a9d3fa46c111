#include "luxtrace/scene/radiance_shapes.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace::radiance {

namespace {

using Vec2 = glm::dvec2;

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// p in the closed triangle (a, b, c), counter-clockwise.
bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    return orient(a, b, p) >= 0.0 && orient(b, c, p) >= 0.0 && orient(c, a, p) >= 0.0;
}

std::uint32_t add_vertex(TriangleMesh& out, const Vec3& p) {
    out.vertices.push_back(p);
    return static_cast<std::uint32_t>(out.vertices.size() - 1);
}

}  // namespace

int circle_segments(double chord_tolerance) {
    const double t = std::clamp(chord_tolerance, 1e-9, 0.29);  // 0.29: at least 4 chords
    return std::max(4, static_cast<int>(std::ceil(kPi / std::acos(1.0 - t))));
}

Vec3 polygon_area_vector(const std::vector<Vec3>& v) {
    Vec3 n(0.0);
    for (std::size_t i = 2; i < v.size(); ++i) n += glm::cross(v[i - 1] - v[0], v[i] - v[0]);
    return n;
}

bool append_polygon(const std::vector<Vec3>& vertices, TriangleMesh& out) {
    const Vec3 area = polygon_area_vector(vertices);
    const double twice_area = glm::length(area);
    if (!(twice_area > 0.0)) return true;
    // Project on the plane of the two axes not dominant in the normal, turned so that the
    // outline runs counter-clockwise in 2-D.
    const Vec3 an = glm::abs(area);
    const int ax = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    const int u = (ax + 1) % 3, w = (ax + 2) % 3;
    const bool mirrored = area[ax] < 0.0;
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    std::vector<Vec2> p;
    p.reserve(vertices.size());
    for (const Vec3& x : vertices) {
        out.vertices.push_back(x);
        p.emplace_back(x[u], mirrored ? -x[w] : x[w]);
    }
    auto emit = [&](std::size_t a, std::size_t b, std::size_t c) {
        out.triangles.push_back({base + a, base + b, base + c});
    };
    std::vector<std::size_t> ring(vertices.size());
    for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = i;
    // Flat (collinear) vertices add no area: a relative threshold on the 2-D cross product.
    double extent = 0.0;
    for (const Vec2& q : p) extent = std::max({extent, std::abs(q.x - p[0].x), std::abs(q.y - p[0].y)});
    const double flat = 1e-14 * extent * extent;
    // Pass 0 clips ears no reflex vertex lies in (the usual test); pass 1 only refuses
    // vertices strictly inside; pass 2 takes any convex vertex (a self-intersecting outline).
    bool clean = true;
    int pass = 0;
    std::size_t start = 0;  // the search goes on where the last ear was cut: O(n^2) for usual outlines
    while (ring.size() > 3) {
        const std::size_t n = ring.size();
        bool clipped = false;
        for (std::size_t step = 0; step < n && !clipped; ++step) {
            const std::size_t k = (start + step) % n;
            const std::size_t ia = ring[(k + n - 1) % n], ib = ring[k], ic = ring[(k + 1) % n];
            const double o = orient(p[ia], p[ib], p[ic]);
            if (std::abs(o) <= flat) {  // a flat vertex or a spike: drop it, no triangle
                ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
                start = k == 0 ? 0 : k - 1;
                clipped = true;
                break;
            }
            if (o < 0.0) continue;  // reflex
            bool blocked = false;
            if (pass < 2) {
                for (std::size_t j = 0; j < n && !blocked; ++j) {
                    const std::size_t iq = ring[j];
                    if (iq == ia || iq == ib || iq == ic) continue;
                    const Vec2& q = p[iq];
                    if (q == p[ia] || q == p[ib] || q == p[ic]) continue;  // a seam's twin vertex
                    if (pass == 0) {
                        const std::size_t iqp = ring[(j + n - 1) % n], iqn = ring[(j + 1) % n];
                        if (orient(p[iqp], q, p[iqn]) > flat) continue;  // convex: cannot block alone
                        blocked = in_triangle(q, p[ia], p[ib], p[ic]);
                    } else {
                        blocked = orient(p[ia], p[ib], q) > flat && orient(p[ib], p[ic], q) > flat &&
                                  orient(p[ic], p[ia], q) > flat;
                    }
                }
            }
            if (blocked) continue;
            emit(ia, ib, ic);
            ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
            start = k == 0 ? 0 : k - 1;
            clipped = true;
        }
        if (clipped) {
            pass = 0;
            continue;
        }
        if (pass < 2) {
            ++pass;
            if (pass == 2) clean = false;
            continue;
        }
        for (std::size_t k = 1; k + 1 < ring.size(); ++k) emit(ring[0], ring[k], ring[k + 1]);  // give up: fan
        return false;
    }
    if (ring.size() == 3 && std::abs(orient(p[ring[0]], p[ring[1]], p[ring[2]])) > flat)
        emit(ring[0], ring[1], ring[2]);
    return clean;
}

void append_ring(const Vec3& center, const Vec3& normal, double r_inner, double r_outer, double chord_tolerance,
                 TriangleMesh& out) {
    const Frame f = Frame::around(glm::normalize(normal));
    const int n = circle_segments(chord_tolerance);
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (int k = 0; k < n; ++k) {
        const double phi = 2.0 * kPi * k / n;
        const Vec3 d = std::cos(phi) * f.t + std::sin(phi) * f.b;
        add_vertex(out, center + r_outer * d);
        if (r_inner > 0.0) add_vertex(out, center + r_inner * d);
    }
    if (r_inner > 0.0) {
        for (int k = 0; k < n; ++k) {  // outer 2k, inner 2k + 1
            const std::uint32_t o0 = base + 2 * k, i0 = o0 + 1, o1 = base + 2 * ((k + 1) % n), i1 = o1 + 1;
            out.triangles.push_back({i0, o0, o1});
            out.triangles.push_back({i0, o1, i1});
        }
    } else {
        const std::uint32_t c = add_vertex(out, center);
        for (int k = 0; k < n; ++k)
            out.triangles.push_back(
                {c, base + static_cast<std::uint32_t>(k), base + static_cast<std::uint32_t>((k + 1) % n)});
    }
}

void append_sphere(const Vec3& center, double radius, double chord_tolerance, bool inward, TriangleMesh& out) {
    // A latitude-longitude grid of step delta: a cell's triangles have an angular
    // circumradius of at most about delta / sqrt(2), so the plane of each lies within
    // r (1 - cos(delta / sqrt(2))) of the sphere; 1.3 instead of sqrt(2) keeps a margin.
    const double t = std::clamp(chord_tolerance, 1e-9, 0.29);
    const double delta = 1.3 * std::acos(1.0 - t);
    const int m = std::max(2, static_cast<int>(std::ceil(kPi / delta)));
    const int n = std::max(4, static_cast<int>(std::ceil(2.0 * kPi / delta)));
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    add_vertex(out, center + Vec3(0.0, 0.0, radius));  // north pole: base
    for (int i = 1; i < m; ++i) {
        const double theta = kPi * i / m;
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * kPi * j / n;
            add_vertex(out, center + radius * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                   std::cos(theta)));
        }
    }
    const std::uint32_t south = add_vertex(out, center - Vec3(0.0, 0.0, radius));
    auto at = [&](int i, int j) -> std::uint32_t {  // i: 0..m, j wraps
        if (i == 0) return base;
        if (i == m) return south;
        return base + 1 + static_cast<std::uint32_t>((i - 1) * n + (j % n));
    };
    auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        if (inward) out.triangles.push_back({a, c, b});
        else out.triangles.push_back({a, b, c});
    };
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j) {
            // Toward the south is +theta, toward the east +phi: theta x phi points out.
            const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i + 1 < m) tri(a, b, c);
            if (i > 0) tri(a, c, d);
        }
}

void append_cone(const Vec3& p0, const Vec3& p1, double r0, double r1, double chord_tolerance, bool inward,
                 TriangleMesh& out) {
    const Frame f = Frame::around(glm::normalize(p1 - p0));
    const int n = circle_segments(chord_tolerance);
    auto circle = [&](const Vec3& c, double r) {
        const auto first = static_cast<std::uint32_t>(out.vertices.size());
        if (r <= 0.0) {
            add_vertex(out, c);
            return first;
        }
        for (int k = 0; k < n; ++k) {
            const double phi = 2.0 * kPi * k / n;
            add_vertex(out, c + r * (std::cos(phi) * f.t + std::sin(phi) * f.b));
        }
        return first;
    };
    const std::uint32_t b0 = circle(p0, r0), t0 = circle(p1, r1);
    auto bottom = [&](int k) { return r0 > 0.0 ? b0 + static_cast<std::uint32_t>(k % n) : b0; };
    auto top = [&](int k) { return r1 > 0.0 ? t0 + static_cast<std::uint32_t>(k % n) : t0; };
    auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        if (inward) out.triangles.push_back({a, c, b});
        else out.triangles.push_back({a, b, c});
    };
    for (int k = 0; k < n; ++k) {
        // Around the axis is +phi, along it +axis: phi x axis points away from the axis.
        if (r0 > 0.0) tri(bottom(k), bottom(k + 1), top(k + 1));
        if (r1 > 0.0) tri(bottom(k), top(k + 1), top(k));
    }
}

}  // namespace luxtrace::radiance
