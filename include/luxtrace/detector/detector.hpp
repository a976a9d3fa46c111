#pragma once
// Virtual measuring grids. A detector never blocks light: the tracer asks it, for each
// free flight and each scattering event, which cell (if any) the photon registers in.
#include "luxtrace/core/math.hpp"
#include "luxtrace/detector/cylinder.hpp"
#include "luxtrace/detector/sensor_points.hpp"

#include <optional>
#include <string>
#include <vector>

namespace luxtrace {

// cylindrical / semicylindrical: a grid of points, each the centre of a small cylinder
// whose axis is the grid's normal (cylinder.hpp). points: sensors of a Radiance .pts file,
// each a small disc counting illuminance (sensor_points.hpp); cells i = 0..n-1, ny = 1.
enum class DetectorType { illuminance, luminance, cylindrical, semicylindrical, points };

// The name a scene file and a result file give the type.
const char* detector_type_name(DetectorType type);

// A named rectangle of cells of an illuminance detector (a task area of EN 12464-1),
// [i0, i1) x [j0, j1), 0-based, i along nx and j along ny like a run target's range.
struct TaskArea {
    std::string name;
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
};

// EN 17037's daylight-factor targets in percent (a detector's en17037 key): D_T, to be
// exceeded over 50 % of the cells, and the minimum target D_TM, over 95 % of them.
struct En17037Targets {
    double target_df = 0.0;
    double minimum_df = 0.0;
};

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
    // cylindrical, semicylindrical: the small cylinder at every cell centre, and the
    // illuminance detector on the same grid whose values give the modelling ratio.
    // points: radius_m is each sensor disc's radius.
    double radius_m = 0.01, height_m = 0.2;  // the loader's defaults (detector_loader.cpp says why)
    Vec3 facing{1, 0, 0};                    // semicylindrical: the curved half faces this way
    std::string horizontal;                  // name of that detector, or empty
    int horizontal_index = -1;               // its index in Scene::detectors, or -1
    CylinderShape cylinder;                  // derived: the cylinder in the grid's frame (u, v, normal)
    std::vector<TaskArea> task_areas;        // illuminance only: areas with their own metrics
    // Illuminance: count only photons that have scattered at least once (not the direct
    // flight from a light), as an observer's eye detector does for UGR's background.
    bool indirect_only = false;
    // Illuminance: also store DF = E / E_h,ext (stats/daylight_metrics.hpp), and judge it
    // against EN 17037 when `en17037` is set (which implies daylight_factor).
    bool daylight_factor = false;
    std::optional<En17037Targets> en17037;
    // >= 0: the eye detector of Scene::observers[observer], stored with the observer in
    // the result (/observers/NAME), not among the user's detectors.
    int observer = -1;
    // points: the sensors (positions, directions, the plane index), and the .pts file as
    // the scene names it.
    SensorPoints sensors;
    std::string points_file;

    // Set derived fields (axes, cone) from the user's values; call after filling them.
    void finalize();
    int cells() const { return nx * ny; }
    // points: a sensor disc's pi r^2.
    double cell_area_m2() const {
        return type == DetectorType::points ? kPi * radius_m * radius_m : size_u * size_v / (nx * ny);
    }
    bool cylinders() const { return type == DetectorType::cylindrical || type == DetectorType::semicylindrical; }
    // The curved surface a point's value is the mean illuminance on: 2 pi r h, or pi r h
    // for the half cylinder.
    double lateral_area_m2() const {
        return (type == DetectorType::semicylindrical ? 1.0 : 2.0) * kPi * radius_m * height_m;
    }
    // The cone's projected solid angle, integral of cos(gamma) d omega over the cone:
    // cos(theta) pi sin^2(a), exact while the cone stays above the plane (theta + a <= 90
    // degrees), since cos(gamma) is linear in the direction and the cone is symmetric.
    double projected_solid_angle_sr() const { return cos_view() * kPi * (1.0 - cos_half_angle * cos_half_angle); }
    double cos_view() const { return glm::dot(cone_axis, normal); }
    // The cone dips below the detector plane: the divisor is then no longer exact.
    bool cone_below_plane() const;
    // Value of one registration (times flux per photon) per unit count: 1/A (lux) or
    // 1/(A cos(theta) pi sin^2 a) (cd/m^2): the flux a Lambertian patch of luminance L
    // sends into the cone is L A cos(theta) pi sin^2 a; cylinders: 1/lateral_area_m2().
    double value_per_lm() const;
    const char* units() const { return type == DetectorType::luminance ? "cd/m^2" : "lx"; }

    // Cell index of a point in the detector plane, or -1 outside the rectangle.
    int cell_at(const Vec3& p) const;
    // Illuminance: the cell where the ray o + t d, 0 < t <= t_max, crosses the plane from
    // the front side, or -1. `hit_normal`: the unit normal of the surface the ray ends on
    // at t_max (zero without one). A detector lying on that surface is crossed just past
    // the hit, within plane_tolerance_m; a surface across the plane (a wall standing on
    // the floor a detector lies on) stops the ray before it, however close.
    int crossing(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal) const;
    // Points: append every sensor whose disc the ray crosses from the front (same rules).
    void sensor_crossings(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal,
                          std::vector<int>& cells) const {
        sensors.crossings(o, d, t_max, hit_normal, plane_tolerance_m, cells);
    }
    // Luminance: the cell where a photon leaving point p along d registers, or -1.
    int leaving(const Vec3& p, const Vec3& d) const;
    // Cylinders: append to `cells` every point whose cylinder the ray o + t d,
    // 0 < t <= t_max, enters through its lateral surface from outside (through the
    // facing half for semicylindrical). Only the points whose cylinders the ray's piece
    // inside the grid's slab |z - z0| <= h/2 can reach are tested.
    void cylinder_entries(const Vec3& o, const Vec3& d, double t_max, std::vector<int>& cells) const;
};

}  // namespace luxtrace
