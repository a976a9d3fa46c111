#include "luxtrace/light/orientation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;

// Rodrigues: v turned by `angle` about unit `axis`, right-handed.
Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0 - c));
}

}  // namespace

Frame luminaire_frame(const LuminairePlacement& p) {
    const Vec3 down(0.0, 0.0, -1.0), x(1.0, 0.0, 0.0);
    Vec3 n = glm::normalize(p.aim);
    // 1. The smallest rotation taking straight down to the aim (straight up: a half turn
    //    about x, which keeps C0 along +x).
    Vec3 t = x;
    const Vec3 k = glm::cross(down, n);
    const double sin_a = glm::length(k), cos_a = glm::dot(down, n);
    if (sin_a > 1e-12) t = rotate(x, k / sin_a, std::atan2(sin_a, cos_a));
    // 2. Counter-clockwise seen from above a downlight is a right-handed turn about -n.
    if (p.c0) {
        const Vec3 c = *p.c0 - glm::dot(*p.c0, n) * n;
        if (glm::length(c) < 1e-9 * std::max(1.0, glm::length(*p.c0)))
            throw std::invalid_argument("c0 is parallel to the aim");
        t = c;
    } else if (p.rotation_deg != 0.0) {
        t = rotate(t, -n, p.rotation_deg * kDeg);
    }
    t = glm::normalize(t - glm::dot(t, n) * n);
    Vec3 b = glm::cross(t, n);
    // 3. Tilt: the axis swings toward C0 (b stays).
    if (p.tilt_deg != 0.0) {
        const double a = p.tilt_deg * kDeg;
        const Vec3 n2 = std::cos(a) * n + std::sin(a) * t;
        t = std::cos(a) * t - std::sin(a) * n;
        n = n2;
    }
    // 4. Roll: the axis swings toward C90 (t stays).
    if (p.roll_deg != 0.0) {
        const double a = p.roll_deg * kDeg;
        const Vec3 n2 = std::cos(a) * n + std::sin(a) * b;
        b = std::cos(a) * b - std::sin(a) * n;
        n = n2;
    }
    // 5. Spin about the new axis.
    if (p.spin_deg != 0.0) {
        t = rotate(t, -n, p.spin_deg * kDeg);
        b = glm::cross(t, n);
    }
    return Frame{glm::normalize(t), glm::normalize(b), glm::normalize(n)};
}

double tilt_from_nadir_deg(const Frame& f) { return std::acos(std::clamp(-f.n.z, -1.0, 1.0)) / kDeg; }

}  // namespace luxtrace
