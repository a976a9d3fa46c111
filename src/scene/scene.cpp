#include "luxtrace/scene/scene.hpp"

#include <algorithm>

namespace luxtrace {

double Scene::total_area_m2() const {
    double s = 0.0;
    for (double a : triangle_area_m2) s += a;
    return s;
}

double Scene::ray_epsilon_m() const {
    // Embree works relative to the scene's centre (EmbreeScene), so the scene's size,
    // not its distance from the origin, sets the precision.
    return 2e-6 * std::max(glm::length(bounds_max - bounds_min), 1e-3);
}

}  // namespace luxtrace
