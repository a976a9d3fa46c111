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

// The outline projected on the plane of the two axes not dominant in its normal (`area`),
// turned so that it runs counter-clockwise in 2-D.
std::vector<Vec2> project_outline(const std::vector<Vec3>& vertices, const Vec3& area) {
    const Vec3 an = glm::abs(area);
    const int ax = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    const int u = (ax + 1) % 3, w = (ax + 2) % 3;
    const bool mirrored = area[ax] < 0.0;
    std::vector<Vec2> p;
    p.reserve(vertices.size());
    for (const Vec3& x : vertices) p.emplace_back(x[u], mirrored ? -x[w] : x[w]);
    return p;
}

// Flat (collinear) vertices add no area: a relative threshold on the 2-D cross product.
double flat_threshold(const std::vector<Vec2>& p) {
    double extent = 0.0;
    for (const Vec2& q : p) extent = std::max({extent, std::abs(q.x - p[0].x), std::abs(q.y - p[0].y)});
    return 1e-14 * extent * extent;
}

// Ear clipping of a counter-clockwise 2-D outline, its triangles added to `out` as indices
// from `base`. Pass 0 clips ears no reflex vertex lies in (the usual test); pass 1 only
// refuses vertices strictly inside; pass 2 takes any convex vertex (a self-intersecting
// outline).
class EarClipper {
public:
    EarClipper(const std::vector<Vec2>& p, std::uint32_t base, TriangleMesh& out)
        : p_(p), flat_(flat_threshold(p)), ring_(p.size()), base_(base), out_(out) {
        for (std::size_t i = 0; i < ring_.size(); ++i) ring_[i] = i;
    }

    // False if the outline needed pass 2, or was given up on and fanned.
    bool triangulate() {
        bool clean = true;
        int pass = 0;
        while (ring_.size() > 3) {
            if (cut_one(pass)) {
                pass = 0;
                continue;
            }
            if (pass < 2) {
                ++pass;
                if (pass == 2) clean = false;
                continue;
            }
            for (std::size_t k = 1; k + 1 < ring_.size(); ++k) emit(ring_[0], ring_[k], ring_[k + 1]);  // give up: fan
            return false;
        }
        if (ring_.size() == 3 && std::abs(orient(p_[ring_[0]], p_[ring_[1]], p_[ring_[2]])) > flat_)
            emit(ring_[0], ring_[1], ring_[2]);
        return clean;
    }

private:
    // Removes one vertex: a flat one (no triangle) or an ear `pass` allows (its triangle
    // emitted), searching on from where the last was cut: O(n^2) for usual outlines. False
    // if there is none.
    bool cut_one(int pass) {
        const std::size_t n = ring_.size();
        for (std::size_t step = 0; step < n; ++step) {
            const std::size_t k = (start_ + step) % n;
            const std::size_t ia = ring_[(k + n - 1) % n], ib = ring_[k], ic = ring_[(k + 1) % n];
            const double o = orient(p_[ia], p_[ib], p_[ic]);
            if (std::abs(o) <= flat_) {  // a flat vertex or a spike: drop it, no triangle
                remove(k);
                return true;
            }
            if (o < 0.0) continue;  // reflex
            if (pass < 2 && blocked(ia, ib, ic, pass)) continue;
            emit(ia, ib, ic);
            remove(k);
            return true;
        }
        return false;
    }

    // Whether another vertex of the ring keeps (ia, ib, ic) from being an ear in pass 0 or 1.
    bool blocked(std::size_t ia, std::size_t ib, std::size_t ic, int pass) const {
        const std::size_t n = ring_.size();
        for (std::size_t j = 0; j < n; ++j) {
            const std::size_t iq = ring_[j];
            if (iq == ia || iq == ib || iq == ic) continue;
            const Vec2& q = p_[iq];
            if (q == p_[ia] || q == p_[ib] || q == p_[ic]) continue;  // a seam's twin vertex
            if (pass == 0) {
                const std::size_t iqp = ring_[(j + n - 1) % n], iqn = ring_[(j + 1) % n];
                if (orient(p_[iqp], q, p_[iqn]) > flat_) continue;  // convex: cannot block alone
                if (in_triangle(q, p_[ia], p_[ib], p_[ic])) return true;
            } else if (orient(p_[ia], p_[ib], q) > flat_ && orient(p_[ib], p_[ic], q) > flat_ &&
                       orient(p_[ic], p_[ia], q) > flat_) {
                return true;
            }
        }
        return false;
    }

    void emit(std::size_t a, std::size_t b, std::size_t c) {
        out_.triangles.push_back({base_ + a, base_ + b, base_ + c});
    }

    void remove(std::size_t k) {
        ring_.erase(ring_.begin() + static_cast<std::ptrdiff_t>(k));
        start_ = k == 0 ? 0 : k - 1;
    }

    const std::vector<Vec2>& p_;
    const double flat_;
    std::vector<std::size_t> ring_;  // the outline left, as indices into p_
    std::size_t start_ = 0;          // where the search goes on
    const std::uint32_t base_;
    TriangleMesh& out_;
};

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
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), vertices.begin(), vertices.end());
    const std::vector<Vec2> p = project_outline(vertices, area);
    return EarClipper(p, base, out).triangulate();
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
