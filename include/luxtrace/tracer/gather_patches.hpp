#pragma once
// The surfaces' patches that gathering to sensors works on (issue 37, tracer/sensor_gather.hpp):
// each triangle cut into m x m congruent sub-triangles, m = ceil(longest edge / patch size),
// so that a patch's mean luminance stands for its parts. A point with Embree's barycentric
// (u, v) (p = (1 - u - v) p0 + u p1 + v p2) lies in the patch of row i = floor(m u), column
// j = floor(m v), lower or upper half of that cell of the (u, v) grid; every patch has the
// triangle's area over m^2.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace luxtrace {

struct Scene;

class GatherPatches {
public:
    GatherPatches() = default;
    // patch_m <= 0: one patch per triangle.
    GatherPatches(const Scene& scene, double patch_m);

    std::size_t count() const { return count_; }  // patches of one side of the scene
    std::size_t triangles() const { return first_.size(); }
    std::uint32_t cuts(std::size_t tri) const { return cuts_[tri]; }
    double area_m2(std::size_t patch) const { return area_m2_[patch]; }
    // The patch of triangle `tri` at (u, v).
    std::size_t patch(std::size_t tri, float u, float v) const {
        const std::uint32_t m = cuts_[tri];
        if (m == 1) return first_[tri];
        return first_[tri] + within(m, u, v);
    }
    // The patch's index within its triangle's m^2 (rows of 2 (m - i) - 1 patches).
    static std::size_t within(std::uint32_t m, float u, float v);

private:
    std::vector<std::size_t> first_;  // per triangle, its first patch
    std::vector<std::uint32_t> cuts_;
    std::vector<double> area_m2_;  // per patch
    std::size_t count_ = 0;
};

}  // namespace luxtrace
