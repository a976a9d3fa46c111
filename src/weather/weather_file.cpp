#include "luxtrace/weather/weather_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "luxtrace/core/error.hpp"

namespace luxtrace::weather {
namespace {

constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
// Upper bounds well above anything measured at the ground: the solar constant is
// ~1361 W/m2 and the extraterrestrial illuminance ~133 klx.
constexpr double kMaxIrradiance_w_m2 = 2000.0;
constexpr double kMaxIlluminance_lx = 200000.0;

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
    throw InputError(path + ":" + std::to_string(line) + ": " + what);
}

std::string trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return std::string(s.substr(first, last - first + 1));
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> out;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, sep)) out.push_back(trim(field));
    if (!line.empty() && line.back() == sep) out.emplace_back();
    return out;
}

std::vector<std::string> split_blanks(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    std::string word;
    while (in >> word) out.push_back(word);
    return out;
}

// One number field: the whole text must parse, be finite and lie in [lo, hi].
double number(const std::string& path, int line, const std::string& name, const std::string& text, double lo,
              double hi) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
        fail(path, line, name + " '" + text + "' is not a number");
    }
    if (value < lo || value > hi) {
        std::ostringstream msg;
        msg << name << " " << text << " is outside [" << lo << ", " << hi << "]";
        fail(path, line, msg.str());
    }
    return value;
}

int integer(const std::string& path, int line, const std::string& name, const std::string& text, int lo, int hi) {
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end) {
        fail(path, line, name + " '" + text + "' is not an integer");
    }
    if (value < lo || value > hi) {
        fail(path, line, name + " " + text + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    return value;
}

// A field that may carry the format's missing-value code (stored as NaN).
double maybe_missing(const std::string& path, int line, const std::string& name, const std::string& text,
                     double missing_code, double lo, double hi) {
    const double value = number(path, line, name, text, lo, std::max(hi, missing_code));
    if (value == missing_code) return kMissing;
    if (value > hi) {
        std::ostringstream msg;
        msg << name << " " << text << " is outside [" << lo << ", " << hi << "]";
        fail(path, line, msg.str());
    }
    return value;
}

int days_in_month(int month, bool leap) {
    static constexpr std::array<int, 12> kDays = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return (month == 2 && leap) ? 29 : kDays[static_cast<std::size_t>(month - 1)];
}

std::ifstream open(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open the weather file");
    return in;
}

std::string hour_text(int month, int day, int hour) {
    return std::to_string(month) + "/" + std::to_string(day) + " hour " + std::to_string(hour);
}

// LOCATION,city,state,country,source,WMO,latitude,longitude,time zone,elevation
void read_epw_location(const std::string& path, int line, const std::string& text, WeatherSite& site) {
    const auto loc = split(text, ',');
    if (loc.empty() || loc[0] != "LOCATION") fail(path, line, "the first line is not LOCATION");
    if (loc.size() < 10) fail(path, line, "LOCATION has fewer than 10 fields");
    site.city = loc[1];
    site.latitude_deg = number(path, line, "latitude", loc[6], -90.0, 90.0);
    site.longitude_deg = number(path, line, "longitude", loc[7], -180.0, 180.0);
    site.time_zone_h = number(path, line, "time zone", loc[8], -12.0, 14.0);
    site.elevation_m = number(path, line, "elevation", loc[9], -1000.0, 9000.0);
}

// The hour the next EPW record must hold: the year runs from 1/1 hour 1 to 12/31 hour
// 24 without a gap.
struct ExpectedHour {
    bool leap = false;
    int month = 1;
    int day = 1;
    int hour = 1;
    bool done = false;

    // A leap-year file holds Feb 29 where a common year goes on with Mar 1.
    void allow_leap_day(int record_month, int record_day) {
        if (month == 3 && day == 1 && hour == 1 && record_month == 2 && record_day == 29 && !leap) {
            leap = true;
            month = 2;
            day = 29;
        }
    }
    void advance() {
        if (++hour > 24) {
            hour = 1;
            if (++day > days_in_month(month, leap)) {
                day = 1;
                if (++month > 12) done = true;
            }
        }
    }
};

// The weather of one record's fields, each with the format's missing-value code.
void read_epw_values(const std::string& path, int line, const std::vector<std::string>& f, WeatherHour& h) {
    h.dry_bulb_c = maybe_missing(path, line, "dry bulb temperature", f[6], 99.9, -70.0, 70.0);
    h.dew_point_c = maybe_missing(path, line, "dew point temperature", f[7], 99.9, -70.0, 70.0);
    h.global_horizontal_w_m2 = maybe_missing(path, line, "global horizontal irradiance", f[13], 9999.0, 0.0,
                                             kMaxIrradiance_w_m2);
    h.direct_normal_w_m2 = maybe_missing(path, line, "direct normal irradiance", f[14], 9999.0, 0.0,
                                         kMaxIrradiance_w_m2);
    h.diffuse_horizontal_w_m2 = maybe_missing(path, line, "diffuse horizontal irradiance", f[15], 9999.0, 0.0,
                                              kMaxIrradiance_w_m2);
    h.global_horizontal_lx = maybe_missing(path, line, "global horizontal illuminance", f[16], 999999.0, 0.0,
                                           kMaxIlluminance_lx);
    h.direct_normal_lx = maybe_missing(path, line, "direct normal illuminance", f[17], 999999.0, 0.0,
                                       kMaxIlluminance_lx);
    h.diffuse_horizontal_lx = maybe_missing(path, line, "diffuse horizontal illuminance", f[18], 999999.0, 0.0,
                                            kMaxIlluminance_lx);
}

// One hourly record, which must be the `expected` hour.
WeatherHour read_epw_hour(const std::string& path, int line, const std::string& row, ExpectedHour& expected) {
    const auto f = split(row, ',');
    if (f.size() < 19) {
        fail(path, line, "a truncated record: " + std::to_string(f.size()) + " fields, expected 35");
    }
    WeatherHour h;
    h.year = integer(path, line, "year", f[0], 1, 9999);
    h.month = integer(path, line, "month", f[1], 1, 12);
    h.day = integer(path, line, "day", f[2], 1, 31);
    const int record_hour = integer(path, line, "hour", f[3], 1, 24);
    expected.allow_leap_day(h.month, h.day);
    if (h.month != expected.month || h.day != expected.day || record_hour != expected.hour) {
        fail(path, line,
             "expected " + hour_text(expected.month, expected.day, expected.hour) + ", found " +
                 hour_text(h.month, h.day, record_hour) + " (a missing or extra hour)");
    }
    h.hour = record_hour;
    read_epw_values(path, line, f, h);
    return h;
}

}  // namespace

