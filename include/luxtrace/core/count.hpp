#pragma once
// Photon counts as users write them: 1000000, 1e6, "100M", "2.5k", "3G".
#include <cstdint>
#include <optional>
#include <string>

namespace luxtrace {

// The count, or nullopt if the text is not a non-negative whole number.
std::optional<std::uint64_t> parse_count(const std::string& text);

}  // namespace luxtrace
