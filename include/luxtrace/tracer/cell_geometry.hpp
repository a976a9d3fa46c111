#pragma once
// Where a sensor grid's cell samples the scene from and which way it faces: a points grid's
// sensor is its point, an illuminance grid's cell is sampled over its area. Shared by the
// rays cast from the cells (direct_daylight.hpp, sensor_gather.hpp).
#include "luxtrace/core/math.hpp"
#include "luxtrace/detector/detector.hpp"

#include <cstddef>
#include <vector>

namespace luxtrace {

// A cell's position (at (u1, u2) of its area), normal and corners.
struct CellGeometry {
    const Detector& d;
    bool point() const { return d.type == DetectorType::points; }
    Vec3 normal(std::size_t cell) const { return point() ? d.sensors.directions()[cell] : d.normal; }
    Vec3 position(std::size_t cell, double u1, double u2) const {
        if (point()) return d.sensors.positions()[cell];
        const int i = static_cast<int>(cell) % d.nx, j = static_cast<int>(cell) / d.nx;
        const double a = (i + u1) / d.nx - 0.5, b = (j + u2) / d.ny - 0.5;
        return d.center + a * d.size_u * d.u_axis + b * d.size_v * d.v_axis;
    }
    // The cell's corners (a point sensor: its point): every sample lies in their hull.
    std::vector<Vec3> corners(std::size_t cell) const {
        if (point()) return {position(cell, 0.0, 0.0)};
        return {position(cell, 0.0, 0.0), position(cell, 1.0, 0.0), position(cell, 0.0, 1.0), position(cell, 1.0, 1.0)};
    }
};

}  // namespace luxtrace
