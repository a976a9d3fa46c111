#include "luxtrace/stats/estimates.hpp"

#include "luxtrace/detector/detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxtrace {

namespace {
// Band sums of one side's slot.
std::uint64_t side_sum(const TallyLayout& L, std::span<const std::uint64_t> data, std::size_t side_index,
                       TallyLayout::SurfaceSlot slot) {
    std::uint64_t n = 0;
    for (std::size_t b = 0; b < L.bands(); ++b) n += data[L.side_slot(side_index, b, slot)];
    return n;
}

// sqrt(Q - S^2 / N) of one side in counts, from its arrivals S and repeats X (Q = S + X).
double side_sigma_counts(double s, double x, double n) { return std::sqrt(std::max(0.0, s + x - s * s / n)); }
}  // namespace

std::vector<double> side_illuminance_lx(const TallyLayout& L, std::span<const std::uint64_t> data,
                                        std::span<const double> area, double e0) {
    std::vector<double> e(L.sides());
    for (std::size_t t = 0; t < L.triangles(); ++t)
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side) {
            const std::size_t i = L.side_index(t, side);
            const std::uint64_t n = side_sum(L, data, i, TallyLayout::kCountOdd) +
                                    side_sum(L, data, i, TallyLayout::kCountEven);
            e[t * TallyLayout::kSides + side] = static_cast<double>(n) * e0 / area[t];
        }
    return e;
}

std::vector<double> side_sigma_lx(const TallyLayout& L, std::span<const std::uint64_t> data,
                                  std::span<const double> area, double e0, std::uint64_t photons) {
    std::vector<double> sigma(L.sides(), std::numeric_limits<double>::quiet_NaN());
    if (photons == 0) return sigma;
    for (std::size_t t = 0; t < L.triangles(); ++t)
        for (std::size_t side = 0; side < TallyLayout::kSides; ++side) {
            const std::size_t i = L.side_index(t, side);
            const double s = static_cast<double>(side_sum(L, data, i, TallyLayout::kCountOdd) +
                                                 side_sum(L, data, i, TallyLayout::kCountEven));
            const double x = static_cast<double>(side_sum(L, data, i, TallyLayout::kRepeats));
            sigma[t * TallyLayout::kSides + side] = side_sigma_counts(s, x, static_cast<double>(photons)) * e0 /
                                                    area[t];
        }
    return sigma;
}

SurfaceMaps surface_maps(const TallyLayout& L, std::span<const std::uint64_t> data, std::span<const double> area,
                         double e0, std::uint64_t photons) {
    const std::size_t T = L.triangles(), B = L.bands();
    constexpr std::size_t kS = TallyLayout::kSides;
    auto slot_of = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        return data[L.surface(t, side, b, s)];
    };
    SurfaceMaps m;
    m.illuminance_lx.resize(T * kS * B);
    m.illuminance_direct_lx.resize(T * kS * B);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b) {
                const double k = e0 / area[t];
                const std::size_t i = (t * kS + side) * B + b;
                m.illuminance_lx[i] = k * static_cast<double>(slot_of(t, side, b, TallyLayout::kCountOdd) +
                                                              slot_of(t, side, b, TallyLayout::kCountEven));
                m.illuminance_direct_lx[i] = k * static_cast<double>(slot_of(t, side, b, TallyLayout::kDirectOdd) +
                                                                     slot_of(t, side, b, TallyLayout::kDirectEven));
            }
    m.odd_even_difference_lx.resize(T * kS);
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side) {
            double d = 0.0;
            for (std::size_t b = 0; b < B; ++b)
                d += static_cast<double>(slot_of(t, side, b, TallyLayout::kCountOdd)) -
                     static_cast<double>(slot_of(t, side, b, TallyLayout::kCountEven));
            m.odd_even_difference_lx[t * kS + side] = 2.0 * d * e0 / area[t];
        }
    m.sigma_lx = side_sigma_lx(L, data, area, e0, photons);
    return m;
}

