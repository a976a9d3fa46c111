#pragma once
// The sensors of a points detector (a Radiance .pts grid) as small discs: sensor k is the
// disc of radius r about positions[k], perpendicular to directions[k], and counts photons
// that cross it from the front (against its direction), like one cell of an illuminance
// grid of area pi r^2.
//
// A flight must not test thousands of discs one by one. Sensors are grouped by plane
// (same direction within kSamePlaneCos, offset along it within kSamePlaneM); a flight
// meets each plane once, and within the plane a uniform 2D bin grid (bins at least r wide,
// so a disc reaches only the 3 x 3 bins around the crossing point) gives the few
// candidates. A grid of one plane costs one plane test and about nine bin reads per flight.
// Sensors that share no plane make many planes: a bounding-volume hierarchy over the
// planes' boxes (every disc of the plane inside) then leaves only the planes whose box the
// flight passes through to test.
#include "luxtrace/core/math.hpp"

#include <cstdint>
#include <vector>

namespace luxtrace {

class SensorPoints {
public:
    // Directions within about 0.03 degrees and offsets within 0.1 mm count as one plane:
    // .pts files carry rounded decimals (Honeybee writes 0.800000011921 for a float's 0.8),
    // and a crossing found on the shared plane instead of a sensor's own moves by at most
    // 0.1 mm times the tangent of the incidence, far below any useful disc radius.
    static constexpr double kSamePlaneCos = 1.0 - 1.5e-7;
    static constexpr double kSamePlaneM = 1e-4;

    SensorPoints() = default;
    // `directions` are unit vectors; radius_m > 0.
    SensorPoints(std::vector<Vec3> positions, std::vector<Vec3> directions, double radius_m);

    std::size_t size() const { return positions_.size(); }
    const std::vector<Vec3>& positions() const { return positions_; }
    const std::vector<Vec3>& directions() const { return directions_; }
    double radius_m() const { return radius_m_; }
    std::size_t planes() const { return planes_.size(); }

    // Append every sensor whose disc the ray o + t d, 0 < t <= t_max, crosses from the
    // front. `hit_normal` and `tolerance_m` as Detector::crossing: a disc lying on the
    // surface the ray ends on is crossed just past the hit, within tolerance_m.
    void crossings(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal, double tolerance_m,
                   std::vector<int>& cells) const;

    // Half the smallest distance between two sensors of one plane (the default radius,
    // docs/REFERENCE.md §2), or 0 if no plane holds two sensors. Two sensors at the same
    // point of a plane give 0 too; `first`, `second` then name them (indices).
    static double half_smallest_spacing_m(const std::vector<Vec3>& positions, const std::vector<Vec3>& directions,
                                          int* first = nullptr, int* second = nullptr);

private:
    struct Plane {
        Vec3 normal{0, 0, 1}, u{1, 0, 0}, v{0, 1, 0};
        double offset = 0.0;        // dot(normal, p) on the plane
        double u0 = 0.0, v0 = 0.0;  // lower corner of the bins
        double bin_m = 1.0;
        int nu = 1, nv = 1;
        std::vector<std::uint32_t> bin_start;  // nu * nv + 1 offsets into sensors
        std::vector<std::uint32_t> sensors;    // sensor indices, bin by bin
        std::vector<double> su, sv;            // each listed sensor's plane coordinates
    };
    // A node of the hierarchy over the planes: its box, and either (count 0) its children
    // nodes_[first] and nodes_[first + 1], or (a leaf) the planes plane_order_[first, first + count).
    struct Node {
        Vec3 lo{0.0}, hi{0.0};
        std::uint32_t first = 0, count = 0;
    };
    void cross_plane(const Plane& p, const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal,
                     double tolerance_m, std::vector<int>& cells) const;
    void build_hierarchy();
    static std::vector<std::vector<int>> group_by_plane(const std::vector<Vec3>& positions,
                                                        const std::vector<Vec3>& directions);
    void build_plane(const std::vector<int>& members);

    std::vector<Vec3> positions_, directions_;
    double radius_m_ = 0.0;
    std::vector<Plane> planes_;
    std::vector<Vec3> plane_lo_, plane_hi_;  // each plane's box
    std::vector<Node> nodes_;                // empty: few planes, tested in turn
    std::vector<std::uint32_t> plane_order_;
};

}  // namespace luxtrace
