#include "luxtrace/scene/radiance_sky.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/scene/radiance_materials.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;

// gensky.c's sky efficacy (SKYEFFICACY = D65EFFICACY, color.h) and sun efficacy (SUNEFFICACY):
// its default brightness formulas give luminance, which it divides by these.
constexpr double kGenskySkyEfficacy_lm_per_W = 203.0;
constexpr double kGenskySunEfficacy_lm_per_W = 208.0;
// The solid angle gensky's -R divides by (its 0.5 degree sun, written 5.98e-5 in gensky.c).
constexpr double kGenskySunSolidAngle_sr = 5.98e-5;
// gendaylit's default dew point: precipitable water exp(0.07 Td - 0.075) = 2 cm.
constexpr double kGendaylitDewPoint_c = 10.97353115;

// Solid angle of a distant source of full angle `angle_deg`, as Radiance's renderers take it.
double source_solid_angle_sr(double angle_deg) { return 2.0 * kPi * (1.0 - std::cos(0.5 * angle_deg * kDeg)); }

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// The site of sun.c: latitude north, longitude and standard meridian WEST, in radians;
// gensky's defaults (San Francisco).
struct RadianceSite {
    double latitude_rad = 0.66;
    double longitude_rad = 2.13;
    double meridian_rad = 120.0 * kDeg;
};

// --- The sun's position: Radiance src/gen/sun.c (the IES Lighting Handbook formulas, and
// Michalsky 1988, "The Astronomical Almanac's algorithm for approximate solar position
// (1950-2050)", Solar Energy 40(3), when a year is given). Solar time in hours; azimuth
// in radians from south, positive toward west, as Radiance's.

int day_number(int month, int day) {  // jdate(): no leap day
    constexpr int kBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
    return kBefore[month - 1] + day;
}

double solar_time_adjustment_h(int jd, const RadianceSite& s) {  // stadj(): equation of time + longitude
    return 0.170 * std::sin(4.0 * kPi / 373.0 * (jd - 80)) - 0.129 * std::sin(2.0 * kPi / 355.0 * (jd - 8)) +
           12.0 / kPi * (s.meridian_rad - s.longitude_rad);
}

double solar_declination_rad(int jd) { return 0.4093 * std::sin(2.0 * kPi / 365.0 * (jd - 81)); }  // sdec()

double solar_altitude_rad(const RadianceSite& s, double sd, double st) {  // salt()
    return std::asin(std::sin(s.latitude_rad) * std::sin(sd) -
                     std::cos(s.latitude_rad) * std::cos(sd) * std::cos(st * kPi / 12.0));
}

double solar_azimuth_rad(const RadianceSite& s, double sd, double st) {  // sazi()
    return -std::atan2(std::cos(sd) * std::sin(st * kPi / 12.0),
                       -std::cos(s.latitude_rad) * std::sin(sd) -
                           std::sin(s.latitude_rad) * std::cos(sd) * std::cos(st * kPi / 12.0));
}

double wrap(double x, double period) {
    x = std::fmod(x, period);
    return x < 0.0 ? x + period : x;
}

// Days from noon UT of 1 January 2000 (mjdate()); the hour is standard time at the meridian.
double almanac_day(int year, int month, int day, double hour, const RadianceSite& s) {
    int jd = day_number(month, day) + ((month > 2 && year % 4 == 0) ? 1 : 0);
    jd += (year - 1949) * 365 + (year - 1949) / 4;
    return jd + (hour + s.meridian_rad * 12.0 / kPi) / 24.0 + (2432916.5 - 2451545.0);
}

// Michalsky's declination (msdec()); with `solar_time_h`, also the local solar time.
double almanac_declination_rad(double mjd, const RadianceSite& s, double* solar_time_h) {
    const double mean_longitude = wrap((280.460 + 0.9856474 * mjd) * kDeg, 2.0 * kPi);
    const double mean_anomaly = wrap((357.528 + 0.9856003 * mjd) * kDeg, 2.0 * kPi);
    const double ecliptic_longitude = mean_longitude + 1.915 * kDeg * std::sin(mean_anomaly) +
                                      0.020 * kDeg * std::sin(2.0 * mean_anomaly);
    const double obliquity = (23.439 - 4e-7 * mjd) * kDeg;
    if (solar_time_h) {
        const double ra = std::atan2(std::sin(ecliptic_longitude) * std::cos(obliquity), std::cos(ecliptic_longitude));
        const double ut_h = 24.0 * (mjd - std::floor(mjd)) + 12.0;
        const double gmst_h = 6.697375 + 0.0657098242 * mjd + ut_h;
        const double lmst_h = gmst_h - s.longitude_rad * 12.0 / kPi;
        *solar_time_h = wrap(lmst_h - ra * 12.0 / kPi + 12.0, 24.0);
    }
    return std::asin(std::sin(obliquity) * std::sin(ecliptic_longitude));
}

