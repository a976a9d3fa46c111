#pragma once
// Cheap checks of a loaded scene by tracing a few rays per light, for `luxtrace check`:
// lights whose photons can only die at once, or mostly leave the scene.
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
class EmbreeScene;

std::vector<std::string> probe_scene(const Scene& scene, const EmbreeScene& embree, int rays_per_light = 1024);

}  // namespace luxtrace
