#pragma once
// What `luxtrace check` prints about a loaded scene, and the run's one-line description of
// its lights.
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {
struct Scene;
void print_scene_summary(const Scene& scene, const std::vector<std::string>& warnings, std::ostream& out);
// "3 lights", or for an annual scene, whose lights are thousands of sky patches and suns
// (docs/ANNUAL.md), "145 sky patches, ground, 3925 suns".
std::string describe_lights(const Scene& scene);
}  // namespace luxtrace