// gensky's time zones (cvthour()): name and standard meridian, degrees west; the first
// match counts (the table lists AST, ADT and NDT twice).
struct TimeZone {
    const char* name;
    double meridian_deg;
};
constexpr TimeZone kTimeZones[] = {{"YST", 135},   {"YDT", 120},  {"PST", 120},  {"PDT", 105},   {"MST", 105},
                                   {"MDT", 90},    {"CST", 90},   {"CDT", 75},   {"EST", 75},    {"EDT", 60},
                                   {"AST", 60},    {"ADT", 45},   {"NST", 52.5}, {"NDT", 37.5},  {"GMT", 0},
                                   {"BST", -15},   {"CET", -15},  {"CEST", -30}, {"EET", -30},   {"EEST", -45},
                                   {"AST", -45},   {"ADT", -60},  {"GST", -60},  {"GDT", -75},   {"IST", -82.5},
                                   {"IDT", -97.5}, {"JST", -135}, {"NDT", -150}, {"NZST", -180}, {"NZDT", -195}};

// The command's words in order, with errors naming the line.
class ArgReader {
public:
    ArgReader(const std::vector<std::string>& words, std::string where) : words_(words), where_(std::move(where)) {}

    [[noreturn]] void fail(const std::string& what) const { throw InputError(where_ + ": " + what); }
    bool done() const { return next_ >= words_.size(); }
    const std::string& peek() const { return words_.at(next_); }
    const std::string& word(const std::string& what) {
        if (done()) fail(what + " is missing");
        return words_[next_++];
    }
    double number(const std::string& what) {
        const std::string& w = word(what);
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);
        if (w.empty() || *end != '\0' || !std::isfinite(v)) fail(what + " must be a number, got '" + w + "'");
        return v;
    }
    int integer(const std::string& what) {
        const std::string& w = word(what);
        char* end = nullptr;
        const long v = std::strtol(w.c_str(), &end, 10);
        if (w.empty() || *end != '\0' || v < -100000 || v > 100000) fail(what + " must be an integer, got '" + w + "'");
        return static_cast<int>(v);
    }

private:
    const std::vector<std::string>& words_;
    std::string where_;
    std::size_t next_ = 0;
};

// The first arguments: `-ang altitude azimuth` or `month day hour`, and the options that
// place the sun (-y, -a, -o, -m) once read.
struct When {
    bool by_angles = false;
    double altitude_rad = 0.0, azimuth_rad = 0.0;  // Radiance's: azimuth from south, toward west
    int month = 0, day = 0;
    double hour = 0.0;
    bool solar_time = false;  // "+hour"
    bool zone_given = false;  // the hour named a time zone, which overrides -m
    int year = 0;             // -y; 0 for none
    RadianceSite site;
};

// gensky reads "[+]H[.h][ZONE]" or "[+]H:MM[ZONE]" (cvthour()); gendaylit a decimal "[+]H[.h]".
void read_hour(ArgReader& a, const std::string& program, When& w) {
    const std::string s = a.word("the hour");
    w.solar_time = !s.empty() && s[0] == '+';
    const std::size_t zone_at = std::min(s.size(), s.find_first_not_of("+-0123456789.:"));
    const std::string digits = s.substr(0, zone_at), zone = s.substr(zone_at);
    const auto bad = [&](const std::string& why) { a.fail(program + ": the hour '" + s + "' " + why); };
    char* end = nullptr;
    const std::size_t colon = digits.find(':');
    if (colon != std::string::npos) {
        if (program != "gensky") bad("must be decimal hours (gendaylit reads no H:MM)");
        const std::string h = digits.substr(0, colon), m = digits.substr(colon + 1);
        const bool ok = !h.empty() && !m.empty() && h.find_first_not_of("+0123456789") == std::string::npos &&
                        m.find_first_not_of("0123456789") == std::string::npos;
        if (!ok) bad("is not H:MM");
        w.hour = std::strtod(h.c_str(), nullptr) + std::strtod(m.c_str(), nullptr) / 60.0;
    } else {
        w.hour = std::strtod(digits.c_str(), &end);
        if (digits.empty() || *end != '\0') bad("is not a number of hours");
    }
    if (!(w.hour >= 0.0 && w.hour < 24.0) && !(program == "gensky" && w.hour <= 24.0)) bad("must lie in [0, 24)");
    if (zone.empty()) return;
    if (program != "gensky") bad("has a time zone, which gendaylit does not read (give -m)");
    if (w.solar_time) bad("is solar time and has a time zone");
    std::string upper = zone;
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (const TimeZone& z : kTimeZones)
        if (upper == z.name) {
            w.site.meridian_rad = z.meridian_deg * kDeg;
            w.zone_given = true;
            return;
        }
    bad("names an unknown time zone '" + zone +
        "' (gensky knows YST PST MST CST EST AST NST GMT BST CET EET GST IST "
        "JST NZST and their daylight forms)");
}

