#pragma once
// Text helpers shared by the photometric file readers (ies.cpp, eulumdat.cpp).
#include "luxtrace/core/error.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace luxtrace::detail {

std::string fmt(double v);
std::string_view trim(std::string_view s);
bool iequals(std::string_view a, std::string_view b);
[[noreturn]] void fail_at(const std::string& file, int line, const std::string& what);
// A whole number or decimal ("5000.", ".5", "+1", "1e3"); nullopt if s is not one.
// With `decimal_comma`, a single ',' counts as the decimal point (EULUMDAT files from
// some tools write "7,9").
std::optional<double> parse_number(std::string_view s, bool decimal_comma = false);

// The words of lines[first..], split at blanks and at any of `extra_separators`, each
// with its 1-based line number.
struct Token {
    std::string text;
    int line;
};
std::vector<Token> tokens_of(const std::vector<std::string>& lines, std::size_t first,
                             std::string_view extra_separators = {});

// The file's lines without their line ends. A DOS end-of-file byte (0x1A) ends the text:
// old tools wrote one after the last line. Throws InputError if the file cannot be read.
std::vector<std::string> read_lines(const std::filesystem::path& file, const char* what);

}  // namespace luxtrace::detail
