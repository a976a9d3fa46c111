#include "luxtrace/stats/estimates.hpp"

#include "luxtrace/core/parallel.hpp"
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/stats/global_sums.hpp"
#include "luxtrace/tally/message_packing.hpp"
#include "side_terms.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace luxtrace {

namespace {
using namespace side_terms;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr std::size_t kTriangleGrain = 4096;  // triangles per task (core/parallel.hpp)

// One detector's counts with the error of a cell, a range or the whole grid: eq. (8) from
// n_c and q_c, or with sobol the spread of the replicate means instead (docs/QMC.md).
class DetectorCounts {
public:
    DetectorCounts(const Detector& det, std::size_t di, const WeightedTallies& w, double e0, std::uint64_t photons)
        : det_(det), di_(di), w_(w), bands_(w.layout().bands()), per_count_(e0 * det.value_per_lm()),
          inv_n_(photons > 0 ? 1.0 / static_cast<double>(photons) : 0.0), replicates_(w.layout().replicates()),
          rep_photons_(replicate_photons(w)), rep_sums_(replicates_) {}

    const Detector& detector() const { return det_; }
    std::size_t bands() const { return bands_; }
    std::size_t replicates() const { return replicates_; }
    double per_count() const { return per_count_; }  // a count's value (lx or cd/m^2)
    double cell_n(int c, std::size_t b) const { return w_.cell_n(di_, c, b); }
    double cell_q(int c, std::size_t b) const { return w_.cell_q(di_, c, b); }
    double replicate_n(std::size_t rep, int c, std::size_t b) const { return w_.replicate_n(di_, rep, c, b); }

    // Eq. (8) for one cell from its n_c and q_c.
    double rel(double n, double q) const { return n > 0.0 ? std::sqrt(std::max(0.0, q / (n * n) - inv_n_)) : kNaN; }
    // sobol: `slot(r)` gives the replicate-r count of what is estimated; the bands of a
    // cell are summed by calling it once per band.
    template <class Slot>
    double replicate_rel(Slot&& slot) {
        for (std::size_t q = 0; q < replicates_; ++q) rep_sums_[q] = slot(q);
        const ReplicateEstimate e = replicate_estimate(rep_sums_, rep_photons_);
        return e.mean > 0.0 ? e.sigma / e.mean : kNaN;
    }
    // Cell c's relative error over bands [b0, b1), whose counts are n and q.
    double cell_rel(int c, std::size_t b0, std::size_t b1, double n, double q) {
        if (replicates_ == 0) return rel(n, q);
        return replicate_rel([&](std::size_t rep) {
            double sum = 0.0;
            for (std::size_t b = b0; b < b1; ++b) sum += replicate_n(rep, c, b);
            return sum;
        });
    }
    // Cell c summed over its bands (a photon has one band, so n and q add).
    void band_sums(int c, double& n, double& q) const {
        n = q = 0.0;
        for (std::size_t b = 0; b < bands_; ++b) {
            n += cell_n(c, b);
            q += cell_q(c, b);
        }
    }
    // The whole detector as one cell.
    double total_n() const { return w_.total_n(di_); }
    double total_rel() {
        return replicates_ == 0 ? rel(w_.total_n(di_), w_.total_q(di_))
                                : replicate_rel([&](std::size_t rep) { return w_.replicate_total_n(di_, rep); });
    }
    std::uint64_t received() const { return w_.received(di_); }

private:
    const Detector& det_;
    std::size_t di_;
    const WeightedTallies& w_;
    std::size_t bands_;
    double per_count_, inv_n_;
    std::size_t replicates_;
    std::vector<std::uint64_t> rep_photons_;
    std::vector<double> rep_sums_;  // replicate_rel's scratch
};

// Every cell and band: its value and relative error, eq. (8).
void estimate_cells(DetectorCounts& d, DetectorEstimate& out) {
    const std::size_t nb = d.bands();
    out.value.resize(static_cast<std::size_t>(d.detector().cells()) * nb);
    out.sigma_rel.resize(out.value.size());
    for (int c = 0; c < d.detector().cells(); ++c)
        for (std::size_t b = 0; b < nb; ++b) {
            const double n = d.cell_n(c, b);
            const double q = d.cell_q(c, b);
            out.value[c * nb + b] = n * d.per_count();
            out.sigma_rel[c * nb + b] = d.cell_rel(c, b, b + 1, n, q);
        }
}

// Eq. (9) over the range on band-summed cells.
void estimate_range(DetectorCounts& d, const CellRange& r, DetectorEstimate& out) {
    double sum_l = 0.0, sum_l2 = 0.0, sum_s2 = 0.0, registrations = 0.0;
    const int k = (r.i1 - r.i0) * (r.j1 - r.j0);
    for (int j = r.j0; j < r.j1; ++j)
        for (int i = r.i0; i < r.i1; ++i) {
            const int c = j * d.detector().nx + i;
            double n, q;
            d.band_sums(c, n, q);
            const double l = n * d.per_count();
            const double sigma_c = n > 0.0 ? d.cell_rel(c, 0, d.bands(), n, q) * l : 0.0;
            sum_l += l;
            sum_l2 += l * l;
            sum_s2 += sigma_c * sigma_c;
            registrations += n;
        }
    // A light scene's registrations are weighted; a count target reads the plain run's.
    out.registrations = static_cast<std::uint64_t>(std::llround(registrations));
    out.mean_arithmetic = sum_l / k;
    out.mean_quadratic = std::sqrt(sum_l2 / k);
    out.sigma_abs = std::sqrt(sum_s2 / k);
    out.sigma_rel_arithmetic = out.mean_arithmetic > 0.0 ? out.sigma_abs / out.mean_arithmetic : kNaN;
    out.sigma_rel_quadratic = out.mean_quadratic > 0.0 ? out.sigma_abs / out.mean_quadratic : kNaN;
}

// A task area's Eavg error from the replicate spread of its sum (sobol); without
// replicates illuminance_metrics combines the cells' errors as independent (random).
std::optional<double> task_area_mean_sigma(DetectorCounts& d, const std::vector<double>& v, const TaskArea& a) {
    if (d.replicates() == 0) return std::nullopt;
    const int nx = d.detector().nx;
    const double cells = (a.i1 - a.i0) * (a.j1 - a.j0);
    double area_sum = 0.0;
    for (int j = a.j0; j < a.j1; ++j)
        for (int i = a.i0; i < a.i1; ++i) area_sum += v[j * nx + i];
    return area_sum / cells * d.replicate_rel([&](std::size_t rep) {
        double sum = 0.0;
        for (int j = a.j0; j < a.j1; ++j)
            for (int i = a.i0; i < a.i1; ++i)
                for (std::size_t b = 0; b < d.bands(); ++b) sum += d.replicate_n(rep, j * nx + i, b);
        return sum;
    });
}

// Eavg, Emin, Emax, U0 of the whole grid and of each task area, from the band-summed
// cells and their absolute errors; the whole grid's Eavg error is the exact one of the
// detector's mean.
void estimate_illuminance_metrics(DetectorCounts& d, DetectorEstimate& out) {
    const Detector& det = d.detector();
    std::vector<double> v(det.cells()), s(det.cells());
    for (int c = 0; c < det.cells(); ++c) {
        double n, q;
        d.band_sums(c, n, q);
        v[c] = n * d.per_count();
        s[c] = n > 0.0 ? d.cell_rel(c, 0, d.bands(), n, q) * v[c] : kNaN;
    }
    out.metrics.push_back(
        illuminance_metrics(v, s, det.nx, TaskArea{"", 0, det.nx, 0, det.ny}, out.mean_value * out.mean_sigma_rel));
    for (const TaskArea& a : det.task_areas)
        out.metrics.push_back(illuminance_metrics(v, s, det.nx, a, task_area_mean_sigma(d, v, a)));
    out.summed_value = std::move(v);
    out.summed_sigma = std::move(s);
}

}  // namespace

