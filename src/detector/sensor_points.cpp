#include "luxtrace/detector/sensor_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace luxtrace {

namespace {

// A surface within about 2.6 degrees of a sensor's plane counts as the one it lies on
// (as for an illuminance detector, detector.cpp).
constexpr double kParallelCos = 0.999;

// An orthonormal pair spanning the plane of unit normal n.
void plane_axes(const Vec3& n, Vec3& u, Vec3& v) {
    const Vec3 helper = std::abs(n.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    u = glm::normalize(glm::cross(helper, n));
    v = glm::cross(n, u);
}

}  // namespace

std::vector<std::vector<int>> SensorPoints::group_by_plane(const std::vector<Vec3>& positions,
                                                           const std::vector<Vec3>& directions) {
    std::vector<std::vector<int>> groups;
    std::vector<Vec3> normals;
    std::vector<double> offsets;
    std::size_t last = 0;  // consecutive sensors mostly share a plane: try the last one first
    for (std::size_t k = 0; k < positions.size(); ++k) {
        const Vec3& n = directions[k];
        auto same = [&](std::size_t g) {
            return glm::dot(normals[g], n) >= kSamePlaneCos &&
                   std::abs(glm::dot(normals[g], positions[k]) - offsets[g]) <= kSamePlaneM;
        };
        std::size_t g = groups.size();
        if (!groups.empty() && same(last)) g = last;
        else
            for (std::size_t h = 0; h < groups.size(); ++h)
                if (same(h)) {
                    g = h;
                    break;
                }
        if (g == groups.size()) {
            groups.emplace_back();
            normals.push_back(n);
            offsets.push_back(glm::dot(n, positions[k]));
        }
        groups[g].push_back(static_cast<int>(k));
        last = g;
    }
    return groups;
}

// Up to this many planes are tested in turn; more go through the hierarchy.
constexpr std::size_t kFewPlanes = 4;

SensorPoints::SensorPoints(std::vector<Vec3> positions, std::vector<Vec3> directions, double radius_m)
    : positions_(std::move(positions)), directions_(std::move(directions)), radius_m_(radius_m) {
    for (const std::vector<int>& members : group_by_plane(positions_, directions_)) {
        build_plane(members);
        Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
        for (int k : members) {
            lo = glm::min(lo, positions_[static_cast<std::size_t>(k)] - Vec3(radius_m_));
            hi = glm::max(hi, positions_[static_cast<std::size_t>(k)] + Vec3(radius_m_));
        }
        plane_lo_.push_back(lo);
        plane_hi_.push_back(hi);
    }
    if (planes_.size() > kFewPlanes) build_hierarchy();
}

void SensorPoints::build_hierarchy() {
    plane_order_.resize(planes_.size());
    std::iota(plane_order_.begin(), plane_order_.end(), 0u);
    nodes_.assign(1, Node{});
    // (node, first, last) still to build; a node's two children are appended side by side.
    std::vector<std::array<std::uint32_t, 3>> todo{{0u, 0u, static_cast<std::uint32_t>(planes_.size())}};
    while (!todo.empty()) {
        const auto [node, first, last] = todo.back();
        todo.pop_back();
        Vec3 lo(std::numeric_limits<double>::infinity()), hi(-lo), clo(lo), chi(-lo);
        for (std::uint32_t k = first; k < last; ++k) {
            const std::uint32_t q = plane_order_[k];
            lo = glm::min(lo, plane_lo_[q]);
            hi = glm::max(hi, plane_hi_[q]);
            const Vec3 c = 0.5 * (plane_lo_[q] + plane_hi_[q]);
            clo = glm::min(clo, c);
            chi = glm::max(chi, c);
        }
        nodes_[node].lo = lo;
        nodes_[node].hi = hi;
        if (last - first <= 2) {
            nodes_[node].first = first;
            nodes_[node].count = last - first;
            continue;
        }
        // Split at the median of the box centres along their widest spread.
        const Vec3 spread = chi - clo;
        const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
        const std::uint32_t mid = first + (last - first) / 2;
        std::nth_element(plane_order_.begin() + first, plane_order_.begin() + mid, plane_order_.begin() + last,
                         [&](std::uint32_t a, std::uint32_t b) {
                             return plane_lo_[a][axis] + plane_hi_[a][axis] < plane_lo_[b][axis] + plane_hi_[b][axis];
                         });
        const auto child = static_cast<std::uint32_t>(nodes_.size());
        nodes_[node].first = child;
        nodes_[node].count = 0;
        nodes_.resize(nodes_.size() + 2);
        todo.push_back({child, first, mid});
        todo.push_back({child + 1, mid, last});
    }
}

void SensorPoints::build_plane(const std::vector<int>& members) {
    Plane p;
    p.normal = directions_[static_cast<std::size_t>(members.front())];
    plane_axes(p.normal, p.u, p.v);
    double offset = 0.0;
    for (int k : members) offset += glm::dot(p.normal, positions_[static_cast<std::size_t>(k)]);
    p.offset = offset / static_cast<double>(members.size());
    const std::size_t n = members.size();
    std::vector<double> cu(n), cv(n);
    for (std::size_t m = 0; m < n; ++m) {
        const Vec3& x = positions_[static_cast<std::size_t>(members[m])];
        cu[m] = glm::dot(p.u, x);
        cv[m] = glm::dot(p.v, x);
    }
    const auto [umin, umax] = std::minmax_element(cu.begin(), cu.end());
    const auto [vmin, vmax] = std::minmax_element(cv.begin(), cv.end());
    p.u0 = *umin;
    p.v0 = *vmin;
    const double eu = *umax - *umin, ev = *vmax - *vmin;
    // About one sensor a bin, but never narrower than the radius (so the 3 x 3 bins about
    // a crossing hold every disc reaching it) and never more than ~4 bins a sensor.
    p.bin_m = std::max(radius_m_, std::sqrt(std::max(eu * ev, 0.0) / static_cast<double>(n)));
    auto bins = [&](double extent) { return static_cast<double>(std::floor(extent / p.bin_m)) + 1.0; };
    while (bins(eu) * bins(ev) > 4.0 * static_cast<double>(n) + 16.0) p.bin_m *= 2.0;
    p.nu = static_cast<int>(bins(eu));
    p.nv = static_cast<int>(bins(ev));
    auto bin_of = [&](std::size_t m) {
        const int a = std::min(p.nu - 1, static_cast<int>((cu[m] - p.u0) / p.bin_m));
        const int b = std::min(p.nv - 1, static_cast<int>((cv[m] - p.v0) / p.bin_m));
        return static_cast<std::size_t>(b) * static_cast<std::size_t>(p.nu) + static_cast<std::size_t>(a);
    };
    const std::size_t nbins = static_cast<std::size_t>(p.nu) * static_cast<std::size_t>(p.nv);
    p.bin_start.assign(nbins + 1, 0);
    for (std::size_t m = 0; m < n; ++m) ++p.bin_start[bin_of(m) + 1];
    std::partial_sum(p.bin_start.begin(), p.bin_start.end(), p.bin_start.begin());
    std::vector<std::uint32_t> fill(p.bin_start.begin(), p.bin_start.end() - 1);
    p.sensors.resize(n);
    p.su.resize(n);
    p.sv.resize(n);
    for (std::size_t m = 0; m < n; ++m) {
        const std::uint32_t slot = fill[bin_of(m)]++;
        p.sensors[slot] = static_cast<std::uint32_t>(members[m]);
        p.su[slot] = cu[m];
        p.sv[slot] = cv[m];
    }
    planes_.push_back(std::move(p));
}

void SensorPoints::cross_plane(const Plane& p, const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal,
                               double tolerance_m, std::vector<int>& cells) const {
    const double denom = glm::dot(d, p.normal);
    if (denom >= 0.0) return;  // leaving the front side, or parallel
    const double t = (p.offset - glm::dot(p.normal, o)) / denom;
    // A sensor lying on the surface the ray ends on is crossed just past the hit; a
    // surface across the plane stops the ray before it (as Detector::crossing).
    if (!(t > 0.0 && t <= t_max + tolerance_m)) return;
    if (t > t_max && std::abs(glm::dot(hit_normal, p.normal)) < kParallelCos) return;
    const Vec3 x = o + t * d;
    const double qu = glm::dot(p.u, x), qv = glm::dot(p.v, x);
    const double fa = std::floor((qu - p.u0) / p.bin_m), fb = std::floor((qv - p.v0) / p.bin_m);
    if (!(fa >= -1.0 && fa <= p.nu && fb >= -1.0 && fb <= p.nv)) return;  // beyond every disc (or NaN)
    const int a0 = std::max(0, static_cast<int>(fa) - 1), a1 = std::min(p.nu - 1, static_cast<int>(fa) + 1);
    const int b0 = std::max(0, static_cast<int>(fb) - 1), b1 = std::min(p.nv - 1, static_cast<int>(fb) + 1);
    const double r2 = radius_m_ * radius_m_;
    for (int b = b0; b <= b1; ++b) {
        const std::size_t row = static_cast<std::size_t>(b) * static_cast<std::size_t>(p.nu);
        for (std::size_t s = p.bin_start[row + static_cast<std::size_t>(a0)];
             s < p.bin_start[row + static_cast<std::size_t>(a1) + 1]; ++s) {
            const double du = p.su[s] - qu, dv = p.sv[s] - qv;
            if (du * du + dv * dv <= r2) cells.push_back(static_cast<int>(p.sensors[s]));
        }
    }
}

namespace {

// Whether the segment o + t d, 0 <= t <= t_end, meets the box [lo, hi].
bool segment_meets_box(const Vec3& o, const Vec3& d, double t_end, const Vec3& lo, const Vec3& hi) {
    double t0 = 0.0, t1 = t_end;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (!(t0 <= t1)) return false;
    }
    return true;
}

}  // namespace

