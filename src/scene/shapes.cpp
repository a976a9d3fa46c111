#include "luxtrace/scene/shapes.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

Vec3 default_up(const Vec3& normal) {
    const Vec3 n = glm::normalize(normal);
    return std::abs(n.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
}

TriangleMesh make_rectangle(const Vec3& center, const Vec3& normal, const Vec3& up, double size_u, double size_v,
                            int subdivisions) {
    const Vec3 n = glm::normalize(normal);
    const Vec3 u = glm::normalize(glm::cross(up, n));
    const Vec3 v = glm::cross(n, u);
    const int s = std::max(1, subdivisions);
    TriangleMesh m;
    m.vertices.reserve(std::size_t(s + 1) * (s + 1));
    m.triangles.reserve(2 * std::size_t(s) * s);
    for (int j = 0; j <= s; ++j)
        for (int i = 0; i <= s; ++i)
            m.vertices.push_back(center + (double(i) / s - 0.5) * size_u * u + (double(j) / s - 0.5) * size_v * v);
    for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i) {
            const unsigned a = j * (s + 1) + i, b = a + 1, c = a + s + 2, d = a + s + 1;
            m.triangles.push_back({a, b, c});  // u x v = n: counter-clockwise from the front
            m.triangles.push_back({a, c, d});
        }
    return m;
}

TriangleMesh make_box(const Vec3& center, const Vec3& size, int subdivisions, bool inward) {
    // Each face is the rectangle make_rectangle would make, but every coordinate comes
    // from one table per axis, so that faces meeting at an edge share its vertices bit
    // for bit: the box is watertight for Embree (no crack between faces to escape by).
    const int s = std::max(1, subdivisions);
    const Vec3 lo = center - 0.5 * size, hi = center + 0.5 * size;
    std::vector<double> grid[3];
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k <= s; ++k)
            grid[a].push_back(k == 0 ? lo[a] : k == s ? hi[a] : lo[a] + (hi[a] - lo[a]) * (double(k) / s));
    const int sign = inward ? -1 : 1;
    TriangleMesh m;
    m.vertices.reserve(6 * std::size_t(s + 1) * (s + 1));
    m.triangles.reserve(12 * std::size_t(s) * s);
    for (int axis = 0; axis < 3; ++axis)
        for (int dir = -1; dir <= 1; dir += 2) {
            // The face's "up" is the next axis but one, its u axis (up x normal) the next
            // axis, pointing along +axis when the face's normal does.
            const int up_axis = (axis + 2) % 3, other_axis = (axis + 1) % 3;
            const bool u_forward = sign * dir > 0;
            const auto base = static_cast<unsigned>(m.vertices.size());
            for (int j = 0; j <= s; ++j)
                for (int i = 0; i <= s; ++i) {
                    Vec3 p;
                    p[axis] = dir > 0 ? hi[axis] : lo[axis];
                    p[other_axis] = grid[other_axis][u_forward ? i : s - i];
                    p[up_axis] = grid[up_axis][j];
                    m.vertices.push_back(p);
                }
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i) {
                    const unsigned a = base + j * (s + 1) + i, b = a + 1, c = a + s + 2, d = a + s + 1;
                    m.triangles.push_back({a, b, c});  // u x v = n: counter-clockwise from the front
                    m.triangles.push_back({a, c, d});
                }
        }
    return m;
}

TriangleMesh make_sphere(const Vec3& center, double radius, int subdivisions, bool inward) {
    // Latitude-longitude sphere: `stacks` bands from pole to pole, 2*stacks segments.
    const int stacks = std::max(3, subdivisions);
    const int slices = 2 * stacks;
    TriangleMesh m;
    m.vertices.reserve(std::size_t(stacks + 1) * slices);
    m.triangles.reserve(2 * std::size_t(stacks - 1) * slices);
    for (int j = 0; j <= stacks; ++j) {
        const double theta = kPi * j / stacks;
        for (int i = 0; i < slices; ++i) {
            const double phi = 2.0 * kPi * i / slices;
            m.vertices.push_back(center + radius * Vec3(std::sin(theta) * std::cos(phi),
                                                        std::sin(theta) * std::sin(phi), std::cos(theta)));
        }
    }
    auto idx = [&](int j, int i) { return static_cast<unsigned>(j * slices + (i % slices)); };
    auto add = [&](unsigned a, unsigned b, unsigned c) {
        if (inward) m.triangles.push_back({a, c, b});
        else m.triangles.push_back({a, b, c});
    };
    for (int j = 0; j < stacks; ++j)
        for (int i = 0; i < slices; ++i) {
            // Outward winding: going down in theta (j+1) and around in phi (i+1).
            if (j > 0) add(idx(j, i), idx(j + 1, i), idx(j, i + 1));
            if (j < stacks - 1) add(idx(j, i + 1), idx(j + 1, i), idx(j + 1, i + 1));
        }
    return m;
}

TriangleMesh make_disk(const Vec3& center, const Vec3& normal, double radius, int subdivisions) {
    const Frame f = Frame::around(glm::normalize(normal));
    const int rings = std::max(1, subdivisions);
    const int slices = std::max(12, 8 * rings);
    TriangleMesh m;
    m.vertices.push_back(center);
    for (int r = 1; r <= rings; ++r)
        for (int i = 0; i < slices; ++i) {
            const double phi = 2.0 * kPi * i / slices;
            m.vertices.push_back(center + radius * r / rings * f.to_world(Vec3(std::cos(phi), std::sin(phi), 0)));
        }
    auto idx = [&](int r, int i) { return r == 0 ? 0u : static_cast<unsigned>(1 + (r - 1) * slices + (i % slices)); };
    for (int i = 0; i < slices; ++i) m.triangles.push_back({idx(0, 0), idx(1, i), idx(1, i + 1)});
    for (int r = 1; r < rings; ++r)
        for (int i = 0; i < slices; ++i) {
            m.triangles.push_back({idx(r, i), idx(r + 1, i), idx(r + 1, i + 1)});
            m.triangles.push_back({idx(r, i), idx(r + 1, i + 1), idx(r, i + 1)});
        }
    return m;
}

}  // namespace luxtrace
