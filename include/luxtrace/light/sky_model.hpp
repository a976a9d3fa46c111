#pragma once
// Sky luminance distributions for daylight (docs/DAYLIGHT.md, "Sky luminance
// distributions"): the 15 CIE standard general skies of ISO 15469:2004 / CIE S 011/E:2003,
// the traditional CIE overcast sky (type 16) and a sky of uniform luminance, each as a
// luminance relative to the zenith's, L / L_z, plus the illuminances such a sky gives an
// unobstructed horizontal or vertical plane per unit zenith luminance (by quadrature).
// The Perez all-weather sky (light/perez_sky.hpp) uses the same machinery with its own
// five parameters.
//
// Directions: z up; azimuths clockwise from north seen from above, north = +y, east = +x
// (90 deg east, 180 deg south), so a direction of zenith angle Z and azimuth alpha is
// (sin Z sin alpha, sin Z cos alpha, cos Z). Angles in radians.
#include "luxtrace/core/math.hpp"

namespace luxtrace {

// The gradation (a, b) and indicatrix (c, d, e) parameters of one CIE standard general
// sky (ISO 15469:2004, table 1).
struct CieSkyParameters {
    double a, b, c, d, e;
};

// Types 1 to 15; throws std::invalid_argument for any other type.
CieSkyParameters cie_general_sky_parameters(int cie_type);

// The direction of zenith angle Z and azimuth alpha in the convention above.
Vec3 sky_direction(double zenith_rad, double azimuth_rad);

class SkyModel {
public:
    // cie_type 1-15 (the general skies, which need the sun's position: zenith angle in
    // [0, pi/2]) or 16 (the traditional overcast sky, which ignores it). Throws
    // std::invalid_argument for another type or a sun outside that range.
    static SkyModel cie(int cie_type, double sun_zenith_rad, double sun_azimuth_rad);
    static SkyModel uniform();
    // The Perez all-weather sky (Perez, Seals & Michalsky 1993), lv = (1 + a exp(b / cos Z))
    // (1 + c exp(d chi) + e cos^2 chi), clipped at 0, from its five parameters for this hour
    // (perez_luminance_parameters in light/perez_sky.hpp). Same sun range as cie().
    static SkyModel perez(CieSkyParameters p, double sun_zenith_rad, double sun_azimuth_rad);

    // L / L_z towards a sky element; 0 below the horizon. `dir` need not be normalised.
    double relative_luminance(const Vec3& dir) const;
    double relative_luminance(double zenith_rad, double azimuth_rad) const;

    // E_h / L_z in sr (lx per cd/m2): the illuminance the sky alone gives an unobstructed
    // horizontal plane, integral of (L / L_z) cos Z dOmega over the upper hemisphere.
    double horizontal_illuminance_per_zenith_luminance_sr() const;
    // E_v / L_z in sr on an unobstructed vertical plane whose normal points to
    // `facing_azimuth_rad` (the sky only; no ground).
    double vertical_illuminance_per_zenith_luminance_sr(double facing_azimuth_rad) const;

    // 1-16, 0 for the uniform sky, kPerezType for the Perez sky.
    static constexpr int kPerezType = 17;
    int cie_type() const { return type_; }
    // Whether the luminance depends on the sun's position (the general skies and Perez).
    bool sun_dependent() const { return (type_ >= 1 && type_ <= 15) || type_ == kPerezType; }
    double sun_zenith_rad() const { return sun_zenith_rad_; }
    double sun_azimuth_rad() const { return sun_azimuth_rad_; }

private:
    SkyModel(int type, CieSkyParameters p, double sun_zenith_rad, double sun_azimuth_rad);
    double gradation(double cos_zenith) const;
    double indicatrix(double chi_rad) const;
    double indicatrix(double chi_rad, double cos_chi) const;
    // L / L_z from the cosines of the element's zenith angle and of its distance to the sun.
    double luminance_at(double cos_z, double cos_chi) const;
    // Integral of (L / L_z)(Z, alpha) w(Z, alpha) sin Z over Z in [0, pi/2] and alpha in
    // [alpha0, alpha1], with the sun's zenith angle and azimuth as breakpoints.
    template <class Weight>
    double integrate(double alpha0_rad, double alpha1_rad, const Weight& w) const;

    int type_ = 0;
    CieSkyParameters p_{};
    double sun_zenith_rad_ = 0.0, sun_azimuth_rad_ = 0.0;
    Vec3 sun_direction_{0.0, 0.0, 1.0};  // sky_direction of the sun
    double indicatrix_offset_ = 0.0;     // exp(d pi / 2), 0 for Perez
    double norm_ = 1.0;                  // 1 / (f(Z_s) phi(0)), or 1 / lv(zenith) for Perez
};

}  // namespace luxtrace
