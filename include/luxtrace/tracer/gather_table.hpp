#pragma once
// The light after a diffuse reflection, gathered to the annual grids' sensors ([annual]
// indirect = "gather", issue 37, docs/ANNUAL.md "Gathering the light after a reflection").
// A photon of flux e0 arriving on a patch of area A and diffuse reflectance rho makes the
// patch's Lambertian luminance e0 rho / (pi A) on average (whatever it does next), and a
// sensor that sees the patch through a projected solid angle K (tracer/sensor_gather.hpp)
// gets K times that: each arrival adds e0 K rho / (pi A) to every sensor that sees the
// patch. The sum over photons is unbiased for the light after a diffuse reflection as far
// as each patch's luminance is uniform over it (patches small against the light's
// gradients, gather_patches.hpp); the discs then count only what did not come off a
// diffuse reflection (a registration after one, or after one and panes the gather passes
// too, counts no more: TallyDims::gathered).
//
// Tallies stay integers (any order of addition gives the same bits): a weight is stored as
// round(W K rho / (pi A)) units, W = 2^kWeightBits / the table's largest weight, so that a
// weight loses at most half a unit (about 3e-8 of the largest). The table is a pure function
// of the scene, its seed and the options: every rank builds the same.
#include "luxtrace/tally/photon_tally.hpp"
#include "luxtrace/tracer/gather_patches.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace luxtrace {

class EmbreeScene;
class TallyLayout;
struct Detector;
struct Scene;

// How the ranks share casting the gather's rays, as AnnualSkyShare shares the year's skies:
// this rank casts the rays of part `part` of `parts` of every grid's cells, and `gather`
// (an all-gather in place: each rank holds its part [offsets[part], offsets[part + 1]) of
// `values`) gives every rank every part; every rank then builds the same table. Without
// `gather`, one rank casts them all.
struct GatherShare {
    int part = 0, parts = 1;
    std::function<void(std::vector<double>& values, const std::vector<std::size_t>& offsets)> gather;
};

// Each cell's region of a gathered grid (GatherSlot::region), `regions` a power of two:
// the cells' centres halved at the median along the longest side of their bounds, each
// half again, until `regions` parts of equal counts (to one cell), near cells together.
// The regions' totals are what the replicates' common draws keep apart
// (estimate/gather_factors.hpp): the back of a room moves with the back, not with the window.
std::vector<std::size_t> gather_regions(const Detector& d, std::size_t regions);

class GatherTable {
public:
    static constexpr int kWeightBits = 24;
    GatherTable() = default;  // gathers nothing
    // The grids `layout` keeps gathered (TallyDims::gathered), their cells on every core.
    GatherTable(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout,
                const GatherShare& share = {});

    bool empty() const { return cells_ == 0; }
    const GatherPatches& patches() const { return patches_; }
    // Triangle `tri`'s side `side` at (u, v): its site (side * patches + patch).
    std::size_t site(std::size_t tri, std::size_t side, float u, float v) const {
        return side * patches_.count() + patches_.patch(tri, u, v);
    }
    std::span<const GatherEntry> entries(std::size_t site) const {
        return {entries_.data() + offset_[site], offset_[site + 1] - offset_[site]};
    }
    std::size_t cells() const { return cells_; }
    // Per gathered cell, its slots in the layout.
    std::span<const GatherSlot> slots() const { return slots_; }
    // lx per lm of one unit: 1 / W.
    double unit_lx_per_lm() const { return unit_lx_per_lm_; }
    // Detector det's cells' relative variance of their gathered light from the rays'
    // sampling (SensorGather::form), given each site's irradiance `site_lx` from its
    // `site_arrivals` (sites as site(): the run's arrivals per site, TallyLayout::gather_site;
    // a square's Poisson noise taken out) and each cell's gathered light `gathered_lx` with
    // those irradiances; one figure for all of a cell's light groups and hours.
    std::vector<double> rays_rel_var(std::size_t det, std::size_t cells, std::span<const double> site_lx,
                                     std::span<const double> site_arrivals, std::span<const double> gathered_lx) const;
    std::size_t sites() const { return 2 * patches_.count(); }
    double site_area_m2(std::size_t site) const { return patches_.area_m2(site % patches_.count()); }
    // Wall seconds this rank spent on the table (its share of the rays, the all-gather).
    double build_s() const { return build_s_; }

private:
    GatherPatches patches_;
    std::vector<std::size_t> offset_;  // per site
    std::vector<GatherEntry> entries_;
    std::vector<GatherSlot> slots_;  // per gathered cell
    std::size_t cells_ = 0;
    double unit_lx_per_lm_ = 0.0;
    std::vector<std::size_t> first_cell_;  // per detector, its first gathered cell
    // Per gathered cell, the rays' variance form (SensorGather::form), terms
    // [form_offset_[c], form_offset_[c + 1]).
    std::vector<std::size_t> form_offset_;
    std::vector<FormTerm> form_;
    std::vector<double> site_rho_pi_;  // per patch, rho / pi: a site's luminance per lx
    double build_s_ = 0.0;
};

}  // namespace luxtrace
