#pragma once
// Virtual measuring grids. A detector never blocks light: the tracer asks it, for each
// free flight and each scattering event, which cell (if any) the photon registers in.
#include "luxtrace/core/math.hpp"

#include <string>

namespace luxtrace {

enum class DetectorType { illuminance, luminance };

struct Detector {
    std::string name;
    DetectorType type = DetectorType::illuminance;
    Vec3 center{0.0}, normal{0, 0, 1}, up{0, 1, 0};
    Vec3 u_axis{1, 0, 0}, v_axis{0, 1, 0};  // u = up x normal (cells nx), v = up (cells ny)
    double size_u = 1.0, size_v = 1.0;
    int nx = 1, ny = 1;
    // luminance: axis of the cone of directions leaving the surface toward the viewer,
    // on the front side; view_direction in the scene file may point either way.
    Vec3 view_direction{0, 0, 1};
    Vec3 cone_axis{0, 0, 1};
    double half_angle_deg = 5.0;
    double cos_half_angle = 0.0;
    double plane_tolerance_m = 1e-3;  // how far from the plane a scattering point may lie

    // Set derived fields (axes, cone) from the user's values; call after filling them.
    void finalize();
    int cells() const { return nx * ny; }
    double cell_area_m2() const { return size_u * size_v / (nx * ny); }
    double solid_angle_sr() const { return 2.0 * kPi * (1.0 - cos_half_angle); }
    double cos_view() const { return glm::dot(cone_axis, normal); }
    // Value of one registration (times flux per photon) per unit count: 1/A (lux) or
    // 1/(A cos(theta) Omega) (cd/m^2).
    double value_per_lm() const;
    const char* units() const { return type == DetectorType::illuminance ? "lx" : "cd/m^2"; }

    // Cell index of a point in the detector plane, or -1 outside the rectangle.
    int cell_at(const Vec3& p) const;
    // Illuminance: the cell where the ray o + t d, 0 < t <= t_max, crosses the plane from
    // the front side, or -1.
    int crossing(const Vec3& o, const Vec3& d, double t_max) const;
    // Luminance: the cell where a photon leaving point p along d registers, or -1.
    int leaving(const Vec3& p, const Vec3& d) const;
};

}  // namespace luxtrace
