#include "luxtrace/core/text.hpp"

#include <charconv>

namespace luxtrace {

std::string comma_list(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

std::string shortest_decimal(double x) {
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

}  // namespace luxtrace
