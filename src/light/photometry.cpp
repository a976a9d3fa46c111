// Goniometric tables: lookup, symmetry and flux; see photometry.hpp.
#include "luxtrace/light/photometry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kAngleTol = 1e-6;  // degrees; file angles are written with few digits

bool near(double a, double b) { return std::abs(a - b) <= kAngleTol; }

// Index i of the interval [a[i], a[i+1]] holding x (a has >= 2 entries, x clamped).
std::size_t interval(const std::vector<double>& a, double x) {
    const auto it = std::upper_bound(a.begin(), a.end(), x);
    const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - a.begin() - 1, 0));
    return std::min(i, a.size() - 2);
}

// Linear interpolation weight of x in a[i]..a[i+1].
double weight(const std::vector<double>& a, std::size_t i, double x) {
    return std::clamp((x - a[i]) / (a[i + 1] - a[i]), 0.0, 1.0);
}

// Integrals of the two hat functions of [a, b] (radians) times the solid-angle density:
// sin(t) for a colatitude (type C gamma), cos(t) for a latitude (type B H, type A V).
std::pair<double, double> hat_weights(double a, double b, bool colatitude) {
    const double w = b - a;
    if (colatitude) {
        const double ds = std::sin(b) - std::sin(a);
        return {(w * std::cos(a) - ds) / w, (ds - w * std::cos(b)) / w};
    }
    const double dc = std::cos(a) - std::cos(b);
    return {(dc - w * std::sin(a)) / w, (w * std::sin(b) - dc) / w};
}

}  // namespace

std::optional<CPlaneSymmetry> c_plane_symmetry(const std::vector<double>& h) {
    if (h.size() == 1) return CPlaneSymmetry::Rotational;
    if (h.empty()) return std::nullopt;
    if (near(h.front(), 90.0) && near(h.back(), 270.0)) return CPlaneSymmetry::Bilateral90;
    if (!near(h.front(), 0.0)) return std::nullopt;
    if (near(h.back(), 90.0)) return CPlaneSymmetry::Quadrant;
    if (near(h.back(), 180.0)) return CPlaneSymmetry::Bilateral;
    if (near(h.back(), 360.0)) return CPlaneSymmetry::Full;
    return std::nullopt;
}

const char* shape_name(LuminousOpening::Shape s) {
    using S = LuminousOpening::Shape;
    switch (s) {
    case S::point: return "point";
    case S::rectangle: return "rectangle";
    case S::ellipse: return "disk";
    case S::box: return "box";
    case S::vertical_cylinder: return "vertical cylinder";
    case S::cylinder_along_length: return "horizontal cylinder along C0-C180";
    case S::cylinder_along_width: return "horizontal cylinder along C90-C270";
    case S::ellipsoid: return "sphere";
    }
    return "?";
}

double TiltTable::at(double tilt_deg) const {
    if (angle_deg.empty()) return 1.0;
    if (angle_deg.size() == 1 || tilt_deg <= angle_deg.front()) return multiplier.front();
    if (tilt_deg >= angle_deg.back()) return multiplier.back();
    const std::size_t i = interval(angle_deg, tilt_deg);
    const double t = weight(angle_deg, i, tilt_deg);
    return (1.0 - t) * multiplier[i] + t * multiplier[i + 1];
}

CPlaneSymmetry Photometry::symmetry() const {
    if (type == PhotometricType::C)
        if (const auto s = c_plane_symmetry(horizontal_deg)) return *s;
    throw std::logic_error("Photometry: not a type C table with LM-63 horizontal angles");
}

double Photometry::table_cd(double h_deg, double v_deg) const {
    const auto& v = vertical_deg;
    const auto& h = horizontal_deg;
    if (v.size() < 2 || v_deg < v.front() - kAngleTol || v_deg > v.back() + kAngleTol) return 0.0;
    const std::size_t i = interval(v, v_deg);
    const double s = weight(v, i, v_deg);
    const auto along_v = [&](std::size_t plane) {
        return (1.0 - s) * candela_cd[plane][i] + s * candela_cd[plane][i + 1];
    };
    if (h.size() == 1) return along_v(0);
    if (h_deg < h.front() - kAngleTol || h_deg > h.back() + kAngleTol) return 0.0;
    const std::size_t j = interval(h, h_deg);
    const double t = weight(h, j, h_deg);
    return (1.0 - t) * along_v(j) + t * along_v(j + 1);
}

