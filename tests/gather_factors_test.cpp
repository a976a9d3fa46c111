// The replicates' common draws of the gathered light (estimate/gather_factors.hpp) and the
// grids' regions they are drawn by (tracer/gather_table.hpp's gather_regions).
#include "luxtrace/estimate/gather_factors.hpp"
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/tracer/gather_table.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace luxtrace {
namespace {

constexpr std::size_t R = kGatherRegions;

// A grid's photons as the tally sums them (in doubles): per cell Y, Q and X_r, per region
// the totals' sums and products.
struct Sums {
    std::vector<double> y, q, x;  // x: [cell][region]
    std::array<double, R> t{};
    std::array<double, TallyLayout::kGatherPairs> tt{};
    double photons = 0.0;
};

// Cells of four regions: a photon lights a region's cells together (its driver) and the
// whole grid a little (a common one), each cell with its own noise too; region 3 empty
// when `empty_last`. A rank-one model (one draw for the whole grid) cannot give two cells of
// one region their correlation here.
Sums synthetic(std::size_t cells, bool empty_last, std::vector<std::size_t>& region, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::poisson_distribution<int> driver(2.0), own(0.5), common(0.3);
    const std::size_t used = empty_last ? R - 1 : R;
    region.resize(cells);
    for (std::size_t c = 0; c < cells; ++c) region[c] = c % used;
    Sums s;
    s.y.assign(cells, 0.0);
    s.q.assign(cells, 0.0);
    s.x.assign(cells * R, 0.0);
    for (int photon = 0; photon < 40000; ++photon) {
        std::array<double, R> drive{};
        for (std::size_t r = 0; r < used; ++r) drive[r] = driver(rng);
        const double g = common(rng);
        std::vector<double> v(cells);
        std::array<double, R> total{};
        for (std::size_t c = 0; c < cells; ++c) {
            v[c] = (1.0 + 0.1 * static_cast<double>(c)) * (drive[region[c]] + g) + own(rng);
            total[region[c]] += v[c];
        }
        for (std::size_t c = 0; c < cells; ++c) {
            s.y[c] += v[c];
            s.q[c] += v[c] * v[c];
            for (std::size_t r = 0; r < R; ++r) s.x[c * R + r] += v[c] * total[r];
        }
        for (std::size_t r = 0; r < R; ++r) {
            s.t[r] += total[r];
            for (std::size_t k = r; k < R; ++k) s.tt[TallyLayout::gather_pair(r, k)] += total[r] * total[k];
        }
        s.photons += 1.0;
    }
    return s;
}

struct Model {
    std::vector<double> sd;
    std::vector<float> a;  // [cell][region]
};

Model fit(const Sums& s) {
    std::vector<double> factor(kGatherFactorWords);
    gather_group_factor(s.t, s.tt, s.photons, factor);
    Model m;
    m.a.resize(s.y.size() * R);
    for (std::size_t c = 0; c < s.y.size(); ++c) {
        m.sd.push_back(std::sqrt(s.q[c] - s.y[c] * s.y[c] / s.photons));
        gather_cell_loadings(factor, s.y[c], m.sd[c], std::span<const double>(s.x.data() + c * R, R), s.photons,
                             std::span<float>(m.a.data() + c * R, R));
    }
    return m;
}

double dot(const Model& m, std::size_t i, std::size_t j) {
    double d = 0.0;
    for (std::size_t r = 0; r < R; ++r) d += static_cast<double>(m.a[i * R + r]) * m.a[j * R + r];
    return d;
}

// The common draws' part of each region's total has the region's measured variance
// (sum over its cells of sd a = L^T e_r, so |.|^2 = Cov(T, T)_rr), each cell's loadings
// stay within the unit ball, and two cells of one region correlate in the model as in the
// photons (a single common draw for the grid would give them rho_iT rho_jT, far less).
TEST(GatherFactors, RegionsTotalsAndTheirCellsCorrelationsAsThePhotonsMadeThem) {
    for (const bool empty_last : {false, true}) {
        std::vector<std::size_t> region;
        const Sums s = synthetic(24, empty_last, region, empty_last ? 7 : 3);
        const Model m = fit(s);
        for (std::size_t r = 0; r < R; ++r) {
            std::array<double, R> sum{};
            for (std::size_t c = 0; c < region.size(); ++c)
                if (region[c] == r)
                    for (std::size_t k = 0; k < R; ++k) sum[k] += m.sd[c] * m.a[c * R + k];
            double var_model = 0.0;
            for (const double v : sum) var_model += v * v;
            const double var = s.tt[TallyLayout::gather_pair(r, r)] - s.t[r] * s.t[r] / s.photons;
            EXPECT_NEAR(var_model, var, 1e-5 * (var + 1.0)) << "region " << r << (empty_last ? ", region 3 empty" : "");
        }
        for (std::size_t c = 0; c < region.size(); ++c) EXPECT_LE(dot(m, c, c), 1.0 + 1e-6);
        // Two cells of one region, and of two regions: the model's correlation a_i . a_j
        // against the photons', s_i s_j var(shared) / sqrt((s_i^2 2.3 + 0.5)(s_j^2 2.3 + 0.5))
        // (cell c's scale s_c = 1 + c / 10, the driver's variance 2, the common 0.3, the own
        // noise 0.5).
        const std::size_t i = 0, j = 12, other = 1;  // 12: region 0 with 3 or 4 regions
        ASSERT_EQ(region[i], region[j]);
        ASSERT_NE(region[i], region[other]);
        auto scale = [](std::size_t c) { return 1.0 + 0.1 * static_cast<double>(c); };
        auto rho = [&](std::size_t p, std::size_t q, double shared) {
            const double sp = scale(p), sq = scale(q);
            return sp * sq * shared / std::sqrt((sp * sp * 2.3 + 0.5) * (sq * sq * 2.3 + 0.5));
        };
        EXPECT_NEAR(dot(m, i, j), rho(i, j, 2.3), 0.05);
        EXPECT_NEAR(dot(m, i, other), rho(i, other, 0.3), 0.05);
    }
}

// A 16 x 8 grid in four regions: 32 cells each, each a block of the grid (its bounds apart
// from the others'), the same however often made.
TEST(GatherRegions, EqualNearBlocks) {
    Detector d;
    d.nx = 16, d.ny = 8;
    d.size_u = 8.0, d.size_v = 4.0;
    d.finalize();
    const std::vector<std::size_t> region = gather_regions(d, R);
    ASSERT_EQ(region.size(), 128u);
    std::array<int, R> count{};
    std::array<int, R> lo_i{}, hi_i{}, lo_j{}, hi_j{};
    lo_i.fill(99), lo_j.fill(99), hi_i.fill(-1), hi_j.fill(-1);
    for (int c = 0; c < 128; ++c) {
        const std::size_t r = region[static_cast<std::size_t>(c)];
        ASSERT_LT(r, R);
        ++count[r];
        lo_i[r] = std::min(lo_i[r], c % 16), hi_i[r] = std::max(hi_i[r], c % 16);
        lo_j[r] = std::min(lo_j[r], c / 16), hi_j[r] = std::max(hi_j[r], c / 16);
    }
    for (std::size_t r = 0; r < R; ++r) {
        EXPECT_EQ(count[r], 32);
        // A block of 32 cells: its bounding rectangle holds exactly its cells.
        EXPECT_EQ((hi_i[r] - lo_i[r] + 1) * (hi_j[r] - lo_j[r] + 1), 32) << "region " << r;
    }
    EXPECT_EQ(gather_regions(d, R), region);
    // Fewer cells than regions: each its own, the rest empty.
    Detector small;
    small.nx = 3, small.ny = 1;
    small.finalize();
    const std::vector<std::size_t> few = gather_regions(small, R);
    EXPECT_NE(few[0], few[1]);
    EXPECT_NE(few[1], few[2]);
    EXPECT_NE(few[0], few[2]);
}

}  // namespace
}  // namespace luxtrace
