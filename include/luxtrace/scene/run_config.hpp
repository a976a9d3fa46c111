#pragma once
// The [run] table: budgets, targets and output. Command-line options override it.
#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

enum class Averaging { quadratic, arithmetic };

// One [[run.target]]: a stop criterion on the global map or on (part of) a detector.
struct Target {
    std::string on = "global";  // as written in the scene file
    std::string detector;       // empty for the global map
    // Cell range [i0, i1) x [j0, j1) on the detector; i1 = j1 = 0 means the whole grid.
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0;
    double relative_error = 0.0;  // 0 = not set
    double absolute_error = 0.0;
    double photons_received = 0.0;
    Averaging averaging = Averaging::quadratic;
    // A [[light_scene]] by name: the target is on that combination of the groups. Empty:
    // every group at full output, the plain run.
    std::string light_scene;
    // `on = "annual:DETECTOR:METRIC"` (annual runs): the error of a grid's annual metric
    // (stats/annual_metrics.hpp, kAnnualTargetFigures), the detector in `detector`.
    std::string annual_metric;
};

// Seconds between reductions and progress lines when the scene and the command line
// leave report_every_s out (or set 0).
inline constexpr double kDefaultReportEvery_s = 2.0;

struct RunConfig {
    std::uint64_t seed = 1;
    std::uint64_t photons = 1'000'000;
    double time_limit_s = 0.0;  // 0 = none
    double report_every_s = kDefaultReportEvery_s;
    // Reductions every this many photons (per run, split evenly over the ranks) instead
    // of every report_every_s: the history is then the same on any machine. 0 = by time.
    std::uint64_t report_every_photons = 0;
    std::string output;               // result path (relative to the working directory)
    double checkpoint_every_s = 0.0;  // 0 = none
    std::string checkpoint;           // checkpoint path
    std::string sampler = "random";
    std::uint32_t replicates = 8;  // sobol: independent randomisations (docs/QMC.md)
    int max_bounces = 10000;       // safety bound for lossless mirror traps
    // Keep the surface map per light group (80 bytes per triangle and band per group);
    // false keeps one map of all groups together, and light scenes then have detectors only.
    bool group_maps = true;
    // Embree's BVH build: "auto" (low from kLowBvhTriangles triangles, else high), "low",
    // "medium" or "high" (embree_scene.hpp; docs/SCALING.md measures each).
    std::string bvh_quality = "auto";
    std::vector<Target> targets;
};

}  // namespace luxtrace
