// The weather-file readers (issue 24 §1) on real files: Chicago O'Hare TMY3 as an EPW and
// as the .wea Ladybug made from it (tests/data/weather/README.md), and every class of bad
// input as an InputError naming the file and the line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "luxtrace/core/error.hpp"
#include "luxtrace/weather/weather_file.hpp"
#include "test_support.hpp"

namespace {

using luxtrace::InputError;
using luxtrace::weather::read_epw;
using luxtrace::weather::read_wea;
using luxtrace::weather::read_weather_file;
using luxtrace::weather::WeatherFile;

const std::string kDir = std::string(LUXTRACE_TEST_DATA_DIR) + "/weather/";
const std::string kEpw = kDir + "chicago.epw";
const std::string kWea = kDir + "chicago.wea";

std::vector<std::string> lines_of(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
    return lines;
}

// Writes `lines` to a scratch file and returns the reader's message (empty if it read).
std::string error_of(const std::vector<std::string>& lines, const std::string& name) {
    luxtrace::test_support::ScratchDir dir("weather_" + name.substr(0, name.find('.')));
    const std::string path = (dir.path() / name).string();
    {
        std::ofstream out(path);
        for (const auto& l : lines) out << l << "\n";
    }
    try {
        read_weather_file(path);
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path), std::string::npos) << what;
        return what;
    }
    return {};
}

// Replaces comma field `index` of `line`.
std::string with_field(const std::string& line, std::size_t index, const std::string& value) {
    std::vector<std::string> f;
    std::stringstream in(line);
    std::string s;
    while (std::getline(in, s, ',')) f.push_back(s);
    f.at(index) = value;
    std::string out;
    for (std::size_t i = 0; i < f.size(); ++i) out += (i ? "," : "") + f[i];
    return out;
}

TEST(WeatherFile, EpwLocationAndHours) {
    const WeatherFile w = read_epw(kEpw);
    EXPECT_EQ(w.site.city, "Chicago Ohare Intl Ap");
    EXPECT_DOUBLE_EQ(w.site.latitude_deg, 41.98);
    EXPECT_DOUBLE_EQ(w.site.longitude_deg, -87.92);  // west of Greenwich
    EXPECT_DOUBLE_EQ(w.site.time_zone_h, -6.0);
    EXPECT_DOUBLE_EQ(w.site.elevation_m, 201.0);
    ASSERT_EQ(w.hours.size(), 8760U);
    EXPECT_EQ(w.hours.front().month, 1);
    EXPECT_EQ(w.hours.front().hour, 1.0);  // the hour ending 01:00
    EXPECT_EQ(w.hours.back().month, 12);
    EXPECT_EQ(w.hours.back().day, 31);
    EXPECT_EQ(w.hours.back().hour, 24.0);
}

TEST(WeatherFile, EpwSpotValuesAndColumnSum) {
    const WeatherFile w = read_epw(kEpw);
    // June 21, the hour ending 13:00, as its line states it:
    // 30.6,13.3 ... 895,734,205,96600,75500,25700.
    const auto& h = w.hours.at((31 + 28 + 31 + 30 + 31 + 20) * 24 + 12);
    EXPECT_EQ(h.month, 6);
    EXPECT_EQ(h.day, 21);
    EXPECT_EQ(h.hour, 13.0);
    EXPECT_DOUBLE_EQ(h.dry_bulb_c, 30.6);
    EXPECT_DOUBLE_EQ(h.dew_point_c, 13.3);
    EXPECT_DOUBLE_EQ(h.global_horizontal_w_m2, 895.0);
    EXPECT_DOUBLE_EQ(h.direct_normal_w_m2, 734.0);
    EXPECT_DOUBLE_EQ(h.diffuse_horizontal_w_m2, 205.0);
    EXPECT_DOUBLE_EQ(h.global_horizontal_lx, 96600.0);
    EXPECT_DOUBLE_EQ(h.direct_normal_lx, 75500.0);
    EXPECT_DOUBLE_EQ(h.diffuse_horizontal_lx, 25700.0);
    // The year's global horizontal irradiation: the column's sum (awk -F, 'NR>8{s+=$14}'),
    // 1,406,646 Wh/m2 = 1.41 MWh/m2, as expected for Chicago.
    double sum = 0.0;
    for (const auto& x : w.hours) sum += x.global_horizontal_w_m2;
    EXPECT_DOUBLE_EQ(sum, 1406646.0);
    // Physics: no hour's diffuse exceeds its global, and the night is dark.
    for (const auto& x : w.hours) {
        EXPECT_LE(x.diffuse_horizontal_w_m2, x.global_horizontal_w_m2 + 1.0);
    }
    EXPECT_EQ(w.hours.front().global_horizontal_w_m2, 0.0);
}

