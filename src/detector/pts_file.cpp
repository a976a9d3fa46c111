#include "luxtrace/detector/pts_file.hpp"

#include "luxtrace/core/error.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace luxtrace {

namespace {

// As for mesh vertices (geometry_loader.cpp): beyond this no scene can place a point.
constexpr double kMaxCoordinateM = 1e9;

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
    throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The words of a line, split at blanks.
std::vector<std::string_view> words(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && blank(line[i])) ++i;
        const std::size_t start = i;
        while (i < line.size() && !blank(line[i])) ++i;
        if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
}

double number(const std::string& file, int line, std::string_view word, int column) {
    double value = 0.0;
    const char* begin = word.data();
    if (!word.empty() && word.front() == '+') ++begin;  // from_chars refuses a leading '+'
    const char* end = word.data() + word.size();
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    static const char* const names[] = {"x", "y", "z", "dx", "dy", "dz"};
    if (begin == end || ec != std::errc() || ptr != end)
        fail(file, line,
             std::string("field ") + std::to_string(column + 1) + " (" + names[column] + ") '" + std::string(word) +
                 "' is not a number");
    if (!std::isfinite(value))
        fail(file, line,
             std::string("field ") + std::to_string(column + 1) + " (" + names[column] + ") '" + std::string(word) +
                 "' is not finite");
    return value;
}

}  // namespace

SensorPointList parse_pts(std::string_view text, const std::string& file_name) {
    SensorPointList out;
    int line_no = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t next = text.find('\n', pos);
        if (next == std::string_view::npos) next = text.size();
        const std::string_view line = text.substr(pos, next - pos);
        pos = next + 1;
        ++line_no;
        const std::vector<std::string_view> w = words(line);
        if (w.empty() || w.front().front() == '#') continue;
        if (w.size() != 6)
            fail(file_name, line_no,
                 "expected 6 numbers 'x y z dx dy dz' (a sensor's position and direction), found " +
                     std::to_string(w.size()) + " field(s)");
        double v[6];
        for (int k = 0; k < 6; ++k) v[k] = number(file_name, line_no, w[static_cast<std::size_t>(k)], k);
        for (int k = 0; k < 3; ++k)
            if (!(std::abs(v[k]) <= kMaxCoordinateM))
                fail(file_name, line_no, "the position lies outside the +-1e9 m that luxtrace can place");
        const Vec3 dir(v[3], v[4], v[5]);
        const double len = glm::length(dir);
        if (!(len > 0.0) || !std::isfinite(len))
            fail(file_name, line_no, "the direction (dx dy dz) is zero or too large to normalise");
        out.positions.emplace_back(v[0], v[1], v[2]);
        out.directions.push_back(dir / len);
        out.lines.push_back(line_no);
    }
    if (out.positions.empty())
        fail(file_name, line_no == 0 ? 1 : line_no, "no sensor in the file (expected lines 'x y z dx dy dz')");
    return out;
}

SensorPointList read_pts(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open the sensor-point file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_pts(text.str(), path);
}

}  // namespace luxtrace