When read_when(ArgReader& a, const std::string& program) {
    When w;
    if (a.done()) a.fail(program + " needs 'month day hour' or '-ang altitude azimuth'");
    if (a.peek() == "-ang") {
        a.word("");
        w.by_angles = true;
        w.altitude_rad = a.number(program + " -ang's altitude") * kDeg;
        w.azimuth_rad = a.number(program + " -ang's azimuth") * kDeg;
        return w;
    }
    w.month = a.integer(program + "'s month");
    if (w.month < 1 || w.month > 12) a.fail(program + ": the month must be 1 to 12, got " + std::to_string(w.month));
    w.day = a.integer(program + "'s day");
    if (w.day < 1 || w.day > 31) a.fail(program + ": the day must be 1 to 31, got " + std::to_string(w.day));
    read_hour(a, program, w);
    return w;
}

// Reads a site option (-y -a -o -m) into `w`; false if `option` is none of them.
bool read_site_option(ArgReader& a, const std::string& program, const std::string& option, When& w) {
    if (option == "-y") {
        w.year = a.integer(program + " -y");
        if (w.year != 0 && (w.year < 1 || w.year > 9999)) a.fail(program + " -y: the year must lie in 1 to 9999");
    } else if (option == "-a") {
        const double lat = a.number(program + " -a");
        if (!(std::abs(lat) <= 90.0)) a.fail(program + " -a: the latitude must lie in [-90, 90]");
        w.site.latitude_rad = lat * kDeg;
    } else if (option == "-o") {
        w.site.longitude_rad = a.number(program + " -o") * kDeg;
    } else if (option == "-m") {
        const double m = a.number(program + " -m") * kDeg;
        if (!w.zone_given) w.site.meridian_rad = m;  // a time zone overrides, as in gensky
    } else {
        return false;
    }
    return true;
}

// The sun's altitude and Radiance azimuth for a `month day hour` form (gensky.c computesky()).
void place_sun(When& w, std::vector<std::string>& notes) {
    if (w.by_angles) return;
    double solar_time_h = w.hour, declination = 0.0;
    if (w.year != 0) {
        const double mjd = almanac_day(w.year, w.month, w.day, w.hour, w.site);
        declination = almanac_declination_rad(mjd, w.site, w.solar_time ? nullptr : &solar_time_h);
        if (w.year < 1950 || w.year > 2050)
            notes.push_back("the year " + std::to_string(w.year) +
                            " lies outside 1950-2050, the range of gensky's Michalsky formula");
    } else {
        const int jd = day_number(w.month, w.day);
        declination = solar_declination_rad(jd);
        if (!w.solar_time) solar_time_h = w.hour + solar_time_adjustment_h(jd, w.site);
    }
    w.altitude_rad = solar_altitude_rad(w.site, declination, solar_time_h);
    w.azimuth_rad = solar_azimuth_rad(w.site, declination, solar_time_h);
    if (!w.solar_time && std::abs(w.site.meridian_rad - w.site.longitude_rad) > 45.0 * kDeg)
        notes.push_back(fixed((w.site.longitude_rad - w.site.meridian_rad) * 12.0 / kPi, 1) +
                        " hours between the standard meridian and the longitude (is -m right?)");
}

void clamp_to_87(When& w, std::vector<std::string>& notes) {
    if (w.altitude_rad <= 87.0 * kDeg) return;
    notes.push_back("sun altitude " + fixed(w.altitude_rad / kDeg, 1) +
                    " deg reduced to 87 deg, as gensky and gendaylit do near the zenith");
    w.altitude_rad = 87.0 * kDeg;
}