TEST(WeatherFile, WeaIsWestPositiveAndAgreesWithItsEpw) {
    const WeatherFile wea = read_wea(kWea);
    const WeatherFile epw = read_epw(kEpw);
    // The .wea says longitude 87.92 and time_zone 90 (west positive): stored east positive.
    EXPECT_DOUBLE_EQ(wea.site.longitude_deg, epw.site.longitude_deg);
    EXPECT_DOUBLE_EQ(wea.site.time_zone_h, epw.site.time_zone_h);
    EXPECT_DOUBLE_EQ(wea.site.latitude_deg, epw.site.latitude_deg);
    EXPECT_DOUBLE_EQ(wea.site.elevation_m, epw.site.elevation_m);
    ASSERT_EQ(wea.hours.size(), epw.hours.size());
    // The .wea's hour h.5 is the middle of the EPW's hour ending h+1: same irradiances.
    for (std::size_t i = 0; i < wea.hours.size(); ++i) {
        const auto& a = wea.hours[i];
        const auto& b = epw.hours[i];
        ASSERT_EQ(a.month, b.month);
        ASSERT_EQ(a.day, b.day);
        ASSERT_DOUBLE_EQ(a.hour + 0.5, b.hour);
        ASSERT_DOUBLE_EQ(a.direct_normal_w_m2, b.direct_normal_w_m2);
        ASSERT_DOUBLE_EQ(a.diffuse_horizontal_w_m2, b.diffuse_horizontal_w_m2);
    }
    EXPECT_TRUE(std::isnan(wea.hours.front().dry_bulb_c));  // a .wea carries none
}

TEST(WeatherFile, EpwMissingCodesBecomeNaN) {
    auto lines = lines_of(kEpw);
    lines[8] = with_field(with_field(lines[8], 6, "99.9"), 15, "9999");
    luxtrace::test_support::ScratchDir dir("weather_missing");
    const std::string path = (dir.path() / "m.epw").string();
    {
        std::ofstream out(path);
        for (const auto& l : lines) out << l << "\n";
    }
    const WeatherFile w = read_epw(path);
    EXPECT_TRUE(std::isnan(w.hours[0].dry_bulb_c));
    EXPECT_TRUE(std::isnan(w.hours[0].diffuse_horizontal_w_m2));
    EXPECT_FALSE(std::isnan(w.hours[1].dry_bulb_c));
}

TEST(WeatherFile, EpwLeapYearHoldsFeb29) {
    // Feb 28's 24 records copied as Feb 29: 8784 hours, Mar 1 follows.
    auto lines = lines_of(kEpw);
    const std::size_t feb29 = 8 + (31 + 28) * 24;
    std::vector<std::string> extra(lines.begin() + feb29 - 24, lines.begin() + feb29);
    for (auto& l : extra) l = with_field(l, 2, "29");
    lines.insert(lines.begin() + feb29, extra.begin(), extra.end());
    EXPECT_EQ(error_of(lines, "leap.epw"), "");
    // Feb 29 with one hour short is a missing hour, not a leap year.
    lines.erase(lines.begin() + feb29 + 23);
    EXPECT_NE(error_of(lines, "short.epw").find("expected 2/29 hour 24, found 3/1 hour 1"), std::string::npos);
}

