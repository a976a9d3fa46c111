#include "luxtrace/light/sky_model.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace luxtrace {

namespace {

// ISO 15469:2004 / CIE S 011/E:2003, table 1: gradation groups I-VI (a, b) crossed with
// indicatrix groups 1-6 (c, d, e).
constexpr std::array<CieSkyParameters, 15> kCieGeneralSkies{{
    {4.0, -0.70, 0.0, -1.0, 0.00},    // 1  overcast, steep gradation, azimuthal uniformity
    {4.0, -0.70, 2.0, -1.5, 0.15},    // 2  overcast, steep gradation, slight brightening to sun
    {1.1, -0.80, 0.0, -1.0, 0.00},    // 3  overcast, moderate gradation, azimuthal uniformity
    {1.1, -0.80, 2.0, -1.5, 0.15},    // 4  overcast, moderate gradation, brightening to sun
    {0.0, -1.00, 0.0, -1.0, 0.00},    // 5  sky of uniform luminance
    {0.0, -1.00, 2.0, -1.5, 0.15},    // 6  partly cloudy, no gradation, slight brightening
    {0.0, -1.00, 5.0, -2.5, 0.30},    // 7  partly cloudy, no gradation, brighter circumsolar
    {0.0, -1.00, 10.0, -3.0, 0.45},   // 8  partly cloudy, no gradation, distinct corona
    {-1.0, -0.55, 2.0, -1.5, 0.15},   // 9  partly cloudy, obscured sun
    {-1.0, -0.55, 5.0, -2.5, 0.30},   // 10 partly cloudy, brighter circumsolar region
    {-1.0, -0.55, 10.0, -3.0, 0.45},  // 11 white-blue sky, distinct solar corona
    {-1.0, -0.32, 10.0, -3.0, 0.45},  // 12 CIE standard clear sky, low turbidity
    {-1.0, -0.32, 16.0, -3.0, 0.30},  // 13 CIE standard clear sky, polluted atmosphere
    {-1.0, -0.15, 16.0, -3.0, 0.30},  // 14 cloudless turbid sky, broad solar corona
    {-1.0, -0.15, 24.0, -2.8, 0.15},  // 15 white-blue turbid sky, broad solar corona
}};

constexpr int kTraditionalOvercast = 16;
constexpr int kUniform = 0;

// Adaptive Gauss-Kronrod (15 points, error from the embedded 7-point Gauss rule),
// bisecting until the estimated error is below tol times the integral of |f|.
template <class F>
double adaptive(const F& f, double a, double b, double tol) {
    return boost::math::quadrature::gauss_kronrod<double, 15>::integrate(f, a, b, 12, tol);
}

// The interval's breakpoints: its ends and every alpha + 2 pi k strictly inside it.
std::vector<double> breakpoints(double lo, double hi, double alpha) {
    std::vector<double> b{lo};
    for (double x = alpha - 2.0 * kPi * std::ceil((alpha - lo) / (2.0 * kPi)); x < hi; x += 2.0 * kPi)
        if (x > lo) b.push_back(x);
    b.push_back(hi);
    return b;
}

}  // namespace

CieSkyParameters cie_general_sky_parameters(int cie_type) {
    if (cie_type < 1 || cie_type > 15)
        throw std::invalid_argument("CIE general sky type " + std::to_string(cie_type) + " is not 1 to 15");
    return kCieGeneralSkies[static_cast<std::size_t>(cie_type - 1)];
}

Vec3 sky_direction(double zenith_rad, double azimuth_rad) {
    const double s = std::sin(zenith_rad);
    return {s * std::sin(azimuth_rad), s * std::cos(azimuth_rad), std::cos(zenith_rad)};
}

SkyModel::SkyModel(int type, CieSkyParameters p, double sun_zenith_rad, double sun_azimuth_rad)
    : type_(type), p_(p), sun_zenith_rad_(sun_zenith_rad), sun_azimuth_rad_(sun_azimuth_rad),
      sun_direction_(sky_direction(sun_zenith_rad, sun_azimuth_rad)),
      indicatrix_offset_(type == kPerezType ? 0.0 : std::exp(p.d * 0.5 * kPi)) {
    if (sun_dependent()) {
        const double zenith = indicatrix(sun_zenith_rad_) * gradation(1.0);
        if (!(zenith > 0.0)) throw std::invalid_argument("the sky's zenith luminance is not positive");
        norm_ = 1.0 / zenith;
    }
}

SkyModel SkyModel::cie(int cie_type, double sun_zenith_rad, double sun_azimuth_rad) {
    if (cie_type == kTraditionalOvercast) return SkyModel(cie_type, {}, 0.0, 0.0);
    const CieSkyParameters p = cie_general_sky_parameters(cie_type);
    if (!(sun_zenith_rad >= 0.0 && sun_zenith_rad <= 0.5 * kPi) || !std::isfinite(sun_azimuth_rad))
        throw std::invalid_argument("the sun's zenith angle must lie in [0, 90] deg for a CIE "
                                    "general sky");
    return SkyModel(cie_type, p, sun_zenith_rad, sun_azimuth_rad);
}

SkyModel SkyModel::uniform() { return SkyModel(kUniform, {}, 0.0, 0.0); }

SkyModel SkyModel::perez(CieSkyParameters p, double sun_zenith_rad, double sun_azimuth_rad) {
    if (!(sun_zenith_rad >= 0.0 && sun_zenith_rad <= 0.5 * kPi) || !std::isfinite(sun_azimuth_rad))
        throw std::invalid_argument("the sun's zenith angle must lie in [0, 90] deg for a Perez sky");
    if (!(std::isfinite(p.a) && std::isfinite(p.b) && std::isfinite(p.c) && std::isfinite(p.d) && std::isfinite(p.e)))
        throw std::invalid_argument("a Perez sky parameter is not finite");
    return SkyModel(kPerezType, p, sun_zenith_rad, sun_azimuth_rad);
}

