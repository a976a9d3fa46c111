#include "luxtrace/tracer/gather_patches.hpp"

#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

GatherPatches::GatherPatches(const Scene& scene, double patch_m) {
    const std::size_t n = scene.triangle_count();
    first_.resize(n);
    cuts_.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
        const glm::uvec3& tri = scene.triangles[t];
        const Vec3 &a = scene.vertices[tri.x], &b = scene.vertices[tri.y], &c = scene.vertices[tri.z];
        const double edge = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
        // At most 256 cuts (65,536 patches) a triangle: a 0.3 m patch on a 77 m triangle.
        const double m = patch_m > 0.0 ? std::clamp(std::ceil(edge / patch_m), 1.0, 256.0) : 1.0;
        cuts_[t] = static_cast<std::uint32_t>(m);
        first_[t] = count_;
        count_ += static_cast<std::size_t>(cuts_[t]) * cuts_[t];
        area_m2_.insert(area_m2_.end(), static_cast<std::size_t>(cuts_[t]) * cuts_[t],
                        scene.triangle_area_m2[t] / (m * m));
    }
}

std::size_t GatherPatches::within(std::uint32_t m, float u, float v) {
    const double mu = std::max(0.0, static_cast<double>(u)) * m, mv = std::max(0.0, static_cast<double>(v)) * m;
    const std::uint32_t i = std::min(m - 1, static_cast<std::uint32_t>(mu));
    std::uint32_t j = std::min(m - 1, static_cast<std::uint32_t>(mv));
    j = std::min(j, m - 1 - i);  // rounding past the hypotenuse
    // The upper half of grid cell (i, j) exists below the hypotenuse's row only.
    const bool upper = i + j + 1 < m && (mu - i) + (mv - j) >= 1.0;
    return static_cast<std::size_t>(2 * m * i - i * i + 2 * j + (upper ? 1 : 0));
}

}  // namespace luxtrace
