#include "luxtrace/tracer/gather_table.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/cell_geometry.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace luxtrace {

std::vector<std::size_t> gather_regions(const Detector& d, std::size_t regions) {
    const CellGeometry geometry{d};
    const std::size_t cells = static_cast<std::size_t>(d.cells());
    std::vector<Vec3> centre(cells);
    for (std::size_t c = 0; c < cells; ++c) centre[c] = geometry.position(c, 0.5, 0.5);
    std::vector<std::size_t> order(cells), region(cells, 0);
    for (std::size_t c = 0; c < cells; ++c) order[c] = c;
    // Split [first, last) of `order` into `parts` regions from `base`.
    auto split = [&](auto&& self, std::size_t first, std::size_t last, std::size_t base, std::size_t parts) -> void {
        if (parts <= 1 || last - first < 2) {
            for (std::size_t i = first; i < last; ++i) region[order[i]] = base;
            return;
        }
        Vec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
        for (std::size_t i = first; i < last; ++i) {
            lo = glm::min(lo, centre[order[i]]);
            hi = glm::max(hi, centre[order[i]]);
        }
        const Vec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        // Ties by index: the same regions on every rank and compiler.
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(first), order.begin() + static_cast<std::ptrdiff_t>(last),
                  [&](std::size_t a, std::size_t b) {
                      return centre[a][axis] != centre[b][axis] ? centre[a][axis] < centre[b][axis] : a < b;
                  });
        const std::size_t mid = first + (last - first) / 2;
        self(self, first, mid, base, parts / 2);
        self(self, mid, last, base + parts / 2, parts / 2);
    };
    split(split, 0, cells, 0, regions);
    return region;
}

GatherTable::GatherTable(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout) {
    if (!layout.any_gathered() || !scene.annual) return;
    const AnnualOptions& o = scene.annual->options;
    patches_ = GatherPatches(scene, o.gather_patch_m);
    const std::size_t sites = 2 * patches_.count();
    // Per patch (either side), its diffuse reflectance over pi: its luminance per lx; over
    // its area too, a unit K's weight in lx per lm.
    site_rho_pi_.resize(patches_.count());
    for (std::size_t t = 0, p = 0; t < scene.triangle_count(); ++t) {
        const double rho = scatter_model(scene.materials[scene.triangle_material[t]], 0).diffuse_reflection;
        const std::size_t n = static_cast<std::size_t>(patches_.cuts(t)) * patches_.cuts(t);
        for (std::size_t k = 0; k < n; ++k, ++p) site_rho_pi_[p] = rho / kPi;
    }
    // Every gathered grid's K, cell by cell (the cells numbered across the grids).
    struct Kept {
        std::uint32_t site, cell;
        double weight;
    };
    std::vector<Kept> kept;
    double largest = 0.0;
    first_cell_.assign(scene.detectors.size(), 0);
    for (std::size_t det = 0; det < scene.detectors.size(); ++det) {
        if (!layout.gathered(det)) continue;
        SensorGatherOptions go;
        go.rays = o.gather_rays;
        go.seed = scene.run.seed;
        go.patches = &patches_;
        go.rays_form = true;
        const std::size_t cells = static_cast<std::size_t>(scene.detectors[det].cells());
        const SensorGather g = sensor_gather(scene, embree, det, go, 0, cells);
        first_cell_[det] = cells_;
        const std::vector<std::size_t> region = gather_regions(scene.detectors[det], TallyLayout::kGatherRegions);
        for (std::size_t c = 0; c < cells; ++c) {
            form_offset_.push_back(form_.size());
            form_.insert(form_.end(), g.form.begin() + static_cast<std::ptrdiff_t>(g.form_offset[c]),
                         g.form.begin() + static_cast<std::ptrdiff_t>(g.form_offset[c + 1]));
        }
        for (std::size_t c = 0; c < cells; ++c) {
            slots_.push_back({layout.detector_gathered(det, c, 0), layout.gathered_column_stride(det),
                              layout.detector_gathered_total(det, 0), region[c]});
            for (std::size_t i = g.offset[c]; i < g.offset[c + 1]; ++i) {
                const std::size_t patch = g.site[i] % patches_.count();
                const double w = g.weight_sr[i] * site_rho_pi_[patch] / patches_.area_m2(patch);
                if (!(w > 0.0)) continue;
                kept.push_back({g.site[i], static_cast<std::uint32_t>(cells_ + c), w});
                largest = std::max(largest, w);
            }
        }
        cells_ += cells;
    }
    form_offset_.push_back(form_.size());
    if (cells_ > UINT32_MAX) throw std::runtime_error("gather: more than 2^32 sensor cells");
    offset_.assign(sites + 1, 0);
    // No sensor sees a diffuse surface: nothing is gathered, in units of 1 lx per lm.
    const double units = largest > 0.0 ? std::ldexp(1.0, kWeightBits) / largest : 1.0;
    unit_lx_per_lm_ = 1.0 / units;
    // By site (a counting sort keeps each site's cells in ascending order).
    for (const Kept& k : kept) ++offset_[k.site + 1];
    for (std::size_t s = 0; s < sites; ++s) offset_[s + 1] += offset_[s];
    entries_.resize(kept.size());
    std::vector<std::size_t> at(offset_.begin(), offset_.end() - 1);
    for (const Kept& k : kept)
        entries_[at[k.site]++] = {k.cell, static_cast<std::uint32_t>(std::lround(k.weight * units))};
}

std::vector<double> GatherTable::rays_rel_var(std::size_t det, std::size_t cells, std::span<const double> site_lx,
                                              std::span<const double> site_arrivals,
                                              std::span<const double> gathered_lx) const {
    std::vector<double> out(cells, 0.0);
    if (first_cell_.size() <= det) return out;
    const std::size_t P = patches_.count();
    auto luminance = [&](std::uint32_t site) { return site_rho_pi_[site % P] * site_lx[site]; };
    for (std::size_t c = 0; c < cells; ++c) {
        const std::size_t g = first_cell_[det] + c;
        double var = 0.0;
        for (std::size_t i = form_offset_[g]; i < form_offset_[g + 1]; ++i) {
            const FormTerm& t = form_[i];
            // L_a^2 from n arrivals overstates its square by its Poisson variance, L_a^2 / n.
            const double n = site_arrivals[t.a];
            const double product = t.a == t.b ? (n > 0.0 ? luminance(t.a) * luminance(t.a) * (1.0 - 1.0 / n) : 0.0)
                                              : luminance(t.a) * luminance(t.b);
            var += t.coef * product;
        }
        out[c] = gathered_lx[c] > 0.0 ? std::max(0.0, var) / (gathered_lx[c] * gathered_lx[c]) : 0.0;
    }
    return out;
}

}  // namespace luxtrace