void SensorPoints::crossings(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal, double tolerance_m,
                             std::vector<int>& cells) const {
    if (nodes_.empty()) {
        for (const Plane& p : planes_) cross_plane(p, o, d, t_max, hit_normal, tolerance_m, cells);
        return;
    }
    // The tree splits at medians, so it is about log2(planes) deep: 64 levels hold any.
    const double t_end = t_max + tolerance_m;
    std::array<std::uint32_t, 64> stack;
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& n = nodes_[stack[--top]];
        if (!segment_meets_box(o, d, t_end, n.lo, n.hi)) continue;
        if (n.count == 0) {
            stack[top++] = n.first;
            stack[top++] = n.first + 1;
            continue;
        }
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
            cross_plane(planes_[plane_order_[k]], o, d, t_max, hit_normal, tolerance_m, cells);
    }
}

double SensorPoints::half_smallest_spacing_m(const std::vector<Vec3>& positions, const std::vector<Vec3>& directions,
                                             int* first, int* second) {
    double best = std::numeric_limits<double>::infinity();
    for (const std::vector<int>& members : group_by_plane(positions, directions)) {
        if (members.size() < 2) continue;
        // Sorted along one axis of the plane, a sweep stops comparing once the gap along
        // that axis alone exceeds the best distance so far.
        Vec3 u, v;
        plane_axes(directions[static_cast<std::size_t>(members.front())], u, v);
        std::vector<std::pair<double, int>> order;
        for (int k : members) order.emplace_back(glm::dot(u, positions[static_cast<std::size_t>(k)]), k);
        std::sort(order.begin(), order.end());
        for (std::size_t i = 0; i < order.size(); ++i)
            for (std::size_t j = i + 1; j < order.size() && order[j].first - order[i].first <= best; ++j) {
                const Vec3 r = positions[static_cast<std::size_t>(order[j].second)] -
                               positions[static_cast<std::size_t>(order[i].second)];
                const double dist = glm::length(r - glm::dot(r, directions[static_cast<std::size_t>(order[i].second)]) *
                                                        directions[static_cast<std::size_t>(order[i].second)]);
                if (dist < best) {
                    best = dist;
                    if (first) *first = std::min(order[i].second, order[j].second);
                    if (second) *second = std::max(order[i].second, order[j].second);
                }
            }
    }
    return std::isfinite(best) ? 0.5 * best : 0.0;
}

}  // namespace luxtrace
