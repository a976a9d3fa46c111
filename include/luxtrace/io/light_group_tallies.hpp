#pragma once
// A result's light groups as the run's tallies (issue 22): each group's own counts
// (/light_groups/NAME) laid out again in a TallyLayout, and the scene as the estimates read
// it (estimate/estimate_scene.hpp), from what the file keeps of it. The run's estimate of a
// light scene (estimate_light_scene) then gives any combination of the groups after the
// run, `luxtrace info --scene`: at a [[light_scene]]'s weights, the run's own figures.
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/estimate/estimate_scene.hpp"
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

class ResultFile;

struct LightGroupTallies {
    std::vector<std::string> groups;  // the light groups' names, by index
    // Every group's surface map is kept (run.group_maps): the layout has the mesh's
    // triangles; otherwise none, and no map is estimated.
    bool group_maps = false;
    // The file's detectors (ResultFile::detector_names(), an observer's eye detector not
    // among them) with each group's counts; the sobol replicates' photons.
    TallyLayout layout;
    std::vector<std::uint64_t> data;
    double e0 = 0.0;  // flux per photon, lm
    std::uint64_t photons = 0;
    // What the estimates read of the scene: no observers, the maintenance factor 1.
    std::vector<double> triangle_area_m2;  // empty without group maps
    std::size_t bands = 1;
    std::vector<Detector> detectors;
    std::vector<double> group_flux_lm;
    std::vector<DaylightSource> daylight;

    // Views of the members above (valid while this is neither moved nor destroyed).
    EstimateScene scene() const;
};

// No groups for the result of a run with one light group. Throws InputError when a group's
// counts do not fit the mesh, the detectors or the other groups.
LightGroupTallies read_light_group_tallies(const ResultFile& file);

}  // namespace luxtrace