WeatherFile read_epw(const std::string& path) {
    std::ifstream in = open(path);
    WeatherFile file;
    file.path = path;
    file.format = WeatherFormat::epw;
    std::string text;
    int line = 0;
    if (!std::getline(in, text)) fail(path, 1, "empty file (expected a LOCATION line)");
    ++line;
    read_epw_location(path, line, text, file.site);

    ExpectedHour expected;
    while (std::getline(in, text)) {
        ++line;
        const std::string row = trim(text);
        // The other header lines (DESIGN CONDITIONS ... DATA PERIODS) start with a letter.
        if (file.hours.empty() && (row.empty() || std::isalpha(static_cast<unsigned char>(row[0])))) {
            continue;
        }
        if (row.empty()) fail(path, line, "empty line among the hourly records");
        if (expected.done) fail(path, line, "an extra hour after 12/31 hour 24");
        file.hours.push_back(read_epw_hour(path, line, row, expected));
        expected.advance();
    }
    if (!expected.done) {
        fail(path, line,
             "the file ends after " + std::to_string(file.hours.size()) +
                 " hours (truncated: expected 8760, or 8784 in a leap year); next would be " +
                 hour_text(expected.month, expected.day, expected.hour));
    }
    return file;
}

WeatherFile read_wea(const std::string& path) {
    std::ifstream in = open(path);
    WeatherFile file;
    file.path = path;
    file.format = WeatherFormat::wea;
    std::string text;
    int line = 0;
    const std::array<std::string, 6> keys = {"place",     "latitude",       "longitude",
                                             "time_zone", "site_elevation", "weather_data_file_units"};
    for (const std::string& key : keys) {
        if (!std::getline(in, text)) fail(path, line + 1, "the file ends before '" + key + "'");
        ++line;
        const std::string row = trim(text);
        const auto blank = row.find_first_of(" \t");
        const std::string word = row.substr(0, blank);
        const std::string value = blank == std::string::npos ? "" : trim(row.substr(blank));
        if (word != key) fail(path, line, "expected '" + key + "', found '" + word + "'");
        if (key == "place") {
            file.site.city = value;
        } else if (key == "latitude") {
            file.site.latitude_deg = number(path, line, key, value, -90.0, 90.0);
        } else if (key == "longitude") {
            // Radiance counts longitude west positive; stored east positive.
            file.site.longitude_deg = -number(path, line, key, value, -180.0, 180.0);
        } else if (key == "time_zone") {
            // The standard meridian in degrees, west positive: UTC-6 is 90.
            file.site.time_zone_h = -number(path, line, key, value, -210.0, 180.0) / 15.0;
        } else if (key == "site_elevation") {
            file.site.elevation_m = number(path, line, key, value, -1000.0, 9000.0);
        } else {
            // Only units 1 (W/m2, direct normal and diffuse horizontal irradiance) is read,
            // as in gendaymtx.
            integer(path, line, key, value, 1, 1);
        }
    }
    double previous_time = -1.0;
    double step = 0.0;
    while (std::getline(in, text)) {
        ++line;
        const auto f = split_blanks(text);
        if (f.empty()) continue;
        if (f.size() != 5) {
            fail(path, line,
                 std::to_string(f.size()) + " fields, expected 5 (month day hour direct_normal diffuse_horizontal)");
        }
        WeatherHour h;
        h.month = integer(path, line, "month", f[0], 1, 12);
        h.day = integer(path, line, "day", f[1], 1, days_in_month(h.month, true));
        h.hour = number(path, line, "hour", f[2], 0.0, 24.0);
        h.direct_normal_w_m2 = number(path, line, "direct normal irradiance", f[3], 0.0, kMaxIrradiance_w_m2);
        h.diffuse_horizontal_w_m2 = number(path, line, "diffuse horizontal irradiance", f[4], 0.0, kMaxIrradiance_w_m2);
        h.dry_bulb_c = h.dew_point_c = h.global_horizontal_w_m2 = kMissing;
        h.global_horizontal_lx = h.direct_normal_lx = h.diffuse_horizontal_lx = kMissing;
        // Time in hours from Jan 1 (a leap calendar, so Feb 29 may appear).
        int day_of_year = h.day - 1;
        for (int m = 1; m < h.month; ++m) day_of_year += days_in_month(m, true);
        const double time = 24.0 * day_of_year + h.hour;
        if (time <= previous_time) {
            fail(path, line, "a repeated or out-of-order time (an extra hour)");
        }
        // A .wea may skip nights (filtered files) but within a day the step is constant.
        if (!file.hours.empty() && file.hours.back().month == h.month && file.hours.back().day == h.day) {
            const double gap = time - previous_time;
            if (step == 0.0) {
                step = gap;
            } else if (std::abs(gap - step) > 1e-6) {
                std::ostringstream msg;
                msg << "a time step of " << gap << " h where the file steps by " << step
                    << " h (a missing or extra hour)";
                fail(path, line, msg.str());
            }
        }
        previous_time = time;
        file.hours.push_back(h);
    }
    if (file.hours.empty()) fail(path, line, "no hourly records (truncated)");
    return file;
}

WeatherFile read_weather_file(const std::string& path) {
    std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".epw") return read_epw(path);
    if (ext == ".wea") return read_wea(path);
    throw InputError(path + ": not a weather file (expected .epw or .wea)");
}

}  // namespace luxtrace::weather