// The sun's direction after the enclosing !xform transforms, in luxtrace's angles.
// Radiance's skies: x east, y north, z up, toward the sun (-sin A cos h, -cos A cos h, sin h)
// for azimuth A from south toward west (gensky.c). A transform that keeps z up (rotations
// about z, mirrors in x or y, uniform scale) carries the whole sky with the sun's
// direction, since every sky here is symmetric about the sun's vertical.
void orient_sun(const When& w, const glm::dmat4& transform, const ArgReader& a, double& altitude_deg,
                double& azimuth_deg) {
    Vec3 d(-std::sin(w.azimuth_rad) * std::cos(w.altitude_rad), -std::cos(w.azimuth_rad) * std::cos(w.altitude_rad),
           std::sin(w.altitude_rad));
    const glm::dmat3 m(transform);
    const double scale = glm::length(m[2]);
    const glm::dmat3 r = m / scale;
    const glm::dmat3 rt_r = glm::transpose(r) * r;
    bool keeps_up = scale > 0.0 && std::abs(r[2][0]) < 1e-9 && std::abs(r[2][1]) < 1e-9 && r[2][2] > 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) keeps_up = keeps_up && std::abs(rt_r[i][j] - (i == j ? 1.0 : 0.0)) < 1e-9;
    if (!keeps_up)
        a.fail("the !xform around this line tilts or shears the sky (its z axis no longer points up): luxtrace "
               "keeps a sky's zenith on +z; only rotations about z (-rz), mirrors in x or y, scaling and "
               "translation can enclose a sky");
    d = glm::normalize(r * d);
    altitude_deg = std::asin(std::clamp(d.z, -1.0, 1.0)) / kDeg;
    azimuth_deg = wrap(std::atan2(d.x, d.y) / kDeg, 360.0);
}

// The ground glow note: luxtrace's is exact where gensky's and gendaylit's use a fit.
const char* kGroundNote =
    "ground glow rho E_h / pi from the sky and sun as luxtrace integrates them (Radiance's generators use "
    "gensky's polynomial fit of the sky's horizontal irradiance)";

void read_ground(ArgReader& a, const std::string& program, double& rho) {
    rho = a.number(program + " -g");
    if (!(rho >= 0.0 && rho <= 1.0)) a.fail(program + " -g: the ground reflectance must lie in [0, 1]");
}

// The ground glow note: luxtrace's is exact where gensky's and gendaylit's use a fit.
void note_ground(RadianceSky& out) {
    if (out.sky.ground_reflectance > 0.0) out.notes.push_back(kGroundNote);
}

// The options after the date: the program's own (`own` returns false for one it does not
// read), then -g and the site's (-y -a -o -m); anything else is unknown. `known` lists
// what the program reads, for that error.
template <class Own>
void read_options(ArgReader& a, const std::string& program, When& w, double& rho, const char* known, Own own) {
    while (!a.done()) {
        const std::string o = a.word("");
        if (own(o)) continue;
        if (o == "-g") read_ground(a, program, rho);
        else if (!read_site_option(a, program, o, w))
            a.fail(program + ": unknown option '" + o + "' (read are " + known + ")");
    }
}

[[noreturn]] void fail_below_horizon(const ArgReader& a, const std::string& program, const When& w,
                                     const std::string& why) {
    a.fail(program + ": the sun is below the horizon (altitude " + fixed(w.altitude_rad / kDeg, 2) + " deg)" + why);
}

// --- gensky (gensky.c computesky(); skybright.cal for the distributions).

enum class GenskyType { clear, overcast, uniform, intermediate };

// normsc(): gensky's polynomial fit of E_h F2 / L_z in the sun's altitude.
double gensky_normsc(GenskyType type, double altitude_rad) {
    static constexpr double kClear[5] = {2.766521, 0.547665, -0.369832, 0.009237, 0.059229};
    static constexpr double kIntermediate[5] = {3.5556, -2.7152, -1.3081, 1.0660, 0.60227};
    const double* c = type == GenskyType::intermediate ? kIntermediate : kClear;
    const double x = (altitude_rad - kPi / 4.0) / (kPi / 4.0);
    return (((c[4] * x + c[3]) * x + c[2]) * x + c[1]) * x + c[0];
}

// gensky's E_h / (pi L_z): the sky's horizontal irradiance per pi times zenith radiance.
double gensky_normfactor(GenskyType type, double altitude_rad) {
    const double s = std::sin(altitude_rad);
    switch (type) {
    case GenskyType::uniform: return 1.0;
    case GenskyType::overcast: return 0.777778;  // 7/9 for L = L_z (1 + 2 cos Z) / 3
    case GenskyType::clear: {
        const double f2 = 0.274 * (0.91 + 10.0 * std::exp(-3.0 * (kPi / 2.0 - altitude_rad)) + 0.45 * s * s);
        return gensky_normsc(type, altitude_rad) / f2 / kPi;
    }
    case GenskyType::intermediate: {
        const double f2 = (2.739 + 0.9891 * std::sin(0.3119 + 2.6 * altitude_rad)) *
                          std::exp(-(kPi / 2.0 - altitude_rad) * (0.4441 + 1.48 * altitude_rad));
        return gensky_normsc(type, altitude_rad) / f2 / kPi;
    }
    }
    return 1.0;
}

