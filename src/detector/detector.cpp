#include "luxtrace/detector/detector.hpp"

#include <cmath>

namespace luxtrace {

void Detector::finalize() {
    normal = glm::normalize(normal);
    u_axis = glm::normalize(glm::cross(up, normal));
    v_axis = glm::cross(normal, u_axis);
    cos_half_angle = std::cos(half_angle_deg * kPi / 180.0);
    const Vec3 vd = glm::normalize(view_direction);
    cone_axis = glm::dot(vd, normal) >= 0.0 ? vd : -vd;
    plane_tolerance_m = std::max(1e-4, 1e-3 * std::min(size_u, size_v));
}

double Detector::value_per_lm() const {
    if (type == DetectorType::illuminance) return 1.0 / cell_area_m2();
    return 1.0 / (cell_area_m2() * projected_solid_angle_sr());
}

bool Detector::cone_below_plane() const {
    // theta + a > 90 degrees <=> cos(theta + a) < 0.
    const double cos_t = cos_view(), sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_half_angle * cos_half_angle));
    return cos_t * cos_half_angle - sin_t * sin_a < -1e-12;
}

int Detector::cell_at(const Vec3& p) const {
    const Vec3 r = p - center;
    const double a = glm::dot(r, u_axis) / size_u + 0.5;
    const double b = glm::dot(r, v_axis) / size_v + 0.5;
    if (!(a >= 0.0 && a < 1.0 && b >= 0.0 && b < 1.0)) return -1;
    const int i = std::min(nx - 1, static_cast<int>(a * nx));
    const int j = std::min(ny - 1, static_cast<int>(b * ny));
    return j * nx + i;
}

int Detector::crossing(const Vec3& o, const Vec3& d, double t_max) const {
    const double denom = glm::dot(d, normal);
    if (denom >= 0.0) return -1;  // moving away from the front side, or parallel
    const double t = glm::dot(center - o, normal) / denom;
    // A detector lying on a surface is crossed just at the hit: allow a hair beyond it.
    if (!(t > 0.0 && t <= t_max + plane_tolerance_m)) return -1;
    return cell_at(o + t * d);
}

int Detector::leaving(const Vec3& p, const Vec3& d) const {
    if (std::abs(glm::dot(p - center, normal)) > plane_tolerance_m) return -1;
    if (glm::dot(d, cone_axis) < cos_half_angle) return -1;
    return cell_at(p);
}

}  // namespace luxtrace
