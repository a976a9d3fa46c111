#pragma once
// Small text helpers for messages and reports.
#include <string>
#include <vector>

namespace luxtrace {

// "a, b, c": names joined for a message (empty for none).
std::string comma_list(const std::vector<std::string>& names);

}  // namespace luxtrace
