#pragma once
// The parts of a result file (docs/REFERENCE.md), one writer each; write_result
// (result_file.cpp) calls them in the file's order. Each writes numbers it is given: the
// counts, rearranged from the tally layout into the file's [.., B] arrays, and the
// estimates of estimate/result_estimates.hpp. A new group of datasets (e.g. per light
// group) is one more writer here, called from write_result, and read in result_data.cpp.
#include "hdf5_file.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/result_file.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace luxtrace {

struct Scene;
struct Detector;

namespace result_parts {

// Root attributes: the format, how the run was made, and the run's totals.
void write_run_info(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                    const RunInfo& info, bool checkpoint);
// /mesh: vertices, triangles, areas, materials.
void write_mesh(hid_t file, const Scene& scene);
// /global: the surface map's counts per triangle side and band, its illuminance and errors.
void write_surface_map(hid_t file, const Scene& scene, const TallyLayout& layout,
                       std::span<const std::uint64_t> tallies, const ResultEstimates& est);
// The surface map's counts in `g`: count_odd, count_even, direct_odd, direct_even and
// sumsq [T, 2, B] (and sobol's replicate_count [T, 2, B, R]) of the map groups
// [first_group, last_group) together.
void write_surface_counts(hid_t g, const Scene& scene, const TallyLayout& layout,
                          std::span<const std::uint64_t> tallies, std::size_t first_group, std::size_t last_group);
// A detector's n_c (sumsq: q_c) per cell and band, [cells][B], of the light groups
// [first_group, last_group) together.
std::vector<std::uint64_t> detector_sums(const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                                         std::size_t detector, std::size_t cells, bool sumsq, std::size_t first_group,
                                         std::size_t last_group);
// A detector's counts in `g`: count and sumsq [ny, nx, B] (and sobol's replicate_count
// [R, ny, nx, B] and replicate_total [R]) of the light groups [first_group, last_group).
void write_detector_counts(hid_t g, const Detector& d, std::size_t detector, std::size_t bands,
                           const TallyLayout& layout, std::span<const std::uint64_t> tallies, std::size_t first_group,
                           std::size_t last_group);
// The estimated maps and the global estimate's attributes in `g`.
void write_surface_estimates(hid_t g, const Scene& scene, const SurfaceMaps& maps, const GlobalEstimate& global);
// A detector's summary: its means and errors over the grid.
void write_detector_summary(hid_t g, const DetectorEstimate& e);
// An observer's UGR and the indirect light it comes from.
void write_ugr(hid_t g, const ObserverEstimate& e);
// /detectors/NAME: counts, values, errors, metrics, task areas and cylinders.
void write_detectors(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                     const ResultEstimates& est);
// /observers/NAME: UGR and the luminaires in view, with the eye detector's counts.
void write_observers(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                     const ResultEstimates& est);
// The whole grid's metrics (Eavg, Emin, Emax, U0; initial and maintained; a
// daylight_factor detector's DF quantiles and EN 17037 verdicts) as attributes of `g`,
// each task area's in g/task_areas/AREA.
void write_task_areas(hid_t g, const Detector& d, const std::vector<IlluminanceMetrics>& initial,
                      const std::vector<IlluminanceMetrics>& maintained,
                      const std::optional<DaylightEstimate>& daylight);
// A daylight_factor detector's daylight_factor and daylight_factor_sigma [ny, nx] (%) and
// daylight_reference_lx (E_h,ext) in `g`; nothing for other detectors.
void write_daylight_map(hid_t g, const Detector& d, const std::optional<DaylightEstimate>& daylight);
// /light_groups/NAME (scenes with more than one light group): each group's own counts.
void write_light_groups(hid_t file, const Scene& scene, const TallyLayout& layout,
                        std::span<const std::uint64_t> tallies);
// /light_scenes/NAME: each [[light_scene]]'s maps, detectors and observers with their errors.
void write_light_scenes(hid_t file, const Scene& scene, const ResultEstimates& est);
// /daylight (scenes with sun or sky lights): the site, time and each daylight source.
void write_daylight(hid_t file, const Scene& scene);
// /annual (scenes with [annual]): hours, skies, and per sensor grid the hourly values,
// the coefficients' counts and the annual metrics with their errors.
void write_annual(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                  const ResultEstimates& est);
// /history: one row per reduction.
void write_history(hid_t file, const std::vector<HistoryRow>& history, const RunInfo& info);
// /checkpoint: the state a restart continues from.
void write_checkpoint(hid_t file, const TallyLayout& layout, const CheckpointData& checkpoint);

// Every part of a result (with `checkpoint`, a checkpoint) in the file's order.
void write_all(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
               const RunInfo& info, const ResultEstimates& estimates, const std::vector<HistoryRow>& history,
               const CheckpointData* checkpoint);
// A tally checkpoint's parts: the root attributes, /history and /checkpoint.
void write_tally_checkpoint(hid_t file, const Scene& scene, const TallyLayout& layout, const RunInfo& info,
                            const std::vector<HistoryRow>& history, const CheckpointData& checkpoint);

}  // namespace result_parts
}  // namespace luxtrace
