#pragma once
// The sun's position in the sky for a site and a local standard time, by NREL's Solar
// Position Algorithm (I. Reda and A. Andreas, "Solar position algorithm for solar
// radiation applications", NREL/TP-560-34302, 2003, revised 2008; docs/DAYLIGHT.md).
// SPA is stated to within +-0.0003 deg in zenith and azimuth for the years -2000 to 6000
// (given the right delta_t); it reproduces the paper's worked example to its printed
// digits. Equation numbers in src/light/sun_position.cpp are the paper's.
//
// Angles in degrees. Azimuths clockwise from north (90 east, 180 south), as everywhere in
// luxtrace. Longitudes east positive; the UTC offset is that of standard time, east
// positive (UTC-7 is -7), so the UT is the local time minus the offset.

#include <array>

namespace luxtrace {

// A civil date and time, independent of any parser: proleptic Gregorian from 1582-10-15,
// Julian calendar before (SPA eq. 4).
struct LocalStandardTime {
    int year = 2000;
    int month = 1;              // 1..12
    int day = 1;                // 1..31
    int hour = 0;               // 0..24
    int minute = 0;             // 0..59
    double second = 0.0;        // [0, 61): leap seconds allowed
    double utc_offset_h = 0.0;  // standard time zone, east positive, [-18, 18]
};

// Where the sun is seen from and the air it is seen through.
struct SunSite {
    double latitude_deg = 0.0;       // north positive, [-90, 90]
    double longitude_deg = 0.0;      // EAST positive, [-180, 180]
    double elevation_m = 0.0;        // above the reference ellipsoid
    double pressure_mbar = 1013.25;  // annual mean local pressure, > 0
    double temperature_c = 12.0;     // annual mean local temperature, > -273.15
    double delta_t_s = 69.0;         // TT - UT1 in seconds (69.2 s for 2020)
    // Refraction at sunrise and sunset: below an unrefracted altitude of -(sun radius +
    // this) no refraction is added, since the sun's upper limb is then below the horizon.
    double atmospheric_refraction_deg = 0.5667;
};

// The intermediate values of SPA, named as in the paper, for checking against its Table
// A5.1 (all in degrees unless stated).
struct SpaIntermediates {
    double julian_day = 0.0;                   // JD (UT), eq. 4
    double julian_ephemeris_day = 0.0;         // JDE, eq. 5
    double heliocentric_longitude = 0.0;       // L, eqs. 9-12
    double heliocentric_latitude = 0.0;        // B
    double radius_au = 0.0;                    // R, Earth-sun distance
    double geocentric_longitude = 0.0;         // Theta, eq. 13
    double geocentric_latitude = 0.0;          // beta, eq. 14
    double nutation_longitude = 0.0;           // delta psi, eq. 22
    double nutation_obliquity = 0.0;           // delta epsilon, eq. 23
    double true_obliquity = 0.0;               // epsilon, eq. 25
    double aberration = 0.0;                   // delta tau, eq. 26
    double apparent_longitude = 0.0;           // lambda, eq. 27
    double sidereal_time = 0.0;                // nu, eq. 29 (apparent, Greenwich)
    double right_ascension = 0.0;              // alpha, eq. 30
    double declination = 0.0;                  // delta, eq. 31
    double hour_angle = 0.0;                   // H, eq. 32 (westward from south)
    double topocentric_right_ascension = 0.0;  // alpha', eq. 38
    double topocentric_declination = 0.0;      // delta', eq. 39
    double topocentric_hour_angle = 0.0;       // H', eq. 40
    double elevation_unrefracted = 0.0;        // e0, eq. 41
    double refraction = 0.0;                   // delta e, eq. 42
};

struct SunPosition {
    double zenith_deg = 0.0;    // topocentric, refraction corrected (eq. 44)
    double azimuth_deg = 0.0;   // clockwise from north, [0, 360) (eq. 46)
    double altitude_deg = 0.0;  // 90 - zenith_deg: the refracted elevation above the horizon
    bool above_horizon() const { return altitude_deg > 0.0; }
    SpaIntermediates spa;
};

// Throws std::invalid_argument naming the field out of range (month, day, hour, minute,
// second, utc_offset_h, latitude_deg, longitude_deg, pressure_mbar, temperature_c).
SunPosition sun_position(const LocalStandardTime& time, const SunSite& site);

// The sums of eqs. 9-10 for each power of JME (L0..L5, B0..B1, R0..R4, in 1e-8 rad or
// 1e-8 AU), for a Julian ephemeris millennium: what Table A5.1 prints.
struct EarthPeriodicSums {
    std::array<double, 6> l{};
    std::array<double, 2> b{};
    std::array<double, 5> r{};
};
EarthPeriodicSums earth_periodic_sums(double julian_ephemeris_millennium);

// SPA eq. 4 for a UT date with the day's fraction in `day` (e.g. 2.521180556 for the 2nd
// at 12:30:30 UT).
double julian_day(int year, int month, double day);

}  // namespace luxtrace
