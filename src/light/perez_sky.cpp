#include "luxtrace/light/perez_sky.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace luxtrace {

namespace {

constexpr double kSolarConstantWM2 = 1367.0;  // as Perez 1990 and gendaylit use it
constexpr double kEpsilonMin = 1.0, kEpsilonMax = 12.0;
constexpr double kDeltaMin = 0.01, kDeltaMax = 0.6;

// Lower bounds of clearness bins 2-8 (Perez 1990, table 1; Perez 1993, table 1).
constexpr std::array<double, 7> kBinLowerBounds{1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

// Perez, Seals & Michalsky 1993, table 1 with the erratum (Solar Energy 51, 423), as
// quoted in Radiance's gendaylit.c (coeff_perez, NREL/Radiance src/gen/gendaylit.c) and
// matching the tables in Ladybug Tools and other public implementations.
constexpr std::array<PerezTableRow, 8> kLuminanceTable{{
    {{1.3525, -0.2576, -0.2690, -1.4366},
     {-0.7670, 0.0007, 1.2734, -0.1233},
     {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809},
     {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016},
     {-0.2054, 0.0367, -3.9128, 0.9156},
     {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080},
     {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156},
     {0.2782, -0.1812, -4.5000, 1.1766},
     {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204},
     {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117},
     {0.7234, -0.6219, -5.6812, 2.6297},
     {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062},
     {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250},
     {0.2937, 0.0496, -5.6812, 1.8415},
     {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988},
     {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051},
     {0.2875, -0.5328, -3.8500, 3.3750},
     {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702},
     {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119},
     {-0.3000, 0.1922, 0.7023, -1.6317},
     {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656},
     {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590},
     {-0.3250, 0.1156, 0.7781, 0.0025},
     {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234},
     {1.5000, -0.6426, 1.8564, 0.5636}},
}};

// Perez et al. 1990, table 4, per clearness bin (a, b, c, d), as quoted in gendaylit.c
// (glob_h_diffuse_effi_PEREZ, direct_n_effi_PEREZ).
struct EfficacyRow {
    double a, b, c, d;
};
constexpr std::array<EfficacyRow, 8> kDiffuseEfficacy{{
    {97.24, -0.46, 12.00, -8.91},
    {107.22, 1.15, 0.59, -3.95},
    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90},
    {100.71, 5.94, -22.75, -23.74},
    {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03},
    {152.23, 0.35, -45.27, -7.98},
}};
constexpr std::array<EfficacyRow, 8> kDirectEfficacy{{
    {57.20, -4.55, -2.98, 117.12},
    {98.99, -3.46, -1.21, 12.38},
    {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56},
    {106.36, -3.97, -1.75, -6.16},
    {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44},
    {101.18, 1.58, -1.10, -8.29},
}};

double linear(const double x[4], double zenith, double delta) {
    return x[0] + x[1] * zenith + delta * (x[2] + x[3] * zenith);
}

}  // namespace

int perez_clearness_bin(double epsilon) {
    int bin = 1;
    for (double lower : kBinLowerBounds)
        if (epsilon >= lower) ++bin;
    return bin;
}

double perez_sky_clearness(double diffuse_horizontal_w_m2, double direct_normal_w_m2, double sun_zenith_rad) {
    const double k = 1.041 * sun_zenith_rad * sun_zenith_rad * sun_zenith_rad;
    return ((diffuse_horizontal_w_m2 + direct_normal_w_m2) / diffuse_horizontal_w_m2 + k) / (1.0 + k);
}

double relative_air_mass(double sun_zenith_rad) {
    const double zenith_deg = sun_zenith_rad * 180.0 / kPi;
    return 1.0 / (std::cos(sun_zenith_rad) + 0.15 * std::pow(93.885 - zenith_deg, -1.253));
}

double eccentricity_factor(int day_of_year) {
    const double g = 2.0 * kPi * (day_of_year - 1) / 365.0;  // day angle
    return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2.0 * g) +
           0.000077 * std::sin(2.0 * g);
}

double perez_sky_brightness(double diffuse_horizontal_w_m2, double sun_zenith_rad, int day_of_year) {
    return diffuse_horizontal_w_m2 * relative_air_mass(sun_zenith_rad) /
           (kSolarConstantWM2 * eccentricity_factor(day_of_year));
}

int day_of_year(int year, int month, int day) {
    constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    return kBefore[std::clamp(month, 1, 12) - 1] + day + (leap && month > 2 ? 1 : 0);
}

double precipitable_water_cm(double dew_point_c) { return std::exp(0.07 * dew_point_c - 0.075); }

