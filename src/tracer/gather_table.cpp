#include "luxtrace/tracer/gather_table.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/cell_geometry.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"

#include <algorithm>
#include <chrono>
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

namespace {

// One part of a grid's gather (cells [first, last)) as doubles, cell by cell: its entries'
// count, then (site, weight) pairs, its form's count, then (a, b, coef) triples.
void pack_gather(const SensorGather& g, std::vector<double>& out) {
    for (std::size_t c = 0; c < g.cells; ++c) {
        out.push_back(static_cast<double>(g.offset[c + 1] - g.offset[c]));
        for (std::size_t i = g.offset[c]; i < g.offset[c + 1]; ++i) {
            out.push_back(static_cast<double>(g.site[i]));
            out.push_back(g.weight_sr[i]);
        }
        out.push_back(static_cast<double>(g.form_offset[c + 1] - g.form_offset[c]));
        for (std::size_t i = g.form_offset[c]; i < g.form_offset[c + 1]; ++i) {
            out.push_back(static_cast<double>(g.form[i].a));
            out.push_back(static_cast<double>(g.form[i].b));
            out.push_back(g.form[i].coef);
        }
    }
}

// The cells pack_gather packed (every part's, in order) appended to g.
void unpack_gather(const std::vector<double>& in, SensorGather& g) {
    auto word = [&](std::size_t i) { return static_cast<std::uint32_t>(in[i]); };
    for (std::size_t at = 0; at < in.size();) {
        const std::size_t entries = static_cast<std::size_t>(in[at++]);
        for (std::size_t i = 0; i < entries; ++i, at += 2) {
            g.site.push_back(word(at));
            g.weight_sr.push_back(in[at + 1]);
        }
        g.offset.push_back(g.site.size());
        const std::size_t terms = static_cast<std::size_t>(in[at++]);
        for (std::size_t i = 0; i < terms; ++i, at += 3) g.form.push_back({word(at), word(at + 1), in[at + 2]});
        g.form_offset.push_back(g.form.size());
        ++g.cells;
    }
}

// Grid det's gather, its cells' rays cast in parts by the ranks (GatherShare): the same as
// one rank casting them all, since each cell's rays are its own stream.
SensorGather shared_sensor_gather(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                                  const SensorGatherOptions& go, std::size_t cells, const GatherShare& share) {
    if (share.parts <= 1 || !share.gather) return sensor_gather(scene, embree, det, go, 0, cells);
    const std::size_t parts = static_cast<std::size_t>(share.parts), part = static_cast<std::size_t>(share.part);
    std::vector<double> mine;
    pack_gather(sensor_gather(scene, embree, det, go, cells * part / parts, cells * (part + 1) / parts), mine);
    // Each part's length, then the parts.
    std::vector<double> sizes(parts, 0.0);
    std::vector<std::size_t> offsets(parts + 1);
    for (std::size_t r = 0; r <= parts; ++r) offsets[r] = r;
    sizes[part] = static_cast<double>(mine.size());
    share.gather(sizes, offsets);
    for (std::size_t r = 0; r < parts; ++r) offsets[r + 1] = offsets[r] + static_cast<std::size_t>(sizes[r]);
    std::vector<double> all(offsets[parts], 0.0);
    std::copy(mine.begin(), mine.end(), all.begin() + static_cast<std::ptrdiff_t>(offsets[part]));
    share.gather(all, offsets);
    SensorGather g;
    g.offset.push_back(0);
    g.form_offset.push_back(0);
    unpack_gather(all, g);
    if (g.cells != cells) throw std::logic_error("gather: the ranks' parts do not make the grid");
    return g;
}

}  // namespace

GatherTable::GatherTable(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout,
                         const GatherShare& share) {
    if (!layout.any_gathered() || !scene.annual) return;
    const auto t0 = std::chrono::steady_clock::now();
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
        const SensorGather g = shared_sensor_gather(scene, embree, det, go, cells, share);
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
    build_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