double Photometry::intensity_cd(double gamma_rad, double c_rad) const {
    const CPlaneSymmetry sym = symmetry();
    const double g = gamma_rad / kDeg;
    if (sym == CPlaneSymmetry::Rotational) return table_cd(0.0, g);
    double c = std::fmod(c_rad / kDeg, 360.0);
    if (c < 0.0) c += 360.0;
    // Fold c into the file's range by the mirror planes of its symmetry.
    switch (sym) {
    case CPlaneSymmetry::Quadrant:
        if (c > 270.0) c = 360.0 - c;
        else if (c > 180.0) c = c - 180.0;
        else if (c > 90.0) c = 180.0 - c;
        break;
    case CPlaneSymmetry::Bilateral:
        if (c > 180.0) c = 360.0 - c;
        break;
    case CPlaneSymmetry::Bilateral90:
        if (c < 90.0) c = 180.0 - c;
        else if (c > 270.0) c = 540.0 - c;
        break;
    default: break;
    }
    return table_cd(c, g);
}

double Photometry::intensity_cd(const Vec3& local) const {
    if (type == PhotometricType::C) {
        const double gamma = std::acos(std::clamp(local.z, -1.0, 1.0));
        return intensity_cd(gamma, std::atan2(local.y, local.x));
    }
    const auto [h, v] = photometric_angles_deg(type, local);
    return table_cd(h, v);
}

std::pair<double, double> photometric_angles_deg(PhotometricType type, const Vec3& d) {
    switch (type) {
    case PhotometricType::C: {
        double c = std::atan2(d.y, d.x) / kDeg;
        if (c < 0.0) c += 360.0;
        return {c, std::acos(std::clamp(d.z, -1.0, 1.0)) / kDeg};
    }
    case PhotometricType::B:  // latitude H about the polar axis x, V around it from z toward y
        return {std::asin(std::clamp(d.x, -1.0, 1.0)) / kDeg, std::atan2(d.y, d.z) / kDeg};
    case PhotometricType::A:  // latitude V about the polar axis y, H around it from z toward x
        return {std::atan2(d.x, d.z) / kDeg, std::asin(std::clamp(d.y, -1.0, 1.0)) / kDeg};
    }
    return {0.0, 0.0};
}

Vec3 photometric_direction(PhotometricType type, double h_deg, double v_deg) {
    const double h = h_deg * kDeg, v = v_deg * kDeg;
    switch (type) {
    case PhotometricType::C: return {std::sin(v) * std::cos(h), std::sin(v) * std::sin(h), std::cos(v)};
    case PhotometricType::B: return {std::sin(h), std::cos(h) * std::sin(v), std::cos(h) * std::cos(v)};
    case PhotometricType::A: return {std::cos(v) * std::sin(h), std::sin(v), std::cos(v) * std::cos(h)};
    }
    return {0.0, 0.0, 1.0};
}

double Photometry::flux_lm() const {
    const auto& v = vertical_deg;
    const auto& h = horizontal_deg;
    if (v.size() < 2 || h.empty()) return 0.0;
    if (type == PhotometricType::C || type == PhotometricType::A) {
        // The vertical angle carries the solid-angle density (sin gamma, cos V): per plane,
        // the exact integral of the linear interpolant; then trapezoids across planes.
        const bool colatitude = type == PhotometricType::C;
        std::vector<double> plane(h.size(), 0.0);
        for (std::size_t i = 0; i + 1 < v.size(); ++i) {
            const auto [w0, w1] = hat_weights(v[i] * kDeg, v[i + 1] * kDeg, colatitude);
            for (std::size_t k = 0; k < plane.size(); ++k)
                plane[k] += w0 * candela_cd[k][i] + w1 * candela_cd[k][i + 1];
        }
        if (plane.size() == 1) return type == PhotometricType::C ? 2.0 * kPi * plane[0] : 0.0;
        double sum = 0.0;
        for (std::size_t k = 0; k + 1 < h.size(); ++k)
            sum += 0.5 * (plane[k] + plane[k + 1]) * (h[k + 1] - h[k]) * kDeg;
        // Type C: the symmetry repeats the file's span of planes 360/span times around.
        return type == PhotometricType::C ? sum * 360.0 / (h.back() - h.front()) : sum;
    }
    // Type B: the horizontal (lateral) angle carries the density cos H.
    if (h.size() < 2) return 0.0;
    std::vector<double> row(v.size(), 0.0);
    for (std::size_t k = 0; k + 1 < h.size(); ++k) {
        const auto [w0, w1] = hat_weights(h[k] * kDeg, h[k + 1] * kDeg, false);
        for (std::size_t i = 0; i < v.size(); ++i) row[i] += w0 * candela_cd[k][i] + w1 * candela_cd[k + 1][i];
    }
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < v.size(); ++i) sum += 0.5 * (row[i] + row[i + 1]) * (v[i + 1] - v[i]) * kDeg;
    return sum;
}

}  // namespace luxtrace