double perez_diffuse_efficacy_lm_w(double epsilon, double delta, double sun_zenith_rad, double w_cm) {
    const EfficacyRow& r = kDiffuseEfficacy[static_cast<std::size_t>(perez_clearness_bin(epsilon) - 1)];
    return r.a + r.b * w_cm + r.c * std::cos(sun_zenith_rad) + r.d * std::log(delta);
}

double perez_direct_efficacy_lm_w(double epsilon, double delta, double sun_zenith_rad, double w_cm) {
    const EfficacyRow& r = kDirectEfficacy[static_cast<std::size_t>(perez_clearness_bin(epsilon) - 1)];
    return std::max(0.0, r.a + r.b * w_cm + r.c * std::exp(5.73 * sun_zenith_rad - 5.0) + r.d * delta);
}

const PerezTableRow& perez_luminance_table_row(int bin) {
    if (bin < 1 || bin > 8)
        throw std::invalid_argument("Perez clearness bin " + std::to_string(bin) + " is not 1 to 8");
    return kLuminanceTable[static_cast<std::size_t>(bin - 1)];
}

CieSkyParameters perez_luminance_parameters(double epsilon, double delta, double sun_zenith_rad) {
    const int bin = perez_clearness_bin(epsilon);
    const PerezTableRow& x = perez_luminance_table_row(bin);
    if (bin >= 2 && bin <= 5) delta = std::max(delta, 0.2);
    const double z = sun_zenith_rad;
    CieSkyParameters p{linear(x.a, z, delta), linear(x.b, z, delta), linear(x.c, z, delta), linear(x.d, z, delta),
                       linear(x.e, z, delta)};
    if (bin == 1) {  // Perez 1993, eqs. 7 and 8
        p.c = std::exp(std::pow(delta * (x.c[0] + x.c[1] * z), x.c[2])) - x.c[3];
        p.d = -std::exp(delta * (x.d[0] + x.d[1] * z)) + x.d[2] + delta * x.d[3];
    }
    return p;
}

PerezSky::PerezSky(const PerezSkyInput& in, bool normalise) : model_(SkyModel::uniform()) {
    const double z = in.sun_zenith_rad;
    if (!(z >= 0.0 && z < 0.5 * kPi) || !std::isfinite(in.sun_azimuth_rad))
        throw std::invalid_argument("the sun's zenith angle must lie in [0, 90) deg for a Perez sky");
    if (!(in.diffuse_horizontal_w_m2 > 0.0) || !std::isfinite(in.diffuse_horizontal_w_m2))
        throw std::invalid_argument("the diffuse horizontal irradiance must be > 0 W/m2 for a Perez sky");
    if (!(in.direct_normal_w_m2 >= 0.0) || !std::isfinite(in.direct_normal_w_m2))
        throw std::invalid_argument("the direct normal irradiance must be >= 0 W/m2");
    if (!std::isfinite(in.dew_point_c)) throw std::invalid_argument("the dew point is not finite");
    if (in.day_of_year < 1 || in.day_of_year > 366) throw std::invalid_argument("the day of the year is not 1 to 366");

    epsilon_ = perez_sky_clearness(in.diffuse_horizontal_w_m2, in.direct_normal_w_m2, z);
    delta_ = perez_sky_brightness(in.diffuse_horizontal_w_m2, z, in.day_of_year);
    const double eps = std::clamp(epsilon_, kEpsilonMin, kEpsilonMax);
    const double delta = std::clamp(delta_, kDeltaMin, kDeltaMax);
    clamped_ = eps != epsilon_ || delta != delta_;

    const double w_cm = precipitable_water_cm(in.dew_point_c);
    diffuse_efficacy_lm_w_ = perez_diffuse_efficacy_lm_w(eps, delta, z, w_cm);
    direct_efficacy_lm_w_ = perez_direct_efficacy_lm_w(eps, delta, z, w_cm);
    diffuse_horizontal_illuminance_lx_ = in.diffuse_horizontal_w_m2 * diffuse_efficacy_lm_w_;
    direct_normal_illuminance_lx_ = in.direct_normal_w_m2 * direct_efficacy_lm_w_;

    model_ = SkyModel::perez(perez_luminance_parameters(eps, delta, z), z, in.sun_azimuth_rad);
    if (normalise)
        zenith_luminance_cd_m2_ = diffuse_horizontal_illuminance_lx_ /
                                  model_.horizontal_illuminance_per_zenith_luminance_sr();
}

}  // namespace luxtrace
