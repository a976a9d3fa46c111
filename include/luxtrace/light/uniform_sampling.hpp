#pragma once
// Uniform points and directions from uniforms in [0, 1): what every light kind draws its
// photons' starting points and directions with.
#include "luxtrace/core/math.hpp"

#include <cstddef>
#include <vector>

namespace luxtrace {

// Uniform direction on the unit sphere and inside a cone around +z (local frame).
Vec3 sample_uniform_sphere(double u1, double u2);
Vec3 sample_uniform_cone(double cos_max, double u1, double u2);
// Uniform point on the disk of `radius` around the origin in the z = 0 plane.
Vec3 disk_point(double radius, double u1, double u2);
// disk_point with the angle's sine and cosine taken in float: positions good to 1e-7 of
// the radius (what Embree's float origins keep), at a fraction of the double calls' cost;
// for the sky's per-photon disks.
Vec3 disk_point_f(double radius, double u1, double u2);
// Index of the first cdf entry > u (cdf normalised, last entry 1).
std::size_t sample_cdf(const std::vector<double>& cdf, double u);

}  // namespace luxtrace
