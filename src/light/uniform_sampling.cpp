#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

Vec3 sample_uniform_sphere(double u1, double u2) {
    const double z = 1.0 - 2.0 * u1;
    return unit_at_azimuth(std::sqrt(std::max(0.0, 1.0 - z * z)), z, u2);
}

Vec3 sample_uniform_cone(double cos_max, double u1, double u2) {
    // Uniform in solid angle: cos(theta) uniform in [cos_max, 1].
    const double z = 1.0 - u1 * (1.0 - cos_max);
    return unit_at_azimuth(std::sqrt(std::max(0.0, 1.0 - z * z)), z, u2);
}

Vec3 disk_point(double radius, double u1, double u2) {
    const double r = radius * std::sqrt(u1);
    const double phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), 0.0};
}

Vec3 disk_point_f(double radius, double u1, double u2) {
    const double r = radius * std::sqrt(u1);
    const float phi = static_cast<float>(2.0 * kPi * u2);
    return {r * static_cast<double>(std::cos(phi)), r * static_cast<double>(std::sin(phi)), 0.0};
}

std::size_t sample_cdf(const std::vector<double>& cdf, double u) {
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), cdf.size() - 1);
}

}  // namespace luxtrace
