#pragma once
// The analytic illuminance under an isotropic point source, for the tests of detectors
// under a lamp (points_test, sensor_table_test): at (x, y) from the source's foot on a
// plane h below it, E = I h / r^3, and its means over a disc and a square by midpoint sums.
#include "luxtrace/core/math.hpp"

#include <cmath>

namespace luxtrace::test_support {

inline double point_e(double intensity, double h, double x, double y) {
    const double r2 = x * x + y * y + h * h;
    return intensity * h / (r2 * std::sqrt(r2));
}

inline double disc_average(double intensity, double h, double cx, double cy, double radius) {
    constexpr int kRings = 200, kSectors = 256;
    double sum = 0.0, area = 0.0;
    for (int a = 0; a < kRings; ++a) {
        const double rho = (a + 0.5) / kRings * radius;
        for (int b = 0; b < kSectors; ++b) {
            const double phi = (b + 0.5) / kSectors * 2.0 * kPi;
            sum += rho * point_e(intensity, h, cx + rho * std::cos(phi), cy + rho * std::sin(phi));
            area += rho;
        }
    }
    return sum / area;
}

inline double square_average(double intensity, double h, double cx, double cy, double side) {
    constexpr int kSub = 200;
    double sum = 0.0;
    for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b)
            sum += point_e(intensity, h, cx + ((a + 0.5) / kSub - 0.5) * side, cy + ((b + 0.5) / kSub - 0.5) * side);
    return sum / (kSub * kSub);
}

}  // namespace luxtrace::test_support