std::vector<double> side_illuminance_lx(const WeightedTallies& w, std::span<const double> area, double e0) {
    const TallyLayout& L = w.layout();
    std::vector<double> e(L.sides());
    for_each_index(L.triangles(), kTriangleGrain, [&](std::size_t t) {
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side)
            e[t * TallyLayout::kSides + side] = side_count(w, L.side_index(t, side)) * e0 / area[t];
    });
    return e;
}

std::vector<double> side_sigma_lx(const WeightedTallies& w, std::span<const double> area, double e0,
                                  std::uint64_t photons) {
    const TallyLayout& L = w.layout();
    std::vector<double> sigma(L.sides(), kNaN);
    if (photons == 0) return sigma;
    const double n = static_cast<double>(photons);
    for_each_index(L.triangles(), kTriangleGrain, [&](std::size_t t) {
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side) {
            const std::size_t i = L.side_index(t, side);
            sigma[t * TallyLayout::kSides + side] = side_sigma_counts(side_count(w, i), side_sumsq(w, i), n) * e0 /
                                                    area[t];
        }
    });
    return sigma;
}

std::vector<double> side_replicate_sigma_lx(const WeightedTallies& w, std::span<const double> area, double e0,
                                            std::uint64_t photons) {
    const TallyLayout& L = w.layout();
    if (L.replicates() == 0) return {};
    std::vector<double> sigma(L.sides(), kNaN);
    if (photons == 0) return sigma;
    const double n = static_cast<double>(photons);
    const std::vector<std::uint64_t> rep_photons = replicate_photons(w);
    tbb::enumerable_thread_specific<std::vector<double>> scratch(L.replicates());
    for_each_index(L.triangles(), kTriangleGrain, [&](std::size_t t) {
        std::vector<double>& sums = scratch.local();
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side)
            sigma[t * TallyLayout::kSides + side] =
                side_replicate_sigma_counts(w, L.side_index(t, side), sums, rep_photons, n) * e0 / area[t];
    });
    return sigma;
}