// gensky's options after the date.
struct GenskyOptions {
    GenskyType type = GenskyType::clear;
    bool with_sun = true;
    int zenith_unit = 0, solar_unit = 0;  // 0 default, 1 radiance (-b, -r), -1 irradiance (-B, -R)
    double zenith = 0.0, solar = 0.0, turbidity = 2.45;
    bool overcast() const { return type == GenskyType::overcast || type == GenskyType::uniform; }
};

// One of gensky's own options into `g`; false if `o` is none of them.
bool read_gensky_option(ArgReader& a, const std::string& o, GenskyOptions& g) {
    if (o == "+s" || o == "-s") {
        g.type = GenskyType::clear;
        g.with_sun = o[0] == '+';
    } else if (o == "+i" || o == "-i") {
        g.type = GenskyType::intermediate;
        g.with_sun = o[0] == '+';
    } else if (o == "-c" || o == "+c") {
        g.type = GenskyType::overcast;
    } else if (o == "-u" || o == "+u") {
        g.type = GenskyType::uniform;
    } else if (o == "-b" || o == "-B") {
        g.zenith_unit = o == "-B" ? -1 : 1;
        g.zenith = a.number("gensky " + o);
    } else if (o == "-r" || o == "-R") {
        g.solar_unit = o == "-R" ? -1 : 1;
        g.solar = a.number("gensky " + o);
    } else if (o == "-t") {
        g.turbidity = a.number("gensky -t");
    } else {
        return false;
    }
    return true;
}

// Zenith radiance (W sr^-1 m^-2): given (-b), from the diffuse horizontal irradiance
// (-B), or from gensky's luminance formulas in kcd/m2 (the clear sky's from the
// turbidity, the overcast sky's from the sun's altitude) at its sky efficacy.
double gensky_zenith_radiance(const ArgReader& a, const GenskyOptions& g, const When& w, double norm,
                              std::vector<std::string>& notes) {
    const bool overcast = g.overcast();
    double zenith_w = g.zenith;
    if (g.zenith_unit == -1) {
        zenith_w = g.zenith / (norm * kPi);
    } else if (g.zenith_unit == 0) {
        const double sin_h = std::sin(w.altitude_rad);
        const double overcast_kcd = 8.6 * sin_h + 0.123;
        const double clear_kcd = (1.376 * g.turbidity - 1.81) * std::tan(w.altitude_rad) + 0.38;
        double kcd = overcast ? overcast_kcd : clear_kcd;
        if (g.type == GenskyType::intermediate) kcd = (clear_kcd + overcast_kcd) / 2.0;
        zenith_w = std::max(0.0, kcd) * 1000.0 / kGenskySkyEfficacy_lm_per_W;
        notes.push_back("zenith luminance from gensky's formula" +
                        std::string(overcast ? "" : " (turbidity " + fixed(g.turbidity, 2) + ")") +
                        ", which gensky writes as radiance at 203 lm/W and Radiance reads at 179 lm/W");
    }
    if (!(zenith_w > 0.0))
        a.fail("gensky: the sky is dark (zenith radiance " + fixed(zenith_w, 3) + " W/sr/m2" +
               (g.zenith_unit == 0 ? ", sun altitude " + fixed(w.altitude_rad / kDeg, 2) + " deg" : std::string()) +
               "): luxtrace needs a sky of positive brightness");
    return zenith_w;
}

// skybright.cal's distribution as a CIE sky type (or uniform), and its brightness.
void set_gensky_sky(const GenskyOptions& g, double zenith_w, double norm, RadianceSky& out) {
    RadianceSkyLight& sky = out.sky;
    const double k = kRadianceEfficacy_lm_per_W;
    switch (g.type) {
    case GenskyType::clear:
        sky.sky = "cie";
        sky.cie_type = 12;  // skybright.cal's sunnysky: gradation V and indicatrix 6 of ISO 15469
        break;
    case GenskyType::intermediate:
        sky.sky = "cie";
        sky.cie_type = 7;
        out.notes.push_back("gensky's intermediate sky (skybright.cal intersky) as ISO 15469 type 7, the nearest "
                            "of the 15 (cosine-weighted rms 12-21 % in L/L_z for sun altitudes 15-60 deg), scaled "
                            "to gensky's horizontal illuminance");
        break;
    case GenskyType::overcast: sky.sky = "cie", sky.cie_type = 16; break;
    case GenskyType::uniform: sky.sky = "uniform"; break;
    }
    // The intermediate sky keeps gensky's horizontal illuminance, the others their exact
    // distribution with the brightness given.
    if (g.zenith_unit == -1 || g.type == GenskyType::intermediate)
        sky.diffuse_horizontal_lx = k * zenith_w * norm * kPi;
    else sky.zenith_luminance_cd_m2 = k * zenith_w;
}

