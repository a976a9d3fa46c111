#pragma once
// Small text helpers for messages and reports.
#include <string>
#include <vector>

namespace luxtrace {

// "a, b, c": names joined for a message (empty for none).
std::string comma_list(const std::vector<std::string>& names);
// The shortest decimal text that reads back as exactly x (7.5, 8760, 0.800000011920929).
std::string shortest_decimal(double x);

}  // namespace luxtrace