SurfaceMaps surface_maps(const WeightedTallies& w, std::span<const double> area, double e0, std::uint64_t photons) {
    const TallyLayout& L = w.layout();
    const std::size_t T = L.triangles(), B = L.bands();
    constexpr std::size_t kS = TallyLayout::kSides;
    auto slot_of = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        return w.side(L.side_index(t, side), b, s);
    };
    SurfaceMaps m;
    m.illuminance_lx.resize(T * kS * B);
    m.illuminance_direct_lx.resize(T * kS * B);
    for_each_index(T, kTriangleGrain, [&](std::size_t t) {
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b) {
                const double k = e0 / area[t];
                const std::size_t i = (t * kS + side) * B + b;
                m.illuminance_lx[i] = k * (slot_of(t, side, b, TallyLayout::kCountOdd) +
                                           slot_of(t, side, b, TallyLayout::kCountEven));
                m.illuminance_direct_lx[i] = k * (slot_of(t, side, b, TallyLayout::kDirectOdd) +
                                                  slot_of(t, side, b, TallyLayout::kDirectEven));
            }
    });
    m.odd_even_difference_lx.resize(T * kS);
    for_each_index(T, kTriangleGrain, [&](std::size_t t) {
        for (std::size_t side = 0; side < kS; ++side) {
            double d = 0.0;
            for (std::size_t b = 0; b < B; ++b)
                d += slot_of(t, side, b, TallyLayout::kCountOdd) - slot_of(t, side, b, TallyLayout::kCountEven);
            m.odd_even_difference_lx[t * kS + side] = 2.0 * d * e0 / area[t];
        }
    });
    m.sigma_lx = side_sigma_lx(w, area, e0, photons);
    m.replicate_sigma_lx = side_replicate_sigma_lx(w, area, e0, photons);
    return m;
}

GlobalEstimate estimate_global(const WeightedTallies& w, std::span<const double> area, double e0,
                               std::uint64_t photons) {
    return global_estimate(chunk_sums(w, area, e0, photons, {0, chunk_count(w.layout())}), w.layout().replicates() > 0);
}

GlobalEstimate estimate_global(const TallyLayout& layout, std::span<const std::uint64_t> data,
                               std::span<const double> area, double e0, std::uint64_t photons) {
    return estimate_global(WeightedTallies(layout, data), area, e0, photons);
}
DetectorEstimate estimate_detector(const Detector& det, std::size_t di, const TallyLayout& layout,
                                   std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                                   CellRange range) {
    return estimate_detector(det, di, WeightedTallies(layout, data), e0, photons, range);
}

DetectorEstimate estimate_detector(const Detector& det, std::size_t di, const WeightedTallies& w, double e0,
                                   std::uint64_t photons, CellRange r) {
    const bool whole_grid = r.i1 == 0;
    if (r.i1 == 0) r = {0, det.nx, 0, det.ny};
    DetectorCounts d(det, di, w, e0, photons);
    DetectorEstimate out;
    out.replicate_spread = d.replicates() > 0;
    out.dof = d.replicates() > 0 ? static_cast<int>(d.replicates()) - 1 : 0;
    estimate_cells(d, out);
    estimate_range(d, r, out);
    out.photons_received = d.received();
    out.mean_value = d.total_n() * d.per_count() / det.cells();
    out.mean_sigma_rel = d.total_rel();
    if (whole_grid && (det.type == DetectorType::illuminance || det.type == DetectorType::points))
        estimate_illuminance_metrics(d, out);
    return out;
}

ReplicateEstimate replicate_estimate(std::span<const double> sums, std::span<const std::uint64_t> photons) {
    ReplicateEstimate e;
    double total = 0.0, n = 0.0;
    bool all_have_photons = sums.size() == photons.size();
    for (std::size_t r = 0; r < sums.size() && all_have_photons; ++r) {
        total += sums[r];
        n += static_cast<double>(photons[r]);
        all_have_photons = photons[r] > 0;
    }
    if (!all_have_photons || sums.size() < 2) {
        e.sigma = std::numeric_limits<double>::quiet_NaN();
        e.mean = n > 0.0 ? total / n : 0.0;
        return e;
    }
    e.mean = total / n;
    double s = 0.0;
    for (std::size_t r = 0; r < sums.size(); ++r) {
        const double w = static_cast<double>(photons[r]) / n;
        const double d = sums[r] / static_cast<double>(photons[r]) - e.mean;
        s += w * w * d * d;
    }
    const double R = static_cast<double>(sums.size());
    e.sigma = std::sqrt(s * R / (R - 1.0));
    e.dof = static_cast<int>(sums.size()) - 1;
    return e;
}

}  // namespace luxtrace