// gensky writes a sun for +s and +i with the sun above the horizon, unless -r or -R give
// it no brightness.
bool gensky_has_sun(const GenskyOptions& g, double sin_h) {
    return !g.overcast() && sin_h > 0.0 && (g.solar_unit == 0 || g.solar > 0.0) && g.with_sun;
}

// The sun: gensky's solar radiance from the altitude (subdued to 15 % for +i), given
// (-r), or from the direct horizontal irradiance (-R); a 0.5 deg source.
void add_gensky_sun(const GenskyOptions& g, double sin_h, RadianceSky& out) {
    double solar_w = g.solar;
    if (g.solar_unit == -1) {
        solar_w = g.solar / (kGenskySunSolidAngle_sr * sin_h);
    } else if (g.solar_unit == 0) {
        solar_w = 1.5e9 / kGenskySunEfficacy_lm_per_W * (1.147 - 0.147 / std::max(sin_h, 0.16));
        if (g.type == GenskyType::intermediate) solar_w *= 0.15;
        out.notes.push_back("solar radiance from gensky's formula in the sun's altitude");
    }
    const double k = kRadianceEfficacy_lm_per_W;
    out.sun = RadianceSunLight{k * solar_w * source_solid_angle_sr(0.5), out.sky.sun_altitude_deg,
                               out.sky.sun_azimuth_deg};
    out.notes.push_back("the sun as luxtrace's 0.533 deg disc with gensky's direct normal illuminance (gensky's "
                        "source is 0.5 deg)");
}

RadianceSky map_gensky(ArgReader& a, const glm::dmat4& transform, RadianceSky out) {
    When w = read_when(a, "gensky");
    GenskyOptions g;
    read_options(a, "gensky", w, out.sky.ground_reflectance, "+s -s +i -i -c -u -b -B -r -R -t -g -a -o -m -y",
                 [&](const std::string& o) { return read_gensky_option(a, o, g); });
    place_sun(w, out.notes);
    if (!g.overcast()) clamp_to_87(w, out.notes);
    if (!g.overcast() && w.altitude_rad < 0.0)
        fail_below_horizon(a, "gensky", w, ": the clear and intermediate skies need it above; use -c or -u");
    const double sin_h = std::sin(w.altitude_rad);
    const double norm = gensky_normfactor(g.type, w.altitude_rad);
    const double zenith_w = gensky_zenith_radiance(a, g, w, norm, out.notes);
    set_gensky_sky(g, zenith_w, norm, out);
    orient_sun(w, transform, a, out.sky.sun_altitude_deg, out.sky.sun_azimuth_deg);
    if (gensky_has_sun(g, sin_h)) add_gensky_sun(g, sin_h, out);
    note_ground(out);
    return out;
}

// --- gendaylit (gendaylit.c main() and computesky()).

// gendaylit's options after the date.
struct GendaylitOptions {
    bool with_sun = true, cloudy = false;
    char input = 0;  // 'W', 'G', 'P' or 'E'
    double first = 0.0, second = 0.0;
    double dew_point = kGendaylitDewPoint_c;
    bool dew_given = false;
};

// One of gendaylit's own options into `g` (refusing those luxtrace cannot follow); false
// if `o` is none of them.
bool read_gendaylit_option(ArgReader& a, const std::string& o, GendaylitOptions& g, std::vector<std::string>& notes) {
    if (o == "+s" || o == "-s") {
        g.with_sun = o[0] == '+';
        g.cloudy = false;
    } else if (o == "-c" || o == "+c") {
        g.cloudy = true;
        g.with_sun = false;
    } else if (o == "-W" || o == "-G" || o == "-P") {
        g.input = o[1];
        g.first = a.number("gendaylit " + o + "'s first value");
        g.second = a.number("gendaylit " + o + "'s second value");
    } else if (o == "-E") {
        g.input = 'E';
        g.first = a.number("gendaylit -E");
    } else if (o == "-L") {
        a.fail("gendaylit -L (illuminances) is not read: luxtrace's Perez sky takes the irradiances and finds "
               "the illuminances with the Perez efficacies; give -W direct-normal diffuse-horizontal (W/m2)");
    } else if (o == "-O") {
        const double v = a.number("gendaylit -O");
        if (v != 0.0)
            a.fail("gendaylit -O " + fixed(v, 0) +
                   " is not read: only -O 0 (visible radiance, the default) gives the sky Radiance reads at "
                   "179 lm/W");
    } else if (o == "-d") {
        g.dew_point = a.number("gendaylit -d");
        g.dew_given = true;
        if (g.dew_point < -40.0 || g.dew_point > 40.0) {
            notes.push_back("dew point " + fixed(g.dew_point, 1) +
                            " C outside [-40, 40]: gendaylit's default used instead");
            g.dew_point = kGendaylitDewPoint_c;
        }
    } else if (o == "-w") {
    } else if (o == "-t" || o == "-b" || o == "-R") {
        a.number("gendaylit " + o);
        notes.push_back("gendaylit " + o + " has no effect in gendaylit and is ignored");
    } else if (o == "-C" || o == "-CIE" || o == "-l") {
        a.fail("gendaylit " + o + " (a coloured sky) is not read: luxtrace's Perez sky has no colour");
    } else if (o == "-i") {
        a.fail("gendaylit -i (the time interval's correction of low suns) is not read");
    } else {
        return false;
    }
    return true;
}

