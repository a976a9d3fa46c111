#include "luxtrace/light/site.hpp"

#include <cmath>
#include <cstdio>

namespace luxtrace {

Frame Site::horizon() const {
    const Vec3 up(0.0, 0.0, 1.0);
    return {glm::cross(north, up), north, up};
}

Vec3 sky_direction_deg(double altitude_deg, double azimuth_deg) {
    const double h = altitude_deg * kPi / 180.0, a = azimuth_deg * kPi / 180.0;
    return {std::cos(h) * std::sin(a), std::cos(h) * std::cos(a), std::sin(h)};
}

namespace {

bool leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

int days_in_month(int y, int m) {
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return m == 2 && leap(y) ? 29 : kDays[m - 1];
}

}  // namespace

std::optional<LocalStandardTime> parse_local_time(const std::string& text) {
    int y = 0, mo = 0, d = 0, h = 0, mi = 0, s = 0, used = 0;
    char sep = 0;
    LocalStandardTime t;
    const int fields = std::sscanf(text.c_str(), "%4d-%2d-%2d%c%2d:%2d%n", &y, &mo, &d, &sep, &h, &mi, &used);
    if (fields != 6 || (sep != 'T' && sep != ' ') || text.size() < 16 || text[4] != '-' || text[7] != '-' ||
        text[10] != sep || text[13] != ':')
        return std::nullopt;
    if (static_cast<std::size_t>(used) != text.size()) {
        int more = 0;
        if (text[static_cast<std::size_t>(used)] != ':' || std::sscanf(text.c_str() + used, ":%2d%n", &s, &more) != 1 ||
            static_cast<std::size_t>(used + more) != text.size() || more != 3)
            return std::nullopt;
    }
    if (y < 1 || mo < 1 || mo > 12 || d < 1 || d > days_in_month(y, mo) || h < 0 || mi < 0 || mi > 59 || s < 0 ||
        s > 59 || h > 24 || (h == 24 && (mi != 0 || s != 0)))
        return std::nullopt;
    t.year = y;
    t.month = mo;
    t.day = d;
    t.hour = h;
    t.minute = mi;
    t.second = s;
    return t;
}

}  // namespace luxtrace