GlobalEstimate estimate_global(const TallyLayout& L, std::span<const std::uint64_t> data, std::span<const double> area,
                               double e0, std::uint64_t photons) {
    // Eqs. (4)-(5) on the band-summed map of the lit sides: E_odd,t = 2 n_odd E0 / A_t,
    // likewise even; and each side's second-moment variance.
    double s = 0.0, sum_d2 = 0.0, sum_e = 0.0, sum_e2 = 0.0, sum_var = 0.0;
    const double n_photons = static_cast<double>(photons);
    GlobalEstimate g;
    for (std::size_t i = 0; i < L.sides(); ++i) {
        const std::uint64_t odd = side_sum(L, data, i, TallyLayout::kCountOdd);
        const std::uint64_t even = side_sum(L, data, i, TallyLayout::kCountEven);
        if (odd + even == 0) continue;
        const double a = area[L.triangle_of(i)];
        const double k = e0 / a;
        const double e_odd = 2.0 * static_cast<double>(odd) * k;
        const double e_even = 2.0 * static_cast<double>(even) * k;
        const double e = static_cast<double>(odd + even) * k;
        s += a;
        ++g.lit_sides;
        sum_d2 += a * (e_odd - e_even) * (e_odd - e_even);
        sum_e += a * e;
        sum_e2 += a * e * e;
        if (photons > 0) {
            const double sigma = side_sigma_counts(static_cast<double>(odd + even),
                                                   static_cast<double>(side_sum(L, data, i, TallyLayout::kRepeats)),
                                                   n_photons) *
                                 k;
            sum_var += a * sigma * sigma;
        }
    }
    g.moment_primary = L.replicates() == 0;
    g.lit_area_m2 = s;
    if (s <= 0.0) return g;
    g.odd_even_rms_lx = std::sqrt(sum_d2 / s);
    g.sigma_lx = 0.5 * g.odd_even_rms_lx;
    g.moment_sigma_lx = std::sqrt(sum_var / s);
    g.mean_arithmetic_lx = sum_e / s;
    g.mean_quadratic_lx = std::sqrt(sum_e2 / s);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto rel = [&](double sigma, double mean) { return mean > 0.0 ? sigma / mean : nan; };
    g.sigma_rel_arithmetic = rel(g.sigma_lx, g.mean_arithmetic_lx);
    g.sigma_rel_quadratic = rel(g.sigma_lx, g.mean_quadratic_lx);
    g.moment_sigma_rel_arithmetic = rel(g.moment_sigma_lx, g.mean_arithmetic_lx);
    g.moment_sigma_rel_quadratic = rel(g.moment_sigma_lx, g.mean_quadratic_lx);
    return g;
}

