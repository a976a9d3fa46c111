#include "daylight_reference.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace luxtrace::daylight_reference {
namespace {

// The part of `poly` where dot(x - origin, m) >= 0 (Sutherland-Hodgman, one plane).
Polygon clip(const Polygon& poly, const Vec3& origin, const Vec3& m) {
    Polygon out;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& a = poly[i];
        const Vec3& b = poly[(i + 1) % n];
        const double da = glm::dot(a - origin, m), db = glm::dot(b - origin, m);
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
}

double area(const Polygon& poly) {
    Vec3 s(0.0);
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) s += glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    return 0.5 * glm::length(s);
}

Vec3 plane_normal(const Polygon& poly) {
    Vec3 s(0.0);
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) s += glm::cross(poly[i] - poly[0], poly[i + 1] - poly[0]);
    return glm::normalize(s);
}

// Keeps pieces with an area above a negligible fraction of the opening's.
void keep(std::vector<Polygon>& pieces, Polygon p, double min_area) {
    if (p.size() >= 3 && area(p) > min_area) pieces.push_back(std::move(p));
}

// The pieces of `piece` outside the cone that `point` sees `obstruction` in: each edge of
// the obstruction and the point span a plane; what lies outside one of those planes is
// visible, what lies inside all of them is hidden.
std::vector<Polygon> cut_out(const Polygon& piece, const Vec3& point, const Polygon& obstruction, double min_area) {
    Vec3 centroid(0.0);
    for (const Vec3& v : obstruction) centroid += v;
    centroid /= static_cast<double>(obstruction.size());
    std::vector<Polygon> visible;
    Polygon remaining = piece;
    for (std::size_t i = 0; i < obstruction.size() && remaining.size() >= 3; ++i) {
        Vec3 m = glm::cross(obstruction[i] - point, obstruction[(i + 1) % obstruction.size()] - point);
        if (glm::dot(centroid - point, m) < 0.0) m = -m;
        keep(visible, clip(remaining, point, -m), min_area);
        remaining = clip(remaining, point, m);
    }
    return visible;
}

template <class F>
double adaptive(const F& f, double tol) {
    return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(f, 0.0, 1.0, 15, tol);
}

}  // namespace

Polygon rectangle(const Vec3& center, const Vec3& half_u, const Vec3& half_v) {
    return {center - half_u - half_v, center + half_u - half_v, center + half_u + half_v, center - half_u + half_v};
}

std::vector<Polygon> visible_pieces(const Vec3& point, const Vec3& normal, const Polygon& opening,
                                    const std::vector<Polygon>& obstructions) {
    const double min_area = 1e-14 * area(opening);
    std::vector<Polygon> pieces;
    keep(pieces, clip(clip(opening, point, Vec3(0.0, 0.0, 1.0)), point, normal), min_area);
    for (const Polygon& obstruction : obstructions) {
        std::vector<Polygon> next;
        for (const Polygon& p : pieces)
            for (Polygon& v : cut_out(p, point, obstruction, min_area)) next.push_back(std::move(v));
        pieces = std::move(next);
    }
    return pieces;
}

double illuminance_per_zenith_luminance_sr(const SkyModel& sky, const SkyComponentQuery& q, double rel_tol) {
    const Vec3 n_open = plane_normal(q.opening);
    const bool sunny = sky.cie_type() >= 1 && sky.cie_type() <= 15;
    const Vec3 sun = sky_direction(sky.sun_zenith_rad(), sky.sun_azimuth_rad());
    const auto radiance_term = [&](const Vec3& x) {
        const Vec3 d = x - q.point;
        const double r2 = glm::dot(d, d), r = std::sqrt(r2);
        const Vec3 w = d / r;
        const double cos_n = glm::dot(w, q.normal), cos_o = std::abs(glm::dot(w, n_open));
        if (cos_n <= 0.0) return 0.0;
        const double t = q.transmittance ? q.transmittance(cos_o) : 1.0;
        return sky.relative_luminance(w) * cos_n * cos_o * t / r2;
    };
    double total = 0.0;
    for (const Polygon& piece : visible_pieces(q.point, q.normal, q.opening, q.obstructions)) {
        // Fan apex: the sun's image on the opening when it falls inside the piece.
        Vec3 apex = piece[0];
        bool apex_is_vertex = true;
        const double denom = glm::dot(sun, n_open);
        if (sunny && std::abs(denom) > 1e-12) {
            const double t = glm::dot(piece[0] - q.point, n_open) / denom;
            const Vec3 s = q.point + t * sun;
            bool inside = t > 0.0;
            const Vec3 pn = plane_normal(piece);
            for (std::size_t i = 0; inside && i < piece.size(); ++i)
                inside = glm::dot(glm::cross(piece[(i + 1) % piece.size()] - piece[i], s - piece[i]), pn) > 0.0;
            if (inside) apex = s, apex_is_vertex = false;
        }
        const std::size_t first = apex_is_vertex ? 1 : 0, last = apex_is_vertex ? piece.size() - 1 : piece.size();
        for (std::size_t i = first; i < last; ++i) {
            const Vec3 b = piece[i], c = piece[(i + 1) % piece.size()];
            const double jac = glm::length(glm::cross(b - apex, c - b));
            // x(u, v) = apex + u (b - apex) + u v (c - b), dA = u |(b - apex) x (c - b)| du dv.
            const auto row = [&](double u) {
                return u * adaptive([&](double v) { return radiance_term(apex + u * (b - apex) + u * v * (c - b)); },
                                    0.1 * rel_tol);
            };
            total += jac * adaptive(row, rel_tol);
        }
    }
    return total;
}

double sky_component(const SkyModel& sky, const SkyComponentQuery& q, double rel_tol) {
    return illuminance_per_zenith_luminance_sr(sky, q, rel_tol) / sky.horizontal_illuminance_per_zenith_luminance_sr();
}

double pane_transmittance(double cos_incidence, double normal_transmittance, double refractive_index) {
    const double n = refractive_index;
    const double r0 = std::pow((n - 1.0) / (n + 1.0), 2);
    if (normal_transmittance <= 0.0 || normal_transmittance > (1.0 - r0) / (1.0 + r0))
        throw std::invalid_argument("normal transmittance out of (0, (1 - R) / (1 + R)]");
    // T(0) = (1 - r0)^2 tau0 / (1 - r0^2 tau0^2), solved for tau0.
    const double a = r0 * r0 * normal_transmittance, b = (1.0 - r0) * (1.0 - r0);
    const double tau0 = (-b + std::sqrt(b * b + 4.0 * a * normal_transmittance)) / (2.0 * a);
    const double c = std::clamp(cos_incidence, 0.0, 1.0);
    if (c <= 0.0) return 0.0;
    const double sin_t = std::sqrt(1.0 - c * c) / n, cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = std::pow((c - n * cos_t) / (c + n * cos_t), 2);
    const double rp = std::pow((cos_t - n * c) / (cos_t + n * c), 2);
    const double tau = std::pow(tau0, 1.0 / cos_t);
    const auto slab = [tau](double r) { return (1.0 - r) * (1.0 - r) * tau / (1.0 - r * r * tau * tau); };
    return 0.5 * (slab(rs) + slab(rp));
}

Transmittance clear_glass_6mm() {
    return [](double cos_incidence) {
        return pane_transmittance(cos_incidence, kClearGlassNormalTransmittance, kClearGlassRefractiveIndex);
    };
}

}  // namespace luxtrace::daylight_reference
