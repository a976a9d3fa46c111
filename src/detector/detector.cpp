#include "luxtrace/detector/detector.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

const char* detector_type_name(DetectorType type) {
    switch (type) {
    case DetectorType::illuminance: return "illuminance";
    case DetectorType::luminance: return "luminance";
    case DetectorType::cylindrical: return "cylindrical";
    case DetectorType::semicylindrical: return "semicylindrical";
    case DetectorType::points: return "points";
    }
    return "unknown";
}

void Detector::finalize() {
    normal = glm::normalize(normal);
    u_axis = glm::normalize(glm::cross(up, normal));
    v_axis = glm::cross(normal, u_axis);
    cos_half_angle = std::cos(half_angle_deg * kPi / 180.0);
    const Vec3 vd = glm::normalize(view_direction);
    cone_axis = glm::dot(vd, normal) >= 0.0 ? vd : -vd;
    plane_tolerance_m = std::max(1e-4,
                                 1e-3 * (type == DetectorType::points ? 2.0 * radius_m : std::min(size_u, size_v)));
    // The facing direction across the axis (the loader refuses one along it).
    const Vec3 f = facing - glm::dot(facing, normal) * normal;
    if (glm::length(f) > 0.0) facing = glm::normalize(f);
    cylinder.radius_m = radius_m;
    cylinder.height_m = height_m;
    cylinder.half = type == DetectorType::semicylindrical;
    cylinder.facing_x = glm::dot(facing, u_axis);
    cylinder.facing_y = glm::dot(facing, v_axis);
}

double Detector::value_per_lm() const {
    if (type == DetectorType::illuminance || type == DetectorType::points) return 1.0 / cell_area_m2();
    if (cylinders()) return 1.0 / lateral_area_m2();
    return 1.0 / (cell_area_m2() * projected_solid_angle_sr());
}

bool Detector::cone_below_plane() const {
    // theta + a > 90 degrees <=> cos(theta + a) < 0.
    const double cos_t = cos_view(), sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_half_angle * cos_half_angle));
    return cos_t * cos_half_angle - sin_t * sin_a < -1e-12;
}

namespace {
// A surface within about 2.6 degrees of a detector's plane counts as the one it lies on.
constexpr double kParallelCos = 0.999;
}  // namespace

int Detector::cell_at(const Vec3& p) const {
    const Vec3 r = p - center;
    const double a = glm::dot(r, u_axis) / size_u + 0.5;
    const double b = glm::dot(r, v_axis) / size_v + 0.5;
    if (!(a >= 0.0 && a < 1.0 && b >= 0.0 && b < 1.0)) return -1;
    const int i = std::min(nx - 1, static_cast<int>(a * nx));
    const int j = std::min(ny - 1, static_cast<int>(b * ny));
    return j * nx + i;
}

int Detector::crossing(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal) const {
    const double denom = glm::dot(d, normal);
    if (denom >= 0.0) return -1;  // moving away from the front side, or parallel
    const double t = glm::dot(center - o, normal) / denom;
    // A detector lying on a surface is crossed just at the hit: allow a hair beyond it,
    // but only when the surface hit is that surface (parallel to the plane). Otherwise
    // a photon stopped by a wall within the hair of the plane would still count, and
    // sunlight on a wall's outside would leak onto the floor inside.
    if (!(t > 0.0 && t <= t_max + plane_tolerance_m)) return -1;
    if (t > t_max && std::abs(glm::dot(hit_normal, normal)) < kParallelCos) return -1;
    return cell_at(o + t * d);
}

int Detector::leaving(const Vec3& p, const Vec3& d) const {
    if (std::abs(glm::dot(p - center, normal)) > plane_tolerance_m) return -1;
    if (glm::dot(d, cone_axis) < cos_half_angle) return -1;
    return cell_at(p);
}

