#pragma once
// The scene as the estimates read it besides the tallies: the surface's triangle areas,
// the detectors and observers, and the lights summed per light group (their flux, the
// E_h,ext that daylight factors are relative to, the maintenance factor). A run's comes from
// its Scene (estimate_scene); a result file's from what the file keeps of it
// (io/light_group_tallies.hpp), so that a combination of light groups is estimated after
// the run by the run's own code (`luxtrace info --scene`).
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/glare/observer.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

// A light that daylight factors are relative to: its group and the illuminance it alone
// gives an unobstructed horizontal plane (Light::unobstructed_horizontal_lx).
struct DaylightSource {
    std::size_t group = 0;
    double unobstructed_horizontal_lx = 0.0;
};

// The spans view the scene's (or the file's) vectors, which must outlive it.
struct EstimateScene {
    std::span<const double> triangle_area_m2;
    std::size_t bands = 1;
    std::span<const Detector> detectors;     // the tallies' detectors, in their order
    std::span<const Observer> observers;     // each with its eye detector among `detectors`
    std::vector<std::size_t> light_group;    // per light (GlareSource::light): its group
    std::vector<double> group_flux_lm;       // per light group
    std::vector<DaylightSource> daylight;    // the lights that give daylight, in order
    double maintenance_factor = 1.0;         // the lights' flux-weighted one
    bool maintenance_factor_uniform = true;  // ... which every light shares
};

// A run's: views of the scene's vectors, its lights summed.
EstimateScene estimate_scene(const Scene& scene);

// Every light group's flux (lm), per Scene::light_groups.
std::vector<double> light_group_flux_lm(const Scene& scene);
// E_h,ext of daylight factors: the sum over the daylight sources of their unobstructed
// horizontal illuminance, each times its group's weight (empty weights: the plain run, all
// at 1).
double daylight_reference_lx(const EstimateScene& scene, std::span<const double> weights);

}  // namespace luxtrace