DetectorEstimate estimate_detector(const Detector& det, std::size_t di, const TallyLayout& L,
                                   std::span<const std::uint64_t> data, double e0, std::uint64_t photons, CellRange r) {
    const bool whole_grid = r.i1 == 0;
    if (r.i1 == 0) r = {0, det.nx, 0, det.ny};
    const std::size_t nb = L.bands();
    const double per_count = e0 * det.value_per_lm();
    const double inv_n = photons > 0 ? 1.0 / static_cast<double>(photons) : 0.0;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    DetectorEstimate out;
    out.value.resize(static_cast<std::size_t>(det.cells()) * nb);
    out.sigma_rel.resize(out.value.size());
    // eq. (8) for one cell from its n_c and q_c.
    auto rel = [&](double n, double q) { return n > 0.0 ? std::sqrt(std::max(0.0, q / (n * n) - inv_n)) : nan; };
    // sobol: the spread of the replicate means instead (docs/QMC.md). `slot(r)` gives the
    // replicate-r count of what is estimated; the bands of a cell are summed by calling
    // it once per band.
    const std::size_t R = L.replicates();
    std::vector<std::uint64_t> rep_photons(R);
    std::vector<double> rep_sums(R);
    for (std::size_t q = 0; q < R; ++q) rep_photons[q] = data[L.replicate_photons(q)];
    out.replicate_spread = R > 0;
    out.dof = R > 0 ? static_cast<int>(R) - 1 : 0;
    auto replicate_rel = [&](auto&& slot) {
        for (std::size_t q = 0; q < R; ++q) rep_sums[q] = slot(q);
        const ReplicateEstimate e = replicate_estimate(rep_sums, rep_photons);
        return e.mean > 0.0 ? e.sigma / e.mean : nan;
    };
    auto cell_rel = [&](int c, std::size_t b0, std::size_t b1, double n, double q) {
        if (R == 0) return rel(n, q);
        return replicate_rel([&](std::size_t rep) {
            double sum = 0.0;
            for (std::size_t b = b0; b < b1; ++b)
                sum += static_cast<double>(data[L.detector_replicate_n(di, rep, c, b)]);
            return sum;
        });
    };
    for (int c = 0; c < det.cells(); ++c)
        for (std::size_t b = 0; b < nb; ++b) {
            const double n = static_cast<double>(data[L.detector_n(di, c, b)]);
            const double q = static_cast<double>(data[L.detector_q(di, c, b)]);
            out.value[c * nb + b] = n * per_count;
            out.sigma_rel[c * nb + b] = cell_rel(c, b, b + 1, n, q);
        }
    // Eq. (9) over the range on band-summed cells (a photon has one band, so n and q add).
    double sum_l = 0.0, sum_l2 = 0.0, sum_s2 = 0.0;
    const int k = (r.i1 - r.i0) * (r.j1 - r.j0);
    for (int j = r.j0; j < r.j1; ++j)
        for (int i = r.i0; i < r.i1; ++i) {
            const int c = j * det.nx + i;
            double n = 0.0, q = 0.0;
            for (std::size_t b = 0; b < nb; ++b) {
                n += static_cast<double>(data[L.detector_n(di, c, b)]);
                q += static_cast<double>(data[L.detector_q(di, c, b)]);
            }
            const double l = n * per_count;
            const double sigma_c = n > 0.0 ? cell_rel(c, 0, nb, n, q) * l : 0.0;
            sum_l += l;
            sum_l2 += l * l;
            sum_s2 += sigma_c * sigma_c;
            out.registrations += static_cast<std::uint64_t>(n);
        }
    out.mean_arithmetic = sum_l / k;
    out.mean_quadratic = std::sqrt(sum_l2 / k);
    out.sigma_abs = std::sqrt(sum_s2 / k);
    out.sigma_rel_arithmetic = out.mean_arithmetic > 0.0 ? out.sigma_abs / out.mean_arithmetic : nan;
    out.sigma_rel_quadratic = out.mean_quadratic > 0.0 ? out.sigma_abs / out.mean_quadratic : nan;
    out.photons_received = data[L.detector_received(di)];
    const double tn = static_cast<double>(data[L.detector_total_n(di)]);
    const double tq = static_cast<double>(data[L.detector_total_q(di)]);
    out.mean_value = tn * per_count / det.cells();
    out.mean_sigma_rel = R == 0 ? rel(tn, tq) : replicate_rel([&](std::size_t rep) {
        return static_cast<double>(data[L.detector_replicate_total_n(di, rep)]);
    });
    if (whole_grid && det.type == DetectorType::illuminance) {
        // Band-summed cells and their absolute errors; the whole grid's Eavg error is the
        // exact one above, a task area's the replicate spread of its sum (sobol) or the
        // cells' errors combined as independent (random).
        std::vector<double> v(det.cells()), s(det.cells());
        for (int c = 0; c < det.cells(); ++c) {
            double n = 0.0, q = 0.0;
            for (std::size_t b = 0; b < nb; ++b) {
                n += static_cast<double>(data[L.detector_n(di, c, b)]);
                q += static_cast<double>(data[L.detector_q(di, c, b)]);
            }
            v[c] = n * per_count;
            s[c] = n > 0.0 ? cell_rel(c, 0, nb, n, q) * v[c] : nan;
        }
        out.metrics.push_back(
            illuminance_metrics(v, s, det.nx, TaskArea{"", 0, det.nx, 0, det.ny}, out.mean_value * out.mean_sigma_rel));
        for (const TaskArea& a : det.task_areas) {
            std::optional<double> avg_sigma;
            if (R > 0) {
                const double k = (a.i1 - a.i0) * (a.j1 - a.j0);
                double area_sum = 0.0;
                for (int j = a.j0; j < a.j1; ++j)
                    for (int i = a.i0; i < a.i1; ++i) area_sum += v[j * det.nx + i];
                avg_sigma = area_sum / k * replicate_rel([&](std::size_t rep) {
                                double sum = 0.0;
                                for (int j = a.j0; j < a.j1; ++j)
                                    for (int i = a.i0; i < a.i1; ++i)
                                        for (std::size_t b = 0; b < nb; ++b)
                                            sum += static_cast<double>(
                                                data[L.detector_replicate_n(di, rep, j * det.nx + i, b)]);
                                return sum;
                            });
            }
            out.metrics.push_back(illuminance_metrics(v, s, det.nx, a, avg_sigma));
        }
    }
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