namespace {

// Narrows [t0, t1] to the ts where o + t d lies in [lo, hi]; false if nothing is left.
bool clip_to_slab(double o, double d, double lo, double hi, double& t0, double& t1) {
    if (d == 0.0) return o >= lo && o <= hi;
    double ta = (lo - o) / d, tb = (hi - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    return t0 <= t1;
}

}  // namespace

void Detector::cylinder_entries(const Vec3& o, const Vec3& d, double t_max, std::vector<int>& cells) const {
    // The ray in the grid's frame: x along u, y along v, z along the axis (the normal).
    // Only the piece of the flight inside the box holding every cylinder can enter one:
    // the slab |z| <= h/2 (most flights miss it: tested first) over the grid's rectangle
    // widened by the radius.
    const Vec3 r = o - center;
    double t0 = 0.0, t1 = t_max;
    const double oz = glm::dot(r, normal), dz = glm::dot(d, normal);
    if (!clip_to_slab(oz, dz, -0.5 * height_m, 0.5 * height_m, t0, t1)) return;
    const Vec3 ol(glm::dot(r, u_axis), glm::dot(r, v_axis), oz);
    const Vec3 dl(glm::dot(d, u_axis), glm::dot(d, v_axis), dz);
    const double hx = 0.5 * size_u + radius_m, hy = 0.5 * size_v + radius_m;
    if (!clip_to_slab(ol.x, dl.x, -hx, hx, t0, t1) || !clip_to_slab(ol.y, dl.y, -hy, hy, t0, t1)) return;
    // That piece seen along the axis, in cell units: point (i, j) sits at (i + 1/2, j + 1/2)
    // and its cylinder reaches r / du across and r / dv along.
    const double du = size_u / nx, dv = size_v / ny;
    const double xa = (ol.x + t0 * dl.x + 0.5 * size_u) / du, xb = (ol.x + t1 * dl.x + 0.5 * size_u) / du;
    const double ya = (ol.y + t0 * dl.y + 0.5 * size_v) / dv, yb = (ol.y + t1 * dl.y + 0.5 * size_v) / dv;
    // Walk the columns (coordinate p) of the piece's longer extent, widened by the radius
    // (pr); within a column the piece moves along the other coordinate (s) no more than
    // the column is wide (|slope| <= 1), so, widened by sr, a few points per column are
    // tested. The slack keeps rounding from dropping a point the exact test would accept.
    const bool along_x = std::abs(xb - xa) >= std::abs(yb - ya);
    double pa = along_x ? xa : ya, pb = along_x ? xb : yb, sa = along_x ? ya : xa, sb = along_x ? yb : xb;
    const double pr = (along_x ? radius_m / du : radius_m / dv) + 1e-9;
    const double sr = (along_x ? radius_m / dv : radius_m / du) + 1e-9;
    const int np = along_x ? nx : ny, ns = along_x ? ny : nx;
    if (pa > pb) {
        std::swap(pa, pb);
        std::swap(sa, sb);
    }
    const double slope = pb > pa ? (sb - sa) / (pb - pa) : 0.0;
    const int i0 = std::max(0, static_cast<int>(std::ceil(pa - 0.5 - pr)));
    const int i1 = std::min(np - 1, static_cast<int>(std::floor(pb - 0.5 + pr)));
    for (int i = i0; i <= i1; ++i) {
        const double lo = std::max(pa, i + 0.5 - pr), hi = std::min(pb, i + 0.5 + pr);
        const double s_lo = sa + slope * (lo - pa), s_hi = sa + slope * (hi - pa);
        const int j0 = std::max(0, static_cast<int>(std::ceil(std::min(s_lo, s_hi) - sr - 0.5)));
        const int j1 = std::min(ns - 1, static_cast<int>(std::floor(std::max(s_lo, s_hi) + sr - 0.5)));
        for (int j = j0; j <= j1; ++j) {
            const int ci = along_x ? i : j, cj = along_x ? j : i;
            const Vec3 oc(ol.x - ((ci + 0.5) * du - 0.5 * size_u), ol.y - ((cj + 0.5) * dv - 0.5 * size_v), ol.z);
            if (lateral_entry(cylinder, oc, dl, t_max) > 0.0) cells.push_back(cj * nx + ci);
        }
    }
}

}  // namespace luxtrace
