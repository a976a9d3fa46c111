#include "luxtrace/light/luminous_opening.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace luxtrace {
namespace {

using S = LuminousOpening::Shape;

// Elliptic cylinder along axis `ax` (0 x, 1 y, 2 z) of half-length h, cross-section
// semi-axes (a, b) along the other two axes in cyclic order. Returns the point, or the
// projected area when `area` is set.
struct Cylinder {
    int ax;
    double h, a, b;
    int i() const { return (ax + 1) % 3; }
    int j() const { return (ax + 2) % 3; }
    double side(const Vec3& d) const { return 2.0 * std::hypot(b * d[i()], a * d[j()]) * 2.0 * h; }
    double cap(const Vec3& d) const { return kPi * a * b * std::abs(d[ax]); }
    Vec3 sample(const Vec3& d, double u1, double u2) const {
        const double ws = side(d), wc = cap(d);
        Vec3 p(0.0);
        if (u1 * (ws + wc) < wc) {  // the end cap facing d, uniform on the ellipse
            const double t = std::clamp(u1 * (ws + wc) / wc, 0.0, 1.0);
            const double r = std::sqrt(t), phi = 2.0 * kPi * u2;
            p[i()] = a * r * std::cos(phi);
            p[j()] = b * r * std::sin(phi);
            p[ax] = d[ax] >= 0.0 ? h : -h;
            return p;
        }
        // The side: along the ellipse (a cos s, b sin s) the outward normal times the arc
        // element is (b cos s, a sin s) ds, so the weight n.d ds is R cos(s - s0).
        const double t = wc > 0.0 ? std::clamp((u1 * (ws + wc) - wc) / ws, 0.0, 1.0) : u1;
        const double s0 = std::atan2(a * d[j()], b * d[i()]);
        const double s = s0 + std::asin(std::clamp(2.0 * t - 1.0, -1.0, 1.0));
        p[i()] = a * std::cos(s);
        p[j()] = b * std::sin(s);
        p[ax] = (2.0 * u2 - 1.0) * h;
        return p;
    }
};

Cylinder cylinder_of(const LuminousOpening& o) {
    const double L = 0.5 * o.length_m, W = 0.5 * o.width_m, H = 0.5 * o.height_m;
    switch (o.shape) {
    case S::cylinder_along_length: return {0, L, W, H};  // cross-section (y, z)
    case S::cylinder_along_width: return {1, W, H, L};   // cross-section (z, x)
    default: return {2, H, L, W};                        // vertical: cross-section (x, y)
    }
}

}  // namespace

double projected_area_m2(const LuminousOpening& o, const Vec3& d) {
    const double L = o.length_m, W = o.width_m, H = o.height_m;
    switch (o.shape) {
    case S::point: return 0.0;
    case S::rectangle: return L * W * std::abs(d.z);
    case S::ellipse: return 0.25 * kPi * L * W * std::abs(d.z);
    case S::box: return W * H * std::abs(d.x) + L * H * std::abs(d.y) + L * W * std::abs(d.z);
    case S::vertical_cylinder:
    case S::cylinder_along_length:
    case S::cylinder_along_width: {
        const Cylinder c = cylinder_of(o);
        return c.side(d) + c.cap(d);
    }
    case S::ellipsoid: {
        // The shadow of the ellipsoid diag(a, b, c) along d is an ellipse of area
        // pi * a b c * |A^-1 d|.
        const Vec3 s(0.5 * L, 0.5 * W, 0.5 * H);
        return kPi * s.x * s.y * s.z * glm::length(d / s);
    }
    }
    return 0.0;
}

Vec3 sample_opening_point(const LuminousOpening& o, const Vec3& d, double u1, double u2) {
    const double L = o.length_m, W = o.width_m, H = o.height_m;
    switch (o.shape) {
    case S::point: return Vec3(0.0);
    case S::rectangle: return {(u1 - 0.5) * L, (u2 - 0.5) * W, 0.0};
    case S::ellipse: {
        const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
        return {0.5 * L * r * std::cos(phi), 0.5 * W * r * std::sin(phi), 0.0};
    }
    case S::box: {
        // The three faces turned toward d, by projected area; uniform on the chosen one.
        const std::array<double, 3> w{W * H * std::abs(d.x), L * H * std::abs(d.y), L * W * std::abs(d.z)};
        const double total = w[0] + w[1] + w[2];
        double u = u1 * total;
        int f = 0;
        while (f < 2 && u >= w[f]) u -= w[f++];
        const double t = w[f] > 0.0 ? std::clamp(u / w[f], 0.0, 1.0) : 0.5;
        const Vec3 half(0.5 * L, 0.5 * W, 0.5 * H);
        Vec3 p(0.0);
        const int i = (f + 1) % 3, j = (f + 2) % 3;
        p[f] = d[f] >= 0.0 ? half[f] : -half[f];
        p[i] = (2.0 * t - 1.0) * half[i];
        p[j] = (2.0 * u2 - 1.0) * half[j];
        return p;
    }
    case S::vertical_cylinder:
    case S::cylinder_along_length:
    case S::cylinder_along_width: return cylinder_of(o).sample(d, u1, u2);
    case S::ellipsoid: {
        // Lines parallel to d, uniform across the shadow, leave the ellipsoid A S (S the
        // unit sphere) where the lines parallel to A^-1 d leave S: sample those on the
        // unit sphere (uniform on the disk across d', lifted to the half facing d').
        const Vec3 s(0.5 * L, 0.5 * W, 0.5 * H);
        const Vec3 dp = glm::normalize(d / s);
        const Frame f = Frame::around(dp);
        const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        const Vec3 unit = f.to_world(Vec3(x, y, std::sqrt(std::max(0.0, 1.0 - r * r))));
        return unit * s;
    }
    }
    return Vec3(0.0);
}

}  // namespace luxtrace
