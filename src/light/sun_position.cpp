#include "luxtrace/light/sun_position.hpp"

#include "luxtrace/core/math.hpp"

#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

namespace luxtrace {
namespace {

// One periodic term A cos(B + C JME) of the Earth's heliocentric series (Table A4.2;
// A in 1e-8 rad or AU, B in rad, C in rad per Julian millennium).
struct PeriodicTerm {
    double a, b, c;
};

constexpr PeriodicTerm kL0[] = {{175347046, 0, 0},           {3341656, 4.6692568, 6283.07585},
                                {34894, 4.6261, 12566.1517}, {3497, 2.7441, 5753.3849},
                                {3418, 2.8289, 3.5231},      {3136, 3.6277, 77713.7715},
                                {2676, 4.4181, 7860.4194},   {2343, 6.1352, 3930.2097},
                                {1324, 0.7425, 11506.7698},  {1273, 2.0371, 529.691},
                                {1199, 1.1096, 1577.3435},   {990, 5.233, 5884.927},
                                {902, 2.045, 26.298},        {857, 3.508, 398.149},
                                {780, 1.179, 5223.694},      {753, 2.533, 5507.553},
                                {505, 4.583, 18849.228},     {492, 4.205, 775.523},
                                {357, 2.92, 0.067},          {317, 5.849, 11790.629},
                                {284, 1.899, 796.298},       {271, 0.315, 10977.079},
                                {243, 0.345, 5486.778},      {206, 4.806, 2544.314},
                                {205, 1.869, 5573.143},      {202, 2.458, 6069.777},
                                {156, 0.833, 213.299},       {132, 3.411, 2942.463},
                                {126, 1.083, 20.775},        {115, 0.645, 0.98},
                                {103, 0.636, 4694.003},      {102, 0.976, 15720.839},
                                {102, 4.267, 7.114},         {99, 6.21, 2146.17},
                                {98, 0.68, 155.42},          {86, 5.98, 161000.69},
                                {85, 1.3, 6275.96},          {85, 3.67, 71430.7},
                                {80, 1.81, 17260.15},        {79, 3.04, 12036.46},
                                {75, 1.76, 5088.63},         {74, 3.5, 3154.69},
                                {74, 4.68, 801.82},          {70, 0.83, 9437.76},
                                {62, 3.98, 8827.39},         {61, 1.82, 7084.9},
                                {57, 2.78, 6286.6},          {56, 4.39, 14143.5},
                                {56, 3.47, 6279.55},         {52, 0.19, 12139.55},
                                {52, 1.33, 1748.02},         {51, 0.28, 5856.48},
                                {49, 0.49, 1194.45},         {41, 5.37, 8429.24},
                                {41, 2.4, 19651.05},         {39, 6.17, 10447.39},
                                {37, 6.04, 10213.29},        {37, 2.57, 1059.38},
                                {36, 1.71, 2352.87},         {36, 1.78, 6812.77},
                                {33, 0.59, 17789.85},        {30, 0.44, 83996.85},
                                {30, 2.74, 1349.87},         {25, 3.16, 4690.48}};
constexpr PeriodicTerm kL1[] = {{628331966747, 0, 0},       {206059, 2.678235, 6283.07585},
                                {4303, 2.6351, 12566.1517}, {425, 1.59, 3.523},
                                {119, 5.796, 26.298},       {109, 2.966, 1577.344},
                                {93, 2.59, 18849.23},       {72, 1.14, 529.69},
                                {68, 1.87, 398.15},         {67, 4.41, 5507.55},
                                {59, 2.89, 5223.69},        {56, 2.17, 155.42},
                                {45, 0.4, 796.3},           {36, 0.47, 775.52},
                                {29, 2.65, 7.11},           {21, 5.34, 0.98},
                                {19, 1.85, 5486.78},        {19, 4.97, 213.3},
                                {17, 2.99, 6275.96},        {16, 0.03, 2544.31},
                                {16, 1.43, 2146.17},        {15, 1.21, 10977.08},
                                {12, 2.83, 1748.02},        {12, 3.26, 5088.63},
                                {12, 5.27, 1194.45},        {12, 2.08, 4694},
                                {11, 0.77, 553.57},         {10, 1.3, 6286.6},
                                {10, 4.24, 1349.87},        {9, 2.7, 242.73},
                                {9, 5.64, 951.72},          {8, 5.3, 2352.87},
                                {6, 2.65, 9437.76},         {6, 4.67, 4690.48}};
constexpr PeriodicTerm kL2[] =
    {{52919, 0, 0},      {8720, 1.0721, 6283.0758}, {309, 0.867, 12566.152}, {27, 0.05, 3.52},   {16, 5.19, 26.3},
     {16, 3.68, 155.42}, {10, 0.76, 18849.23},      {9, 2.06, 77713.77},     {7, 0.83, 775.52},  {5, 4.66, 1577.34},
     {4, 1.03, 7.11},    {4, 3.44, 5573.14},        {3, 5.14, 796.3},        {3, 6.05, 5507.55}, {3, 1.19, 242.73},
     {3, 6.12, 529.69},  {3, 0.31, 398.15},         {3, 2.28, 553.57},       {2, 4.38, 5223.69}, {2, 3.75, 0.98}};
constexpr PeriodicTerm kL3[] = {{289, 5.844, 6283.076}, {35, 0, 0},         {17, 5.49, 12566.15}, {3, 5.2, 155.42},
                                {1, 4.72, 3.52},        {1, 5.3, 18849.23}, {1, 5.97, 242.73}};
constexpr PeriodicTerm kL4[] = {{114, 3.142, 0}, {8, 4.13, 6283.08}, {1, 3.84, 12566.15}};
constexpr PeriodicTerm kL5[] = {{1, 3.14, 0}};

constexpr PeriodicTerm kB0[] = {{280, 3.199, 84334.662},
                                {102, 5.422, 5507.553},
                                {80, 3.88, 5223.69},
                                {44, 3.7, 2352.87},
                                {32, 4, 1577.34}};
constexpr PeriodicTerm kB1[] = {{9, 3.9, 5507.55}, {6, 1.73, 5223.69}};

constexpr PeriodicTerm kR0[] = {{100013989, 0, 0},
                                {1670700, 3.0984635, 6283.07585},
                                {13956, 3.05525, 12566.1517},
                                {3084, 5.1985, 77713.7715},
                                {1628, 1.1739, 5753.3849},
                                {1576, 2.8469, 7860.4194},
                                {925, 5.453, 11506.77},
                                {542, 4.564, 3930.21},
                                {472, 3.661, 5884.927},
                                {346, 0.964, 5507.553},
                                {329, 5.9, 5223.694},
                                {307, 0.299, 5573.143},
                                {243, 4.273, 11790.629},
                                {212, 5.847, 1577.344},
                                {186, 5.022, 10977.079},
                                {175, 3.012, 18849.228},
                                {110, 5.055, 5486.778},
                                {98, 0.89, 6069.78},
                                {86, 5.69, 15720.84},
                                {86, 1.27, 161000.69},
                                {65, 0.27, 17260.15},
                                {63, 0.92, 529.69},
                                {57, 2.01, 83996.85},
                                {56, 5.24, 71430.7},
                                {49, 3.25, 2544.31},
                                {47, 2.58, 775.52},
                                {45, 5.54, 9437.76},
                                {43, 6.01, 6275.96},
                                {39, 5.36, 4694},
                                {38, 2.39, 8827.39},
                                {37, 0.83, 19651.05},
                                {37, 4.9, 12139.55},
                                {36, 1.67, 12036.46},
                                {35, 1.84, 2942.46},
                                {33, 0.24, 7084.9},
                                {32, 0.18, 5088.63},
                                {32, 1.78, 398.15},
                                {28, 1.21, 6286.6},
                                {28, 1.9, 6279.55},
                                {26, 4.59, 10447.39}};
constexpr PeriodicTerm kR1[] = {{103019, 1.10749, 6283.07585},
                                {1721, 1.0644, 12566.1517},
                                {702, 3.142, 0},
                                {32, 1.02, 18849.23},
                                {31, 2.84, 5507.55},
                                {25, 1.32, 5223.69},
                                {18, 1.42, 1577.34},
                                {10, 5.91, 10977.08},
                                {9, 1.42, 6275.96},
                                {9, 0.27, 5486.78}};
constexpr PeriodicTerm kR2[] = {{4359, 5.7846, 6283.0758}, {124, 5.579, 12566.152}, {12, 3.14, 0},
                                {9, 3.63, 77713.77},       {6, 1.87, 5573.14},      {3, 5.47, 18849.23}};
constexpr PeriodicTerm kR3[] = {{145, 4.273, 6283.076}, {7, 3.92, 12566.15}};
constexpr PeriodicTerm kR4[] = {{4, 2.56, 6283.08}};

// One row of Table A4.3: the multiples Y of X0..X4 (D, M, M', F, Omega) and the
// coefficients a, b (longitude) and c, d (obliquity) in 0.0001 arc seconds.
struct NutationTerm {
    std::array<int, 5> y;
    double a, b, c, d;
};

constexpr NutationTerm kNutation[] = {{{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9},
                                      {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
                                      {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},
                                      {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
                                      {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},
                                      {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
                                      {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},
                                      {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
                                      {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},
                                      {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
                                      {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
                                      {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
                                      {{0, 0, -1, 2, 2}, 123, 0, -53, 0},
                                      {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
                                      {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},
                                      {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
                                      {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
                                      {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
                                      {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},
                                      {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
                                      {{2, 0, 0, 2, 2}, -38, 0, 16, 0},
                                      {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
                                      {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
                                      {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
                                      {{0, 0, 0, 2, 0}, 26, 0, 0, 0},
                                      {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
                                      {{0, 0, -1, 2, 1}, 21, 0, -10, 0},
                                      {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
                                      {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
                                      {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
                                      {{0, 1, 0, 0, 1}, -15, 0, 9, 0},
                                      {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
                                      {{0, -1, 0, 0, 1}, -12, 0, 6, 0},
                                      {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
                                      {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
                                      {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
                                      {{0, 1, 0, 2, 2}, 7, 0, -3, 0},
                                      {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
                                      {{0, -1, 0, 2, 2}, -7, 0, 3, 0},
                                      {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
                                      {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
                                      {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
                                      {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},
                                      {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
                                      {{2, 0, 0, 0, 1}, -6, 0, 3, 0},
                                      {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
                                      {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
                                      {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
                                      {{0, 0, 2, 2, 1}, -5, 0, 3, 0},
                                      {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
                                      {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},
                                      {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
                                      {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
                                      {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
                                      {{1, 0, 0, 0, 0}, -4, 0, 0, 0},
                                      {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
                                      {{0, 0, -2, 2, 2}, -3, 0, 0, 0},
                                      {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
                                      {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
                                      {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
                                      {{2, -1, -1, 2, 2}, -3, 0, 0, 0},
                                      {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
                                      {{2, -1, 0, 2, 2}, -3, 0, 0, 0}};
static_assert(std::size(kNutation) == 63);

double rad(double deg) { return deg * kPi / 180.0; }
double deg(double rad) { return rad * 180.0 / kPi; }

// Step 3.2.6: an angle limited to [0, 360).
double limit_360(double deg) {
    const double limited = std::fmod(deg, 360.0);
    return limited < 0.0 ? limited + 360.0 : limited;
}

// Eqs. 9-10: the sum over one table of A cos(B + C JME).
double periodic_sum(std::span<const PeriodicTerm> terms, double jme) {
    double sum = 0.0;
    for (const PeriodicTerm& t : terms) sum += t.a * std::cos(t.b + t.c * jme);
    return sum;
}

// Eq. 11: the sums as a polynomial in JME, / 1e8, in rad (L, B) or AU (R).
template <std::size_t N>
double earth_series(const std::array<double, N>& sums, double jme) {
    double total = 0.0;
    for (std::size_t i = N; i-- > 0;) total = total * jme + sums[i];
    return total / 1e8;
}

void require(bool ok, const char* field, const std::string& expected) {
    if (!ok) throw std::invalid_argument(std::string("sun position: ") + field + " " + expected);
}

void check(const LocalStandardTime& t, const SunSite& s) {
    require(t.month >= 1 && t.month <= 12, "month", "must be 1 to 12");
    require(t.day >= 1 && t.day <= 31, "day", "must be 1 to 31");
    require(t.hour >= 0 && t.hour <= 24, "hour", "must be 0 to 24");
    require(t.minute >= 0 && t.minute <= 59, "minute", "must be 0 to 59");
    require(t.second >= 0.0 && t.second < 61.0, "second", "must be in [0, 61)");
    require(std::abs(t.utc_offset_h) <= 18.0, "utc_offset_h", "must be -18 to 18");
    require(std::abs(s.latitude_deg) <= 90.0, "latitude_deg", "must be -90 to 90");
    require(std::abs(s.longitude_deg) <= 180.0, "longitude_deg", "must be -180 to 180");
    require(s.pressure_mbar > 0.0 && std::isfinite(s.pressure_mbar), "pressure_mbar", "must be positive");
    require(s.temperature_c > -273.15 && std::isfinite(s.temperature_c), "temperature_c", "must be above -273.15");
    require(std::isfinite(s.elevation_m) && std::isfinite(s.delta_t_s) && std::isfinite(s.atmospheric_refraction_deg),
            "elevation_m, delta_t_s or atmospheric_refraction_deg", "must be finite");
}

}  // namespace

EarthPeriodicSums earth_periodic_sums(double jme) {
    const std::span<const PeriodicTerm> l[] = {kL0, kL1, kL2, kL3, kL4, kL5};
    const std::span<const PeriodicTerm> b[] = {kB0, kB1};
    const std::span<const PeriodicTerm> r[] = {kR0, kR1, kR2, kR3, kR4};
    EarthPeriodicSums sums;
    for (std::size_t i = 0; i < sums.l.size(); ++i) sums.l[i] = periodic_sum(l[i], jme);
    for (std::size_t i = 0; i < sums.b.size(); ++i) sums.b[i] = periodic_sum(b[i], jme);
    for (std::size_t i = 0; i < sums.r.size(); ++i) sums.r[i] = periodic_sum(r[i], jme);
    return sums;
}

double julian_day(int year, int month, double day) {
    if (month <= 2) {  // January and February count as months 13 and 14 of the year before
        year -= 1;
        month += 12;
    }
    // Eq. 4; INT truncates toward zero.
    const double jd = std::trunc(365.25 * (year + 4716.0)) + std::trunc(30.6001 * (month + 1)) + day - 1524.5;
    if (jd < 2299160.0) return jd;  // Julian calendar: B = 0
    const double a = std::trunc(year / 100.0);
    return jd + 2.0 - a + std::trunc(a / 4.0);
}

namespace {

// The time scales of one instant (3.1).
struct TimeScales {
    double jd;   // Julian day (UT), eq. 4
    double jde;  // Julian ephemeris day, eq. 5
    double jc;   // Julian century, eq. 6
    double jce;  // Julian ephemeris century, eq. 7
    double jme;  // Julian ephemeris millennium, eq. 8
};

// 3.1: time scales. The day's fraction in UT: local standard time minus its offset.
TimeScales time_scales(const LocalStandardTime& time, const SunSite& site) {
    const double day = time.day + (time.hour - time.utc_offset_h + (time.minute + time.second / 60.0) / 60.0) / 24.0;
    TimeScales t;
    t.jd = julian_day(time.year, time.month, day);
    t.jde = t.jd + site.delta_t_s / 86400.0;  // eq. 5
    t.jc = (t.jd - 2451545.0) / 36525.0;      // eq. 6
    t.jce = (t.jde - 2451545.0) / 36525.0;    // eq. 7
    t.jme = t.jce / 10.0;                     // eq. 8
    return t;
}

// 3.2: the Earth's heliocentric position (eqs. 9-12, Table A4.2).
void heliocentric_position(double jme, SpaIntermediates& s) {
    const EarthPeriodicSums sums = earth_periodic_sums(jme);
    s.heliocentric_longitude = limit_360(deg(earth_series(sums.l, jme)));
    s.heliocentric_latitude = deg(earth_series(sums.b, jme));
    s.radius_au = earth_series(sums.r, jme);
}

// 3.3: geocentric.
void geocentric_position(SpaIntermediates& s) {
    s.geocentric_longitude = limit_360(s.heliocentric_longitude + 180.0);  // eq. 13
    s.geocentric_latitude = -s.heliocentric_latitude;                      // eq. 14
}

// 3.4: nutation (eqs. 15-23, Table A4.3).
void nutation(double jce, SpaIntermediates& s) {
    const double jce2 = jce * jce, jce3 = jce2 * jce;
    const std::array<double, 5> x = {297.85036 + 445267.111480 * jce - 0.0019142 * jce2 + jce3 / 189474.0,  // eq. 15
                                     357.52772 + 35999.050340 * jce - 0.0001603 * jce2 - jce3 / 300000.0,   // eq. 16
                                     134.96298 + 477198.867398 * jce + 0.0086972 * jce2 + jce3 / 56250.0,   // eq. 17
                                     93.27191 + 483202.017538 * jce - 0.0036825 * jce2 + jce3 / 327270.0,   // eq. 18
                                     125.04452 - 1934.136261 * jce + 0.0020708 * jce2 + jce3 / 450000.0};   // eq. 19
    double sum_psi = 0.0, sum_eps = 0.0;
    for (const NutationTerm& t : kNutation) {
        double arg = 0.0;
        for (int j = 0; j < 5; ++j) arg += x[j] * t.y[j];
        sum_psi += (t.a + t.b * jce) * std::sin(rad(arg));  // eq. 20
        sum_eps += (t.c + t.d * jce) * std::cos(rad(arg));  // eq. 21
    }
    s.nutation_longitude = sum_psi / 36000000.0;  // eq. 22
    s.nutation_obliquity = sum_eps / 36000000.0;  // eq. 23
}

// 3.5-3.7: the true obliquity of the ecliptic, the aberration correction and the sun's
// apparent longitude.
void apparent_longitude(double jme, SpaIntermediates& s) {
    // 3.5: eq. 24 in arc seconds, U = JME/10.
    constexpr double kObliquity[] = {84381.448, -4680.93, -1.55, 1999.25, -51.38, -249.67,
                                     -39.05,    7.12,     27.87, 5.79,    2.45};
    const double u = jme / 10.0;
    double eps0 = 0.0;
    for (int i = std::size(kObliquity) - 1; i >= 0; --i) eps0 = eps0 * u + kObliquity[i];
    s.true_obliquity = eps0 / 3600.0 + s.nutation_obliquity;  // eq. 25

    s.aberration = -20.4898 / (3600.0 * s.radius_au);                                     // eq. 26
    s.apparent_longitude = s.geocentric_longitude + s.nutation_longitude + s.aberration;  // eq. 27
}

// 3.8: apparent sidereal time at Greenwich.
void sidereal_time(const TimeScales& t, SpaIntermediates& s) {
    const double jc = t.jc;
    const double nu0 = limit_360(280.46061837 + 360.98564736629 * (t.jd - 2451545.0) + 0.000387933 * jc * jc -
                                 jc * jc * jc / 38710000.0);  // eq. 28
    const double eps = rad(s.true_obliquity);
    s.sidereal_time = nu0 + s.nutation_longitude * std::cos(eps);  // eq. 29
}

// 3.9-3.10: geocentric right ascension and declination.
void geocentric_equatorial(SpaIntermediates& s) {
    const double eps = rad(s.true_obliquity);
    const double lambda = rad(s.apparent_longitude), beta = rad(s.geocentric_latitude);
    s.right_ascension = limit_360(deg(
        std::atan2(std::sin(lambda) * std::cos(eps) - std::tan(beta) * std::sin(eps), std::cos(lambda))));  // eq. 30
    s.declination = deg(
        std::asin(std::sin(beta) * std::cos(eps) + std::cos(beta) * std::sin(eps) * std::sin(lambda)));  // eq. 31
}

// The sun as the observer sees it, in radians: what 3.14 and 3.15 start from.
struct Topocentric {
    double declination;  // delta', eq. 39
    double hour_angle;   // H', eq. 40
};

// 3.12-3.13: parallax of the observer on the Earth's surface.
Topocentric topocentric_position(const SunSite& site, SpaIntermediates& s) {
    const double xi = rad(8.794 / (3600.0 * s.radius_au));  // eq. 33
    const double phi = rad(site.latitude_deg);
    const double uu = std::atan(0.99664719 * std::tan(phi));                        // eq. 34 (1 - flattening)
    const double xx = std::cos(uu) + site.elevation_m / 6378140.0 * std::cos(phi);  // eq. 35
    const double yy = 0.99664719 * std::sin(uu) + site.elevation_m / 6378140.0 * std::sin(phi);  // eq. 36
    const double h = rad(s.hour_angle), delta = rad(s.declination);
    const double d_alpha = std::atan2(-xx * std::sin(xi) * std::sin(h),
                                      std::cos(delta) - xx * std::sin(xi) * std::cos(h));  // eq. 37
    s.topocentric_right_ascension = s.right_ascension + deg(d_alpha);                      // eq. 38
    const double delta_p = std::atan2((std::sin(delta) - yy * std::sin(xi)) * std::cos(d_alpha),
                                      std::cos(delta) - xx * std::sin(xi) * std::cos(h));  // eq. 39
    s.topocentric_declination = deg(delta_p);
    s.topocentric_hour_angle = s.hour_angle - deg(d_alpha);  // eq. 40
    return {delta_p, rad(s.topocentric_hour_angle)};
}

// 3.14: elevation and zenith, refraction corrected.
void elevation(const SunSite& site, const Topocentric& topo, SunPosition& out) {
    SpaIntermediates& s = out.spa;
    const double phi = rad(site.latitude_deg), delta_p = topo.declination, h_p = topo.hour_angle;
    const double e0 = deg(
        std::asin(std::sin(phi) * std::sin(delta_p) + std::cos(phi) * std::cos(delta_p) * std::cos(h_p)));  // eq. 41
    constexpr double kSunRadiusDeg = 0.26667;
    s.elevation_unrefracted = e0;
    s.refraction = 0.0;
    if (e0 >= -(kSunRadiusDeg + site.atmospheric_refraction_deg)) {
        s.refraction = site.pressure_mbar / 1010.0 * 283.0 / (273.0 + site.temperature_c) * 1.02 /
                       (60.0 * std::tan(rad(e0 + 10.3 / (e0 + 5.11))));  // eq. 42
    }
    out.altitude_deg = e0 + s.refraction;      // eq. 43
    out.zenith_deg = 90.0 - out.altitude_deg;  // eq. 44
}

// 3.15: azimuth; Gamma from south westward (eq. 45), Phi from north eastward (eq. 46).
double azimuth(const SunSite& site, const Topocentric& topo) {
    const double phi = rad(site.latitude_deg), delta_p = topo.declination, h_p = topo.hour_angle;
    const double gamma = deg(
        std::atan2(std::sin(h_p), std::cos(h_p) * std::sin(phi) - std::tan(delta_p) * std::cos(phi)));
    return limit_360(gamma + 180.0);
}

}  // namespace

SunPosition sun_position(const LocalStandardTime& time, const SunSite& site) {
    check(time, site);
    SunPosition out;
    SpaIntermediates& s = out.spa;
    const TimeScales t = time_scales(time, site);  // 3.1
    s.julian_day = t.jd;
    s.julian_ephemeris_day = t.jde;
    heliocentric_position(t.jme, s);  // 3.2
    geocentric_position(s);           // 3.3
    nutation(t.jce, s);               // 3.4
    apparent_longitude(t.jme, s);     // 3.5-3.7
    sidereal_time(t, s);              // 3.8
    geocentric_equatorial(s);         // 3.9-3.10
    // 3.11: local hour angle, westward from south.
    s.hour_angle = limit_360(s.sidereal_time + site.longitude_deg - s.right_ascension);  // eq. 32
    const Topocentric topo = topocentric_position(site, s);                              // 3.12-3.13
    elevation(site, topo, out);                                                          // 3.14
    out.azimuth_deg = azimuth(site, topo);                                               // 3.15
    return out;
}

}  // namespace luxtrace