// The hour's irradiances (W/m2).
struct Irradiance {
    double direct_normal = 0.0, diffuse = 0.0;
};

// -P: Perez 1990 eqs. 1 and 2 solved for the irradiances, after gendaylit's clamps.
Irradiance from_perez_parameters(double first, double second, double zenith_rad, double e0_w_m2,
                                 std::vector<std::string>& notes) {
    const double epsilon = std::clamp(first, 1.0, 12.009), delta = std::clamp(second, 0.01, 0.6);
    if (epsilon != first || delta != second)
        notes.push_back("-P clamped to epsilon " + fixed(epsilon, 3) + ", delta " + fixed(delta, 3) +
                        " (gendaylit's range)");
    const double z3 = zenith_rad * zenith_rad * zenith_rad;
    Irradiance e;
    e.diffuse = delta / relative_air_mass(zenith_rad) * e0_w_m2;
    e.direct_normal = e.diffuse * (epsilon - 1.0) * (1.0 + 1.041 * z3);
    return e;
}

// -E: Erbs, Klein & Duffie 1982: the diffuse fraction from the clearness index.
Irradiance from_global(const ArgReader& a, double first, double sin_h, double e0_w_m2,
                       std::vector<std::string>& notes) {
    const double s0 = e0_w_m2 * sin_h;
    if (!(first >= 0.0)) a.fail("gendaylit -E: the global irradiance must not be negative");
    double global = first;
    if (global > s0) {
        notes.push_back("global irradiance above the extraterrestrial one taken as 0.999 of it, as gendaylit");
        global = 0.999 * s0;
    }
    const double kt = global / s0;
    const double fraction = kt <= 0.22  ? 1.0 - 0.09 * kt
                            : kt <= 0.8 ? 0.9511 - 0.1604 * kt + 4.388 * kt * kt - 16.638 * kt * kt * kt +
                                              12.336 * kt * kt * kt * kt
                                        : 0.165;
    Irradiance e;
    e.diffuse = global * fraction;
    e.direct_normal = (global - e.diffuse) / sin_h;
    notes.push_back("the diffuse fraction from the global irradiance by Erbs' model, as gendaylit -E");
    return e;
}

// Direct normal and diffuse horizontal irradiance from -W, -G, -P or -E, within
// gendaylit's range.
Irradiance gendaylit_irradiance(const ArgReader& a, const GendaylitOptions& g, const When& w, int day_of_year,
                                std::vector<std::string>& notes) {
    const double sin_h = std::sin(w.altitude_rad), zenith_rad = kPi / 2.0 - w.altitude_rad;
    const double e0_w_m2 = 1367.0 * eccentricity_factor(day_of_year);
    Irradiance e;
    switch (g.input) {
    case 'W': e = {g.first, g.second}; break;
    case 'G': e = {g.first / sin_h, g.second}; break;
    case 'P': e = from_perez_parameters(g.first, g.second, zenith_rad, e0_w_m2, notes); break;
    case 'E': e = from_global(a, g.first, sin_h, e0_w_m2, notes); break;
    }
    if (!(e.diffuse > 0.0 && e.diffuse <= 1367.0))
        a.fail("gendaylit: the diffuse horizontal irradiance must lie in (0, 1367] W/m2, got " + fixed(e.diffuse, 3));
    if (!(e.direct_normal >= 0.0 && e.direct_normal <= 1367.0))
        a.fail("gendaylit: the direct normal irradiance must lie in [0, 1367] W/m2, got " + fixed(e.direct_normal, 3));
    return e;
}

