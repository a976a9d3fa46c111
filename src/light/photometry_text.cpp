#include "photometry_text.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace luxtrace::detail {

std::string fmt(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

std::string_view trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r\f\v");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t\r\f\v");
    return s.substr(b, e - b + 1);
}

bool iequals(std::string_view a, std::string_view b) {
    return std::ranges::equal(a, b, [](char x, char y) {
        return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
    });
}

void fail_at(const std::string& file, int line, const std::string& what) {
    throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

std::optional<double> parse_number(std::string_view s, bool decimal_comma) {
    s = trim(s);
    std::string buf;
    if (decimal_comma && std::count(s.begin(), s.end(), ',') == 1 && s.find('.') == std::string_view::npos) {
        buf.assign(s);
        buf[buf.find(',')] = '.';
        s = buf;
    }
    if (s.size() > 1 && s.front() == '+') s.remove_prefix(1);  // from_chars rejects '+'
    if (s.empty()) return std::nullopt;
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::vector<Token> tokens_of(const std::vector<std::string>& lines, std::size_t first,
                             std::string_view extra_separators) {
    const std::string separators = " \t\r\f\v" + std::string(extra_separators);
    std::vector<Token> tokens;
    for (std::size_t k = first; k < lines.size(); ++k) {
        const std::string_view l = lines[k];
        std::size_t pos = 0;
        while (pos < l.size()) {
            const auto b = l.find_first_not_of(separators, pos);
            if (b == std::string_view::npos) break;
            auto e = l.find_first_of(separators, b);
            if (e == std::string_view::npos) e = l.size();
            tokens.push_back({std::string(l.substr(b, e - b)), static_cast<int>(k) + 1});
            pos = e;
        }
    }
    return tokens;
}

std::vector<std::string> read_lines(const std::filesystem::path& file, const char* what) {
    const std::string name = file.string();
    std::error_code ec;
    if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
        throw InputError(name + ": not a regular file");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open " + what);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (const auto eof = text.find('\x1a'); eof != std::string::npos) text.resize(eof);
    std::vector<std::string> lines;
    std::size_t pos = 0;
    while (pos < text.size()) {
        auto e = text.find('\n', pos);
        if (e == std::string::npos) e = text.size();
        std::string l = text.substr(pos, e - pos);
        if (!l.empty() && l.back() == '\r') l.pop_back();
        lines.push_back(std::move(l));
        pos = e + 1;
    }
    return lines;
}

}  // namespace luxtrace::detail
