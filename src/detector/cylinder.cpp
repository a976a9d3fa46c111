#include "luxtrace/detector/cylinder.hpp"

#include <cmath>

namespace luxtrace {

double lateral_entry(const CylinderShape& c, const Vec3& o, const Vec3& d, double t_max) {
    // |o_xy + t d_xy|^2 = r^2: a t^2 + 2 b t + k = 0.
    const double a = d.x * d.x + d.y * d.y;
    const double b = o.x * d.x + o.y * d.y;
    const double k = o.x * o.x + o.y * o.y - c.radius_m * c.radius_m;
    // Inside or on the infinite cylinder (k <= 0) the distance to the axis can only grow
    // past r; moving away (b >= 0, which also covers rays along the axis) it never shrinks.
    if (k <= 0.0 || b >= 0.0) return -1.0;
    const double disc = b * b - a * k;
    if (disc <= 0.0) return -1.0;  // passes by, or touches it tangentially
    // The smaller root (-b - sqrt(disc)) / a, written without cancellation; > 0 as k > 0.
    const double t = k / (std::sqrt(disc) - b);
    if (!(t <= t_max)) return -1.0;
    if (!(std::abs(o.z + t * d.z) <= 0.5 * c.height_m)) return -1.0;
    // The half cylinder: the entry point's outward normal is its offset from the axis.
    if (c.half && (o.x + t * d.x) * c.facing_x + (o.y + t * d.y) * c.facing_y < 0.0) return -1.0;
    return t;
}

}  // namespace luxtrace
