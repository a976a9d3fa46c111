#pragma once
// `luxtrace info RESULT --scene "a=0.5,b=1"`: a combination of the result's light groups
// (issue 22), estimated from each group's own counts in /light_groups without tracing
// again, by the run's own estimate of a light scene (estimate/result_estimates.hpp), with
// exact errors (the groups' photons are disjoint; docs/REFERENCE.md §1).
#include <iosfwd>
#include <string>
#include <vector>

namespace luxtrace {
class ResultFile;

// The weights of `spec` ("NAME=W,NAME=W"), one per group of `groups` (groups not named: 0).
// Throws InputError naming --scene for bad syntax, an unknown or repeated group, or a
// weight that is negative or not a number.
std::vector<double> parse_scene_weights(const std::string& spec, const std::vector<std::string>& groups);

// Prints the combination's global map mean and errors and each detector's mean with its
// error. Throws InputError naming --scene for a file without light groups.
void print_light_scene(const ResultFile& file, const std::string& spec, std::ostream& out);
}  // namespace luxtrace
