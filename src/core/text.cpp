#include "luxtrace/core/text.hpp"

namespace luxtrace {

std::string comma_list(const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
}

}  // namespace luxtrace
