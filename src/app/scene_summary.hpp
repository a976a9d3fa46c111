#pragma once
// What `luxtrace check` prints about a loaded scene.
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace luxtrace {
struct Scene;
void print_scene_summary(const Scene& scene, const std::vector<std::string>& warnings, std::ostream& out);
}  // namespace luxtrace
