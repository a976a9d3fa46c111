#pragma once
// An annual run's figures per detector (issue 24, docs/ANNUAL.md): every hour's illuminance
// and direct sun with their standard errors (annual_coefficients.hpp), and the annual metrics
// with their errors, biases and verdict flip probabilities (stats/annual_metrics.hpp).
#include "luxtrace/estimate/annual_coefficients.hpp"
#include "luxtrace/stats/annual_metrics.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

struct AnnualDetectorEstimate {
    AnnualSeries value, sigma;
    AnnualEstimate metrics;
    // [annual] direct = "shadow_rays": per cell, the year's direct exposure by shadow rays
    // (the sum of its direct coefficients, lx h) from the sky patches and the ground, and
    // from the suns, with their standard errors; empty otherwise. The plain detector then
    // holds the rest: the three add to the year's exposure.
    std::vector<double> direct_sky_lx_h, direct_sky_sigma_lx_h, direct_sun_lx_h, direct_sun_sigma_lx_h;
    // [annual] indirect = "gather": the same for the gathered light after a diffuse
    // reflection (the plain detector then holds what came off other surfaces).
    std::vector<double> gather_sky_lx_h, gather_sky_sigma_lx_h, gather_sun_lx_h, gather_sun_sigma_lx_h;
    // ... and per cell the relative error of its gathered light from the gather's own rays
    // (in the sigmas above and in every hour's).
    std::vector<double> gather_rays_sigma_rel;
};

// The post-processing's blocks of cells (each its coefficients, series and replicates on one
// core): a block starts at a multiple of this.
inline constexpr std::size_t kAnnualBlockCells = 32;

// Where the grids' hourly series go block by block, from any core, instead of into
// AnnualDetectorEstimate::value and sigma (a whole building's would not fit in memory,
// io/annual_series_file.hpp): grid `det`, its cells [first, first + value.sensors), every
// hour. Those estimates then hold the series' hours and sensors and no values.
using AnnualSeriesSink =
    std::function<void(std::size_t det, std::size_t first, const AnnualSeries& value, const AnnualSeries& sigma)>;
// A grid's four hourly series: the illuminance, the direct sun, and their errors.
enum class AnnualSeriesKind : std::size_t { total = 0, direct = 1, total_sigma = 2, direct_sigma = 3 };
inline constexpr std::size_t kAnnualSeriesKinds = 4;
// ... and where they are read back: hours [h0, h1) of every cell hour-major, or cells
// [first, first + count) of every hour cell-major.
struct AnnualSeriesSource {
    std::function<void(std::size_t det, AnnualSeriesKind kind, std::size_t h0, std::size_t h1, std::span<float> out)>
        read_hours;
    std::function<void(std::size_t det, AnnualSeriesKind kind, std::size_t first, std::size_t count,
                       std::span<float> out)>
        read_cells;
    explicit operator bool() const { return static_cast<bool>(read_hours); }
};

// The hours LM-83 and EN 17037 count (occupied; EN 17037's daylight hours: the half of the
// year with the most diffuse horizontal illuminance, annual_metrics.hpp).
AnnualHours annual_hours(const AnnualSetup& annual);

// One sensor grid (Scene::detectors[det], annual/annual_grid.hpp): its metrics with their
// errors from `replicates` replicate years (0: the values alone), and, with `series`, every
// hour's values and their errors (value, sigma). The replicates' draws depend on the run's
// seed and the detector, so a target and the result agree. `direct`: the run's direct
// coefficients by shadow rays (empty with [annual] direct = "photons").
AnnualDetectorEstimate estimate_annual_grid(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                            std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                            int replicates, bool series, const AnnualDirect& direct,
                                            const AnnualSeriesSink* sink = nullptr);

// The gathered year's exposure and its errors (AnnualDetectorEstimate::gather_*) from the
// whole grid's tallies; nothing for a grid that gathers nothing.
void annual_gather_year(const Scene& scene, std::size_t det, const TallyLayout& layout,
                        std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                        const DirectCoefficients* direct, AnnualDetectorEstimate& e);

// The post-processing shared among parts (ranks, docs/ANNUAL.md step 7): each part runs the
// blocks of its cells and rank 0 merges the parts. The figures are those of
// estimate_annual_grid with series, to the bit.
//
// The cells part `part` of `parts` takes: whole blocks, [first, last).
struct AnnualCellRange {
    std::size_t first = 0, last = 0;
};
AnnualCellRange annual_part_cells(std::size_t cells, int part, int parts);
// The grid's dark rates (AnnualCoefficients::dark_rates), which every part needs: from the
// whole grid's counts.
AnnualDarkRates annual_dark_rates(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                  std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                  const DirectCoefficients* direct);
// A part's cells' hourly series (hours x its cells) and metric sums (AnnualMetricDraws::words).
struct AnnualGridPart {
    AnnualCellRange cells;
    AnnualSeries value, sigma;
    std::vector<std::uint64_t> metric_words;
};
// `data` needs the words of the part's cells only, `direct` (null without shadow rays) the
// part's cells' coefficients (sized for the whole grid).
AnnualGridPart estimate_annual_part(const Scene& scene, std::size_t det, const TallyLayout& layout,
                                    std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                    int replicates, AnnualCellRange cells, const AnnualDarkRates& dark,
                                    const DirectCoefficients* direct);
// The grid's estimate from parts covering its cells, added one by one in any order;
// `direct` the whole grid's coefficients.
class AnnualPartsMerge {
public:
    // `sink`: where the parts' series go (AnnualSeriesSink), or null: into the estimate.
    AnnualPartsMerge(const Scene& scene, std::size_t det, int replicates, const DirectCoefficients* direct,
                     const AnnualSeriesSink* sink = nullptr);
    void add(const AnnualGridPart& part);
    AnnualDetectorEstimate finish();

private:
    AnnualHours hours_;
    std::size_t det_ = 0, cells_ = 0;
    const AnnualSeriesSink* sink_ = nullptr;
    AnnualMetricDraws sums_;
    AnnualDetectorEstimate estimate_;
};

// Per Scene::detectors (empty for a scene without [annual]; std::nullopt for detectors that
// are not sensor grids). e0 = flux per photon, photons = N. `replicates` for the metrics'
// errors (0: no errors, for checkpoints).
std::vector<std::optional<AnnualDetectorEstimate>> estimate_annual(const Scene& scene, const TallyLayout& layout,
                                                                   std::span<const std::uint64_t> data, double e0,
                                                                   std::uint64_t photons, int replicates,
                                                                   const AnnualDirect& direct,
                                                                   const AnnualSeriesSink* sink = nullptr);

}  // namespace luxtrace
