#include "luxtrace/core/count.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace luxtrace {

std::optional<std::uint64_t> parse_count(const std::string& text) {
    if (text.empty()) return std::nullopt;
    // Plain digits exactly (a double would round counts above 2^53).
    if (text.find_first_not_of("0123456789") == std::string::npos) {
        errno = 0;
        const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
        if (errno == ERANGE) return std::nullopt;
        return static_cast<std::uint64_t>(v);
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str()) return std::nullopt;
    double mult = 1.0;
    const std::string suffix(end);
    if (suffix == "k" || suffix == "K") mult = 1e3;
    else if (suffix == "M") mult = 1e6;
    else if (suffix == "G" || suffix == "B") mult = 1e9;
    else if (suffix == "T") mult = 1e12;
    else if (!suffix.empty()) return std::nullopt;
    const double total = v * mult;
    if (!std::isfinite(total) || total < 0.0 || total > 1.8e19 || total != std::floor(total)) return std::nullopt;
    return static_cast<std::uint64_t>(total);
}

}  // namespace luxtrace
