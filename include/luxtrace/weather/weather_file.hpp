#pragma once
// Hourly weather from an EnergyPlus weather file (.epw) or a Radiance .wea file, the
// input of annual daylight (issue 24). Conventions (docs/WEATHER.md): longitudes and time
// zones are stored EAST positive (a .wea's west-positive values are negated); an hour
// record's `hour` is the hour ENDING at that time (EPW 1-24); a .wea's decimal hour is
// kept as written (usually the middle of the hour, x.5). A field that carries its
// format's missing-value code is stored as NaN.
#include <string>
#include <vector>

namespace luxtrace::weather {

struct WeatherSite {
    std::string city;
    double latitude_deg = 0.0;   // north positive
    double longitude_deg = 0.0;  // EAST positive
    double time_zone_h = 0.0;    // hours east of Greenwich (UTC+h)
    double elevation_m = 0.0;
};

struct WeatherHour {
    int year = 0;  // 0 in a .wea (which carries no year)
    int month = 0;
    int day = 0;
    double hour = 0.0;  // EPW: 1-24, the hour ending then; .wea: decimal hour as written
    double dry_bulb_c = 0.0;
    double dew_point_c = 0.0;
    double global_horizontal_w_m2 = 0.0;
    double direct_normal_w_m2 = 0.0;
    double diffuse_horizontal_w_m2 = 0.0;
    double global_horizontal_lx = 0.0;
    double direct_normal_lx = 0.0;
    double diffuse_horizontal_lx = 0.0;
};

// Which reader read it: an EPW hour is the hour ending then, a .wea hour as written.
enum class WeatherFormat { epw, wea };

struct WeatherFile {
    std::string path;
    WeatherFormat format = WeatherFormat::epw;
    WeatherSite site;
    std::vector<WeatherHour> hours;
};

// Both throw luxtrace::InputError naming the file, the line and what is wrong.
WeatherFile read_epw(const std::string& path);
WeatherFile read_wea(const std::string& path);
// By extension: ".epw" or ".wea" (case-insensitive); anything else is an InputError.
WeatherFile read_weather_file(const std::string& path);

}  // namespace luxtrace::weather
