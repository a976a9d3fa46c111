#pragma once
// Where and when daylight is simulated ([site] in the scene file, docs/DAYLIGHT.md): the
// geographic site and local standard time the sun's position comes from (sun_position.hpp),
// and how the sky's compass sits in the scene.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/sun_position.hpp"

#include <optional>
#include <string>

namespace luxtrace {

struct Site {
    // latitude_deg, longitude_deg and utc_offset_h were given: with `time`, the sun's
    // position can be computed.
    bool located = false;
    SunSite sun_site;
    double utc_offset_h = 0.0;
    std::optional<LocalStandardTime> time;  // with utc_offset_h filled in
    std::string time_text;                  // as written, for messages and reports
    // The scene's horizontal direction of north (unit); up is always +z.
    Vec3 north{0.0, 1.0, 0.0};

    // The sky frame (z up, north +y, east +x: sky_model.hpp) in scene coordinates:
    // t = east, b = north, n = up.
    Frame horizon() const;
};

// The unit vector in the sky frame towards altitude h and azimuth alpha (clockwise from
// north), both in degrees.
Vec3 sky_direction_deg(double altitude_deg, double azimuth_deg);

// "YYYY-MM-DDTHH:MM" or "YYYY-MM-DDTHH:MM:SS" (a space may replace the T); std::nullopt
// unless the date exists and the time lies in [00:00, 24:00].
std::optional<LocalStandardTime> parse_local_time(const std::string& text);

}  // namespace luxtrace