// Gradation phi(Z) = 1 + a exp(b / cos Z), phi(pi/2) = 1 (S 011 eq. 3; phi(0), eq. 4).
double SkyModel::gradation(double cos_zenith) const {
    if (cos_zenith <= 0.0) return 1.0;
    return 1.0 + p_.a * std::exp(p_.b / cos_zenith);
}

// Scattering indicatrix f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi (eq. 5;
// f(Z_s), eq. 6); Perez 1993 (eq. 1) has no exp(d pi/2) term.
double SkyModel::indicatrix(double chi_rad) const { return indicatrix(chi_rad, std::cos(chi_rad)); }

double SkyModel::indicatrix(double chi_rad, double cos_chi) const {
    return 1.0 + p_.c * (std::exp(p_.d * chi_rad) - indicatrix_offset_) + p_.e * cos_chi * cos_chi;
}

double SkyModel::luminance_at(double cos_z, double cos_chi) const {
    if (type_ == kUniform) return 1.0;
    if (type_ == kTraditionalOvercast) return (1.0 + 2.0 * cos_z) / 3.0;  // L_z (1 + 2 sin h) / 3
    cos_chi = std::clamp(cos_chi, -1.0, 1.0);
    // L / L_z = f(chi) phi(Z) / (f(Z_s) phi(0)) (eq. 1). Perez's fitted parameters can
    // drive lv below 0 near the horizon in a few bins; a luminance is not negative.
    const double l = indicatrix(std::acos(cos_chi), cos_chi) * gradation(cos_z) * norm_;
    return type_ == kPerezType ? std::max(l, 0.0) : l;
}

double SkyModel::relative_luminance(double zenith_rad, double azimuth_rad) const {
    if (zenith_rad > 0.5 * kPi) return 0.0;
    const double cos_z = std::cos(zenith_rad);
    // Angular distance chi between the element and the sun (eq. 2).
    const double cos_chi = std::cos(sun_zenith_rad_) * cos_z +
                           std::sin(sun_zenith_rad_) * std::sin(zenith_rad) * std::cos(azimuth_rad - sun_azimuth_rad_);
    return luminance_at(cos_z, cos_chi);
}

double SkyModel::relative_luminance(const Vec3& dir) const {
    // The same angles from the direction itself: no angle is computed but chi (the sky's
    // patch means call this some ten million times a year of hours).
    const double r = glm::length(dir);
    if (!(r > 0.0) || dir.z < 0.0) return 0.0;
    return luminance_at(dir.z / r, glm::dot(dir, sun_direction_) / r);
}

// Nested adaptive Gauss-Kronrod over the zenith angle (outer) and azimuth (inner). The
// integrand is smooth but for a cone-shaped kink at the sun (chi is not differentiable
// there) and the weight's cut-offs, so the sun's zenith angle splits the outer interval,
// its azimuth the inner one, and the cut-offs are interval ends: each piece is then
// smooth or has its kink at an end, where the adaptive bisection converges.
template <class Weight>
double SkyModel::integrate(double alpha0_rad, double alpha1_rad, const Weight& w) const {
    constexpr double kInnerTol = 1e-9, kOuterTol = 1e-8;
    const bool sunny = sun_dependent();
    const std::vector<double> alpha_cuts = sunny ? breakpoints(alpha0_rad, alpha1_rad, sun_azimuth_rad_)
                                                 : std::vector<double>{alpha0_rad, alpha1_rad};
    const auto ring = [&](double zenith) {
        double sum = 0.0;
        for (std::size_t i = 0; i + 1 < alpha_cuts.size(); ++i)
            sum += adaptive([&](double alpha) { return relative_luminance(zenith, alpha) * w(zenith, alpha); },
                            alpha_cuts[i], alpha_cuts[i + 1], kInnerTol);
        return sum * std::sin(zenith);
    };
    std::vector<double> zenith_cuts{0.0};
    if (sunny && sun_zenith_rad_ > 0.0 && sun_zenith_rad_ < 0.5 * kPi) zenith_cuts.push_back(sun_zenith_rad_);
    zenith_cuts.push_back(0.5 * kPi);
    double total = 0.0;
    for (std::size_t i = 0; i + 1 < zenith_cuts.size(); ++i)
        total += adaptive(ring, zenith_cuts[i], zenith_cuts[i + 1], kOuterTol);
    return total;
}

double SkyModel::horizontal_illuminance_per_zenith_luminance_sr() const {
    // The sky is symmetric about the sun's vertical plane: one half, doubled.
    const double a0 = sun_azimuth_rad_;
    return 2.0 * integrate(a0, a0 + kPi, [](double zenith, double) { return std::cos(zenith); });
}

double SkyModel::vertical_illuminance_per_zenith_luminance_sr(double facing_azimuth_rad) const {
    // The plane sees the quarter sphere within 90 deg of its normal; cos of the incidence
    // angle is sin Z cos(alpha - facing).
    return integrate(facing_azimuth_rad - 0.5 * kPi, facing_azimuth_rad + 0.5 * kPi,
                     [facing_azimuth_rad](double zenith, double alpha) {
                         return std::sin(zenith) * std::cos(alpha - facing_azimuth_rad);
                     });
}

}  // namespace luxtrace