// The sun of the Perez sky drawn from the sky's keys; gendaylit writes a sun only when
// the sky is not fully overcast (epsilon > 1).
void add_perez_sun(const ArgReader& a, const GendaylitOptions& g, RadianceSky& out) {
    const RadianceSkyLight& sky = out.sky;
    PerezSkyInput in;
    in.sun_zenith_rad = (90.0 - sky.sun_altitude_deg) * kDeg;
    in.sun_azimuth_rad = sky.sun_azimuth_deg * kDeg;
    in.diffuse_horizontal_w_m2 = sky.diffuse_horizontal_w_m2;
    in.direct_normal_w_m2 = sky.direct_normal_w_m2;
    in.dew_point_c = sky.dew_point_c;
    in.day_of_year = sky.day_of_year;
    try {
        const PerezSky perez(in, false);
        if (g.with_sun && perez.epsilon() > 1.0 && sky.direct_normal_w_m2 > 0.0)
            out.sun = RadianceSunLight{perez.direct_normal_illuminance_lx(), sky.sun_altitude_deg, sky.sun_azimuth_deg};
    } catch (const std::invalid_argument& e) {
        a.fail(std::string("gendaylit: ") + e.what());
    }
}

RadianceSky map_gendaylit(ArgReader& a, const glm::dmat4& transform, RadianceSky out) {
    When w = read_when(a, "gendaylit");
    GendaylitOptions g;
    read_options(a, "gendaylit", w, out.sky.ground_reflectance, "-W -G -P -E -O 0 -d -g +s -s -c -w -a -o -m -y",
                 [&](const std::string& o) { return read_gendaylit_option(a, o, g, out.notes); });
    if (g.input == 0) a.fail("gendaylit needs the hour's light: -W, -G, -P or -E");
    place_sun(w, out.notes);
    if (!g.cloudy) clamp_to_87(w, out.notes);
    if (!(w.altitude_rad > 0.0))
        fail_below_horizon(a, "gendaylit", w,
                           ", where gendaylit writes a dark sky; luxtrace's Perez sky needs the sun above it");
    // The day for the extraterrestrial irradiance: jdate() of the date, 0 for -ang (a
    // global never set), which the day angle makes the same as 365.
    RadianceSkyLight& sky = out.sky;
    sky.day_of_year = w.by_angles ? 365 : day_number(w.month, w.day);
    const Irradiance e = gendaylit_irradiance(a, g, w, sky.day_of_year, out.notes);
    sky.sky = "perez";
    sky.diffuse_horizontal_w_m2 = e.diffuse;
    sky.direct_normal_w_m2 = e.direct_normal;
    sky.dew_point_c = g.dew_point;
    if (!g.dew_given) out.notes.push_back("dew point 10.97 C, gendaylit's default (precipitable water 2 cm)");
    orient_sun(w, transform, a, sky.sun_altitude_deg, sky.sun_azimuth_deg);
    add_perez_sun(a, g, out);
    note_ground(out);
    return out;
}

}  // namespace

std::string RadianceSky::describe() const {
    std::string s = command + " -> ";
    if (sky.sky == "perez")
        s += "Perez sky (direct normal " + fixed(sky.direct_normal_w_m2, 1) + " W/m2, diffuse horizontal " +
             fixed(sky.diffuse_horizontal_w_m2, 1) + " W/m2, dew point " + fixed(sky.dew_point_c, 2) + " C, day " +
             std::to_string(sky.day_of_year) + ")";
    else if (sky.sky == "cie") s += "CIE type " + std::to_string(sky.cie_type) + " sky";
    else s += sky.sky + " sky";
    if (sky.zenith_luminance_cd_m2) s += ", zenith " + fixed(*sky.zenith_luminance_cd_m2, 0) + " cd/m2";
    if (sky.diffuse_horizontal_lx) s += ", diffuse horizontal " + fixed(*sky.diffuse_horizontal_lx, 0) + " lx";
    s += ", sun " + fixed(sky.sun_altitude_deg, 1) + " deg altitude " + fixed(sky.sun_azimuth_deg, 1) +
         " deg azimuth (from north, clockwise)";
    s += sun ? "; sun light, direct normal " + fixed(sun->direct_normal_lx / 1000.0, 1) + " klx" : "; no sun light";
    s += "; ground reflectance " + fixed(sky.ground_reflectance, 3);
    for (const std::string& n : notes) s += "; " + n;
    return s;
}

RadianceSky map_radiance_sky(const RadianceModel& model, const RadianceCommand& cmd) {
    RadianceSky out;
    out.command = cmd.program;
    for (const std::string& w : cmd.arguments) out.command += " " + w;
    ArgReader a(cmd.arguments, model.where(cmd.at));
    if (cmd.program == "gensky") return map_gensky(a, cmd.transform, std::move(out));
    if (cmd.program == "gendaylit") return map_gendaylit(a, cmd.transform, std::move(out));
    a.fail("'" + cmd.program + "' is not a sky generator (gensky or gendaylit)");
}

}  // namespace luxtrace