TEST(WeatherFile, EpwBadInputNamesFileAndLine) {
    const auto good = lines_of(kEpw);
    auto has = [](const std::string& msg, const std::string& part) { return msg.find(part) != std::string::npos; };
    // Truncated file: the last day cut off.
    {
        auto l = good;
        l.resize(l.size() - 24);
        const auto msg = error_of(l, "t.epw");
        EXPECT_TRUE(has(msg, "truncated")) << msg;
    }
    // Truncated record: the last line cut in the middle.
    {
        auto l = good;
        l.back() = l.back().substr(0, 40);
        const auto msg = error_of(l, "r.epw");
        EXPECT_TRUE(has(msg, ":8768: a truncated record")) << msg;
    }
    // A missing hour (Jan 1, hour 5 removed: line 13).
    {
        auto l = good;
        l.erase(l.begin() + 12);
        const auto msg = error_of(l, "m.epw");
        EXPECT_TRUE(has(msg, ":13: expected 1/1 hour 5, found 1/1 hour 6")) << msg;
    }
    // An extra hour (Jan 1, hour 1 repeated) and a line after Dec 31 hour 24.
    {
        auto l = good;
        l.insert(l.begin() + 9, good[8]);
        EXPECT_TRUE(has(error_of(l, "e.epw"), ":10: expected 1/1 hour 2, found 1/1 hour 1"));
        l = good;
        l.push_back(good.back());
        EXPECT_TRUE(has(error_of(l, "x.epw"), ":8769: an extra hour"));
    }
    // A field that does not parse, and one out of its range.
    {
        auto l = good;
        l[100] = with_field(l[100], 14, "7x3");
        EXPECT_TRUE(has(error_of(l, "p.epw"), ":101: direct normal irradiance '7x3' is not"));
        l = good;
        l[100] = with_field(l[100], 6, "85.0");
        EXPECT_TRUE(has(error_of(l, "d.epw"), ":101: dry bulb temperature 85.0 is outside"));
        l = good;
        l[100] = with_field(l[100], 13, "-5");
        EXPECT_TRUE(has(error_of(l, "g.epw"), ":101: global horizontal irradiance -5 is outside"));
    }
    // A LOCATION out of range.
    {
        auto l = good;
        l[0] = with_field(l[0], 6, "95.0");
        EXPECT_TRUE(has(error_of(l, "l.epw"), ":1: latitude 95.0 is outside"));
        l[0] = with_field(good[0], 8, "-16");
        EXPECT_TRUE(has(error_of(l, "z.epw"), ":1: time zone -16 is outside"));
    }
    EXPECT_EQ(error_of(good, "ok.epw"), "");
}

TEST(WeatherFile, WeaBadInputNamesFileAndLine) {
    const auto good = lines_of(kWea);
    auto has = [](const std::string& msg, const std::string& part) { return msg.find(part) != std::string::npos; };
    {
        auto l = good;
        l.resize(4);  // cut inside the header
        EXPECT_TRUE(has(error_of(l, "h.wea"), ":5: the file ends before 'site_elevation'"));
        l = good;
        l.back() = "12 31 23.500 0";
        EXPECT_TRUE(has(error_of(l, "t.wea"), "4 fields, expected 5"));
    }
    {
        auto l = good;
        l.erase(l.begin() + 10);  // 1/1 3.5 missing
        EXPECT_TRUE(has(error_of(l, "m.wea"), ":11: a time step of 2 h"));
        l = good;
        l.insert(l.begin() + 10, good[10]);
        EXPECT_TRUE(has(error_of(l, "e.wea"), ":12: a repeated or out-of-order time"));
    }
    {
        auto l = good;
        l[20] = "1 1 14.500 abc 0";
        EXPECT_TRUE(has(error_of(l, "p.wea"), ":21: direct normal irradiance 'abc' is not"));
        l[20] = "1 1 14.500 100 -3";
        EXPECT_TRUE(has(error_of(l, "r.wea"), ":21: diffuse horizontal irradiance -3 is outside"));
        l = good;
        l[1] = "latitude 91";
        EXPECT_TRUE(has(error_of(l, "l.wea"), ":2: latitude 91 is outside"));
        l = good;
        l[5] = "weather_data_file_units 2";
        EXPECT_TRUE(has(error_of(l, "u.wea"), ":6: weather_data_file_units 2 is outside"));
    }
    EXPECT_EQ(error_of(good, "ok.wea"), "");
}

}  // namespace
