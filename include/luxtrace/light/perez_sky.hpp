#pragma once
// The Perez all-weather sky (docs/DAYLIGHT.md, "The Perez all-weather sky"): one hour's
// sky from the sun's position, the diffuse horizontal and direct normal irradiances and the
// dew point, as Radiance's gendaylit builds it.
//  - Sky clearness epsilon and brightness Delta: Perez et al. 1990 (Solar Energy 44),
//    eqs. 1 and 2, with Kasten's relative air mass and Spencer's eccentricity factor.
//  - Luminous efficacies of the diffuse and direct light: Perez et al. 1990, table 4,
//    with the precipitable water from the dew point (ibid., W = exp(0.07 Td - 0.075) cm).
//  - Luminance distribution: Perez, Seals & Michalsky 1993 (Solar Energy 50), eq. 1 and
//    table 1 (with the 1993 erratum, Solar Energy 51), five parameters a..e per clearness bin.
// Directions and angles as in light/sky_model.hpp.
#include "luxtrace/light/sky_model.hpp"

namespace luxtrace {

// The eight sky-clearness bins of Perez 1990/1993, 1 (overcast) to 8 (clear), with lower
// bounds 1, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2; epsilon below 1 falls in bin 1.
int perez_clearness_bin(double epsilon);

// Perez 1990 eq. 1: epsilon = ((E_d + E_n) / E_d + 1.041 Z^3) / (1 + 1.041 Z^3), Z in rad.
double perez_sky_clearness(double diffuse_horizontal_w_m2, double direct_normal_w_m2, double sun_zenith_rad);
// Perez 1990 eq. 2: Delta = E_d m / E_0n, with m Kasten's relative optical air mass and
// E_0n the extraterrestrial normal irradiance (1367 W/m2 times the eccentricity factor).
double perez_sky_brightness(double diffuse_horizontal_w_m2, double sun_zenith_rad, int day_of_year);
// Kasten (1966): m = 1 / (cos Z + 0.15 (93.885 - Z_deg)^-1.253).
double relative_air_mass(double sun_zenith_rad);
// Spencer (1971): (r0 / r)^2 on day 1-366.
double eccentricity_factor(int day_of_year);
// 1 January = 1 (Gregorian; 29 February counts in a leap year).
int day_of_year(int year, int month, int day);
// Perez 1990: W = exp(0.07 Td - 0.075), in cm.
double precipitable_water_cm(double dew_point_c);

// Perez 1990, table 4, in lm/W: diffuse a + b W + c cos Z + d ln Delta, direct normal
// a + b W + c exp(5.73 Z - 5) + d Delta (not below 0).
double perez_diffuse_efficacy_lm_w(double epsilon, double delta, double sun_zenith_rad, double precipitable_water_cm);
double perez_direct_efficacy_lm_w(double epsilon, double delta, double sun_zenith_rad, double precipitable_water_cm);

// One row of Perez 1993, table 1 (bin 1-8): for each of a..e the four x1..x4 of
// x = x1 + x2 Z + Delta (x3 + x4 Z). Throws std::invalid_argument for another bin.
struct PerezTableRow {
    double a[4], b[4], c[4], d[4], e[4];
};
const PerezTableRow& perez_luminance_table_row(int bin);

// The five parameters of the luminance distribution for this hour (Perez 1993, eqs. 6-8;
// in bin 1, c = exp((Delta (c1 + c2 Z))^c3) - c4 and d = -exp(Delta (d1 + d2 Z)) + d3 +
// Delta d4). As gendaylit, Delta is raised to 0.2 in bins 2-5 (1.065 < epsilon < 2.8).
CieSkyParameters perez_luminance_parameters(double epsilon, double delta, double sun_zenith_rad);

struct PerezSkyInput {
    double sun_zenith_rad = 0.0;           // in [0, 90 deg)
    double sun_azimuth_rad = 0.0;          // clockwise from north
    double diffuse_horizontal_w_m2 = 0.0;  // > 0
    double direct_normal_w_m2 = 0.0;       // >= 0
    double dew_point_c = 0.0;
    int day_of_year = 150;  // 1-366, for the eccentricity factor (gendaylit -ang's default)
};

// The fitted ranges of the model (gendaylit's): epsilon in [1, 12), Delta in [0.01, 0.6].
// Values outside are clamped into them for the distribution and efficacies, and the
// clamping is reported.
class PerezSky {
public:
    // Throws std::invalid_argument for a sun at or below the horizon, a zenith angle
    // outside [0, 90) deg, a diffuse irradiance not > 0, a direct one < 0, a non-finite
    // dew point or a day outside 1-366.
    // normalise = false skips the integration that sets the zenith luminance (then 0): for
    // callers that scale the distribution themselves (annual skies, 4,000 hours at a time).
    explicit PerezSky(const PerezSkyInput& in, bool normalise = true);

    double epsilon() const { return epsilon_; }  // as computed from the input, unclamped
    double delta() const { return delta_; }
    int clearness_bin() const { return perez_clearness_bin(epsilon_); }
    bool clamped() const { return clamped_; }  // epsilon or Delta was outside the fitted range

    double diffuse_efficacy_lm_w() const { return diffuse_efficacy_lm_w_; }
    double direct_efficacy_lm_w() const { return direct_efficacy_lm_w_; }
    double diffuse_horizontal_illuminance_lx() const { return diffuse_horizontal_illuminance_lx_; }
    double direct_normal_illuminance_lx() const { return direct_normal_illuminance_lx_; }

    // The distribution as L / L_z (SkyModel::perez) and its zenith luminance, chosen so
    // that the sky's horizontal illuminance is the diffuse horizontal illuminance.
    const SkyModel& model() const { return model_; }
    double zenith_luminance_cd_m2() const { return zenith_luminance_cd_m2_; }
    double luminance_cd_m2(double zenith_rad, double azimuth_rad) const {
        return zenith_luminance_cd_m2_ * model_.relative_luminance(zenith_rad, azimuth_rad);
    }

private:
    double epsilon_ = 1.0, delta_ = 0.0;
    bool clamped_ = false;
    double diffuse_efficacy_lm_w_ = 0.0, direct_efficacy_lm_w_ = 0.0;
    double diffuse_horizontal_illuminance_lx_ = 0.0, direct_normal_illuminance_lx_ = 0.0;
    SkyModel model_;
    double zenith_luminance_cd_m2_ = 0.0;
};

}  // namespace luxtrace
