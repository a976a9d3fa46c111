#pragma once
// Small geometric helpers on top of GLM shared by the physics code.
#include <glm/glm.hpp>

#include <cmath>
#include <numbers>

namespace luxtrace {

using Vec3 = glm::dvec3;
using Vec3f = glm::vec3;

inline constexpr double kPi = std::numbers::pi;

// The unit vector (r cos phi, r sin phi, z) normalised, phi = 2 pi u, for r^2 + z^2 = 1
// up to rounding. The azimuth is taken in float: directions are good to 1e-7, which is
// what Embree takes, and float sin/cos cost a fraction of double ones.
inline Vec3 unit_at_azimuth(double r, double z, double u) {
    const float phi = static_cast<float>(2.0 * kPi * u);
    return glm::normalize(Vec3(r * static_cast<double>(std::cos(phi)), r * static_cast<double>(std::sin(phi)), z));
}

// Right-handed orthonormal frame (t, b, n) around a unit vector n.
// Duff et al., "Building an Orthonormal Basis, Revisited" (2017): branch-free, no
// singularity except the sign flip at n.z = 0, which it handles.
struct Frame {
    Vec3 t, b, n;
    static Frame around(const Vec3& n) {
        const double sign = std::copysign(1.0, n.z);
        const double a = -1.0 / (sign + n.z);
        const double b = n.x * n.y * a;
        return {Vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y), n};
    }
    Vec3 to_world(const Vec3& v) const { return v.x * t + v.y * b + v.z * n; }
    Vec3 to_local(const Vec3& v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
};

}  // namespace luxtrace
