#pragma once
// What `luxtrace run` prints at the end of a run and `luxtrace info` prints about a result
// or checkpoint file: read from the file, so both print the same.
#include <iosfwd>

namespace luxtrace {
class ResultFile;
void print_result_summary(const ResultFile& result, std::ostream& out);
}  // namespace luxtrace
