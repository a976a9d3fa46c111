// Chi-square tests of every emission sampling routine, driven by the production
// PhiloxSampler, and tests of the sampler itself (range, order independence, seeds,
// uniformity, pair correlation). Each chi-square test is rejected at p = 0.999.
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/alias_table.hpp"
#include "luxtrace/light/ies.hpp"
#include "luxtrace/light/light_set.hpp"
#include "luxtrace/light/photometry_distribution.hpp"
#include "luxtrace/light/uniform_sampling.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/sampler/photon_sampler.hpp"
#include "luxtrace/sampler/sobol.hpp"
#include "luxtrace/stats/estimates.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <boost/random/sobol.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#ifndef LUXTRACE_EXAMPLES_DIR
#error "define LUXTRACE_EXAMPLES_DIR (the examples folder)"
#endif

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;
using luxtrace::test_support::chi2_quantile;
using luxtrace::test_support::kZ999;

// Pearson chi-square of observed counts against (unnormalised) bin probabilities.
// Bins whose expected count is below 5 are pooled into one bin; bins of probability
// zero must stay empty. Returns the statistic so a caller can print it.
double expect_chi_square(const std::vector<std::int64_t>& observed, const std::vector<double>& weight,
                         const std::string& what) {
    double wsum = 0.0;
    std::int64_t n = 0;
    for (double w : weight) wsum += w;
    for (std::int64_t o : observed) n += o;
    std::int64_t forbidden = 0, pooled_obs = 0;
    double pooled_exp = 0.0, stat = 0.0;
    int bins = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        const double e = static_cast<double>(n) * weight[i] / wsum;
        if (weight[i] <= 0.0) {
            forbidden += observed[i];
        } else if (e < 5.0) {
            pooled_obs += observed[i];
            pooled_exp += e;
        } else {
            const double d = static_cast<double>(observed[i]) - e;
            stat += d * d / e;
            ++bins;
        }
    }
    if (pooled_exp > 0.0) {
        const double d = static_cast<double>(pooled_obs) - pooled_exp;
        stat += d * d / pooled_exp;
        ++bins;
    }
    const double limit = chi2_quantile(bins - 1, kZ999);
    EXPECT_EQ(forbidden, 0) << what << ": samples in bins of zero probability";
    EXPECT_LT(stat, limit) << what << ": chi-square " << stat << " over " << bins - 1
                           << " dof (limit at p = 0.999: " << limit << ")";
    std::printf("  %-40s chi2 = %8.2f  dof = %4d  limit = %8.2f\n", what.c_str(), stat, bins - 1, limit);
    return stat;
}

int bin_of(double x, int n) {  // x in [0,1] -> 0..n-1
    return std::clamp(static_cast<int>(std::floor(x * n)), 0, n - 1);
}

// Orthonormal (t, b) around n built here by Gram-Schmidt, independent of luxtrace::Frame,
// so azimuth bins test the library's frame rather than reuse it.
struct Basis {
    Vec3 t, b, n;
    explicit Basis(const Vec3& axis) : n(glm::normalize(axis)) {
        const Vec3 ref = std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        t = glm::normalize(ref - glm::dot(ref, n) * n);
        b = glm::cross(n, t);
    }
    double phi01(const Vec3& d) const {  // azimuth in [0, 1)
        double p = std::atan2(glm::dot(d, b), glm::dot(d, t)) / (2.0 * kPi);
        return p < 0.0 ? p + 1.0 : p;
    }
};

TEST(Sampling, UniformSphereEqualSolidAngleBins) {
    // Bins equal in cos(theta) and phi have equal solid angle.
    constexpr int nz = 10, nphi = 20, N = 200000;
    PhiloxSampler s(11);
    std::vector<std::int64_t> obs(nz * nphi, 0);
    int bad_length = 0;
    const Basis axis(Vec3(0, 0, 1));
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        const double u1 = s.next(), u2 = s.next();
        const Vec3 d = sample_uniform_sphere(u1, u2);
        bad_length += std::abs(glm::length(d) - 1.0) > 1e-12;
        obs[bin_of(0.5 * (d.z + 1.0), nz) * nphi + bin_of(axis.phi01(d), nphi)]++;
    }
    EXPECT_EQ(bad_length, 0);
    expect_chi_square(obs, std::vector<double>(obs.size(), 1.0), "uniform sphere");
}

TEST(Sampling, CosineHemisphereUniformInCosSquared) {
    // pdf cos(theta)/pi: d(cos^2 theta) is uniform, and phi is uniform. Two tilted
    // normals, one below the horizon (the frame's sign branch).
    for (const Vec3 normal : {Vec3(0.3, -0.5, 0.8), Vec3(-0.6, 0.2, -0.7)}) {
        constexpr int nc = 10, nphi = 12, N = 120000;
        const Basis axis(normal);
        PhiloxSampler s(12);
        std::vector<std::int64_t> obs(nc * nphi + 1, 0);  // last bin: below the surface
        int bad_length = 0;
        for (int k = 0; k < N; ++k) {
            s.start_photon(k);
            const double u1 = s.next(), u2 = s.next();
            const Vec3 d = sample_cosine_hemisphere(axis.n, u1, u2);
            bad_length += std::abs(glm::length(d) - 1.0) > 1e-12;
            const double c = glm::dot(d, axis.n);
            if (c < 0.0) obs.back()++;
            else obs[bin_of(c * c, nc) * nphi + bin_of(axis.phi01(d), nphi)]++;
        }
        EXPECT_EQ(bad_length, 0);
        std::vector<double> w(obs.size(), 1.0);
        w.back() = 0.0;
        expect_chi_square(obs, w, "cosine hemisphere n.z = " + std::to_string(axis.n.z));
    }
}

TEST(Sampling, UniformConeInsideOnly) {
    const double cos_max = std::cos(30.0 * kDeg);
    constexpr int nc = 20, nphi = 12, N = 120000;
    PhiloxSampler s(13);
    const Basis axis(Vec3(0, 0, 1));
    std::vector<std::int64_t> obs(nc * nphi + 1, 0);  // last bin: outside the cone
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        const double u1 = s.next(), u2 = s.next();
        const Vec3 d = sample_uniform_cone(cos_max, u1, u2);
        if (d.z < cos_max - 1e-12) obs.back()++;
        else obs[bin_of((1.0 - d.z) / (1.0 - cos_max), nc) * nphi + bin_of(axis.phi01(d), nphi)]++;
    }
    std::vector<double> w(obs.size(), 1.0);
    w.back() = 0.0;
    expect_chi_square(obs, w, "uniform cone 30 deg");
}

TEST(Sampling, SpotLightEmitsInsideItsConeOnly) {
    // A whole spot light, aimed off-axis, framed as the scene loader frames it.
    for (const double half_deg : {25.0, 120.0}) {
        SpotLight spot;
        spot.position = Vec3(1.0, 2.0, 3.0);
        const Vec3 aim = glm::normalize(Vec3(1.0, 2.0, -3.0));
        spot.cos_half_angle = std::cos(half_deg * kDeg);
        spot.frame = Frame::around(aim);
        Light l;
        l.flux_lm = 100.0;
        l.kind = spot;
        const Basis axis(aim);
        constexpr int nc = 20, nphi = 12, N = 120000;
        PhiloxSampler s(half_deg < 90.0 ? 14 : 114);
        std::vector<std::int64_t> obs(nc * nphi + 1, 0);
        int off_origin = 0;
        for (int k = 0; k < N; ++k) {
            s.start_photon(k);
            const double a = s.next(), b = s.next(), c = s.next(), d = s.next();
            const EmittedRay r = l.emit(a, b, c, d);
            off_origin += glm::length(r.origin - spot.position) > 0.0;
            const double cz = glm::dot(r.direction, axis.n);
            if (cz < spot.cos_half_angle - 1e-12) obs.back()++;
            else
                obs[bin_of((1.0 - cz) / (1.0 - spot.cos_half_angle), nc) * nphi +
                    bin_of(axis.phi01(r.direction), nphi)]++;
        }
        EXPECT_EQ(off_origin, 0);
        std::vector<double> w(obs.size(), 1.0);
        w.back() = 0.0;
        expect_chi_square(obs, w, "spot light half angle " + std::to_string(int(half_deg)));
    }
}

TEST(Sampling, IesPointLightFollowsIntensity) {
    const Photometry p = load_ies(std::filesystem::path(LUXTRACE_EXAMPLES_DIR) / "office" / "fixture.ies");
    PointLight point;
    point.position = Vec3(2.0, 2.0, 2.8);
    // Tilted so far that Frame::around(aim) would put C0 27 deg away from the loader's
    // C0: a light that ignored its frame would rotate the quadrant pattern visibly.
    const Vec3 aim = glm::normalize(Vec3(0.6, 0.6, -0.3));
    auto dist = std::make_shared<PhotometryDistribution>(p);
    point.distribution = dist;
    // The loader's frame: +z = nadir (aim), +x = C0 = scene +x projected off the aim
    // (the loader uses +y instead when |aim.x| >= 0.9, not the case here).
    ASSERT_LT(std::abs(aim.x), 0.9);
    const Vec3 c0 = glm::normalize(Vec3(1, 0, 0) - aim.x * aim);
    const Vec3 c90 = glm::cross(aim, c0);
    point.frame = Frame{c0, c90, aim};
    Light l;
    l.flux_lm = dist->flux_lm();
    l.kind = point;

    // Bins 5 deg in gamma over the whole sphere (the file stops at 90: the upper half
    // must stay dark) and 22.5 deg in C, both aligned with the file's angles so the
    // bilinear intensity is smooth inside a bin.
    constexpr int ng = 36, ncp = 16, sub = 16, N = 1000000;
    const double dg = kPi / ng, dc = 2.0 * kPi / ncp;
    std::vector<double> w(ng * ncp, 0.0);
    double total = 0.0;
    for (int i = 0; i < ng; ++i)
        for (int j = 0; j < ncp; ++j) {
            double sum = 0.0;  // midpoint rule for the integral of I sin(g) dg dc
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    const double g = (i + (a + 0.5) / sub) * dg;
                    const double c = (j + (b + 0.5) / sub) * dc;
                    sum += p.intensity_cd(g, c) * std::sin(g);
                }
            w[i * ncp + j] = sum * (dg / sub) * (dc / sub);
            total += w[i * ncp + j];
        }
    EXPECT_NEAR(total, p.flux_lm(), 1e-3 * p.flux_lm());  // the reference integral itself

    PhiloxSampler s(15);
    std::vector<std::int64_t> obs(w.size(), 0);
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        const double a = s.next(), b = s.next(), c = s.next(), d = s.next();
        const Vec3 dir = l.emit(a, b, c, d).direction;
        const double g = std::acos(std::clamp(glm::dot(dir, aim), -1.0, 1.0));
        double cp = std::atan2(glm::dot(dir, c90), glm::dot(dir, c0));
        if (cp < 0.0) cp += 2.0 * kPi;
        obs[bin_of(g / kPi, ng) * ncp + bin_of(cp / (2.0 * kPi), ncp)]++;
    }
    expect_chi_square(obs, w, "IES point light (gamma, C)");
}

TEST(Sampling, AreaEmitterUniformByAreaAndLambertian) {
    // Two triangles of different area and orientation; normal = e1 x e2 as the loader.
    struct Tri {
        Vec3 p0, e1, e2;
    };
    const std::vector<Tri> tris = {{Vec3(0, 0, 1), Vec3(2, 0, 0), Vec3(0, 1, 0)},
                                   {Vec3(3, 0, 0), Vec3(0, 3, 0), Vec3(0.5, 0, 1)}};
    AreaLight emitter;
    EmitterSurface& surf = emitter.surface;
    std::vector<double> area;
    for (std::size_t t = 0; t < tris.size(); ++t) {
        const Vec3 cr = glm::cross(tris[t].e1, tris[t].e2);
        area.push_back(0.5 * glm::length(cr));
        surf.p0.push_back(tris[t].p0);
        surf.e1.push_back(tris[t].e1);
        surf.e2.push_back(tris[t].e2);
        surf.normal.push_back(glm::normalize(cr));
        surf.scene_triangle.push_back(10 + static_cast<int>(t));
        surf.area_m2 += area.back();
        surf.cdf.push_back(surf.area_m2);
    }
    for (double& c : surf.cdf) c /= surf.area_m2;
    ASSERT_GT(std::abs(area[0] - area[1]), 0.5);
    Light l;
    l.flux_lm = 500.0;
    l.kind = emitter;

    // Position bins: each triangle cut into m^2 equal sub-triangles in barycentric
    // coordinates (cell (i,j), lower or upper half); cells past the hypotenuse are
    // outside the triangle and get probability 0.
    constexpr int m = 5, nc = 10, nphi = 8, N = 400000;
    std::vector<std::int64_t> pos(2 * m * m * 2, 0);
    std::vector<double> wpos(pos.size(), 0.0);
    for (int t = 0; t < 2; ++t)
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j) {
                if (i + j <= m - 1) wpos[((t * m + i) * m + j) * 2 + 0] = area[t] / (m * m);
                if (i + j <= m - 2) wpos[((t * m + i) * m + j) * 2 + 1] = area[t] / (m * m);
            }
    std::vector<std::int64_t> dir(nc * nphi + 1, 0);  // last bin: behind the front side
    std::vector<double> wdir(dir.size(), 1.0);
    wdir.back() = 0.0;
    int off_plane = 0, bad_triangle = 0;
    PhiloxSampler s(16);
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        const double a = s.next(), b = s.next(), c = s.next(), d = s.next();
        const EmittedRay r = l.emit(a, b, c, d);
        const int t = r.emitter_triangle - 10;
        if (t < 0 || t > 1) {
            ++bad_triangle;
            continue;
        }
        const Tri& tr = tris[t];
        const Vec3 q = r.origin - tr.p0;
        off_plane += std::abs(glm::dot(q, surf.normal[t])) > 1e-12;
        // Barycentric (alpha, beta) from the 2x2 normal equations.
        const double g11 = glm::dot(tr.e1, tr.e1), g12 = glm::dot(tr.e1, tr.e2), g22 = glm::dot(tr.e2, tr.e2),
                     r1 = glm::dot(q, tr.e1), r2 = glm::dot(q, tr.e2);
        const double det = g11 * g22 - g12 * g12;
        const double al = (r1 * g22 - r2 * g12) / det, be = (r2 * g11 - r1 * g12) / det;
        const int i = bin_of(al, m), j = bin_of(be, m);
        const bool upper = (al * m - i) + (be * m - j) > 1.0;
        pos[((t * m + i) * m + j) * 2 + (upper ? 1 : 0)]++;

        const Basis axis(surf.normal[t]);
        const double cz = glm::dot(r.direction, axis.n);
        if (cz <= 0.0) dir.back()++;
        else dir[bin_of(cz * cz, nc) * nphi + bin_of(axis.phi01(r.direction), nphi)]++;
    }
    EXPECT_EQ(bad_triangle, 0);
    EXPECT_EQ(off_plane, 0);
    expect_chi_square(pos, wpos, "area light positions by area");
    expect_chi_square(dir, wdir, "area light cosine directions");
}

TEST(Sampling, LightSetPicksByFluxAndColourShare) {
    // Colour shares as the loader stores them: not normalised, some bands dark.
    const std::vector<double> flux = {100.0, 300.0, 50.0, 550.0};
    const std::vector<std::vector<double>> share = {{1, 1, 1}, {2, 1, 0}, {0, 0, 5}, {0.2, 0.3, 0.5}};
    std::vector<Light> lights;
    for (std::size_t i = 0; i < flux.size(); ++i) {
        Light l;
        l.flux_lm = flux[i];
        l.band_share = share[i];
        lights.push_back(l);
    }
    const LightSet set(lights);
    EXPECT_NEAR(set.total_flux_lm(), 1000.0, 1e-9);
    constexpr int N = 1000000;
    std::vector<std::int64_t> obs(12, 0);
    std::vector<double> w(12, 0.0);
    for (int i = 0; i < 4; ++i) {
        const double ssum = share[i][0] + share[i][1] + share[i][2];
        for (int b = 0; b < 3; ++b) w[i * 3 + b] = flux[i] / 1000.0 * share[i][b] / ssum;
    }
    PhiloxSampler s(17);
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        const double u1 = s.next(), u2 = s.next();
        const std::size_t li = set.pick_light(u1);
        ASSERT_LT(li, 4u);
        const int b = set.pick_band(li, u2);
        ASSERT_GE(b, 0);
        ASSERT_LT(b, 3);
        obs[li * 3 + b]++;
    }
    expect_chi_square(obs, w, "light set (light, band)");
}

TEST(Philox, ValuesStrictlyInsideUnitIntervalAndUniform) {
    constexpr int N = 100000, D = 10, nb = 1000, nb_dim = 50;
    PhiloxSampler s(2024);
    std::vector<std::int64_t> all(nb, 0);
    std::vector<std::vector<std::int64_t>> per_dim(D, std::vector<std::int64_t>(nb_dim, 0));
    int outside = 0;
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        for (int d = 0; d < D; ++d) {
            const double u = s.next();
            outside += !(u > 0.0 && u < 1.0);
            all[bin_of(u, nb)]++;
            per_dim[d][bin_of(u, nb_dim)]++;
        }
    }
    EXPECT_EQ(outside, 0);
    expect_chi_square(all, std::vector<double>(nb, 1.0), "philox 1D, all dimensions");
    for (int d = 0; d < D; ++d)
        expect_chi_square(per_dim[d], std::vector<double>(nb_dim, 1.0), "philox 1D, dimension " + std::to_string(d));
}

TEST(Philox, ValueDependsOnlyOnSeedPhotonAndDimension) {
    const std::vector<std::uint64_t> photons = {0, 1, 7, 123456789, (1ull << 32) + 5, (1ull << 40) + 3, UINT64_MAX};
    constexpr std::uint32_t D = 13;  // spans several four-word blocks
    PhiloxSampler ref(99);
    std::vector<std::vector<double>> want;
    for (std::uint64_t k : photons) {
        ref.start_photon(k);
        std::vector<double> v;
        for (std::uint32_t d = 0; d < D; ++d) v.push_back(ref.next());
        want.push_back(v);
    }
    // Photons in reverse order, dimensions in reverse by jumping.
    PhiloxSampler rev(99);
    for (std::size_t i = photons.size(); i-- > 0;) {
        rev.start_photon(photons[i]);
        for (std::uint32_t d = D; d-- > 0;) {
            rev.set_dimension(d);
            EXPECT_EQ(rev.next(), want[i][d]) << "photon " << photons[i] << " dim " << d;
        }
    }
    // Interleaved: one dimension of every photon at a time, on a sampler that has been
    // used for other photons before (no state may leak between photons).
    PhiloxSampler mix(99);
    mix.start_photon(42);
    for (int i = 0; i < 9; ++i) mix.next();
    for (std::uint32_t d = 0; d < D; ++d)
        for (std::size_t i = 0; i < photons.size(); ++i) {
            mix.start_photon(photons[i]);
            mix.set_dimension(d);
            EXPECT_EQ(mix.next(), want[i][d]) << "photon " << photons[i] << " dim " << d;
        }
}

TEST(Philox, DistinctCountersGiveDistinctBlocks) {
    // Each (photon, four-dimension block) is its own Philox counter: no two of them may
    // yield the same four words (a collision of 128 random bits has probability ~1e-28,
    // so any duplicate means counters alias, e.g. photon k+1 reusing photon k's block 1).
    constexpr int N = 50000, blocks = 4;
    PhiloxSampler s(5);
    std::vector<std::array<double, 4>> seen;
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        for (int b = 0; b < blocks; ++b) seen.push_back({s.next(), s.next(), s.next(), s.next()});
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(std::adjacent_find(seen.begin(), seen.end()), seen.end());
}

TEST(Philox, BatchedBlocksAreRandom123sBlocks) {
    // The tracer draws the blocks of its photons in flight together (AVX2 lanes where
    // the CPU has them); every word must be the one Random123's scalar Philox4x32-10
    // gives for the same counter and key, for any batch size, photon indices using the
    // high 32 bits and seeds using theirs.
    std::mt19937_64 pick(31);
    for (const std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{0xdeadbeefcafef00d}}) {
        PhiloxSampler s(seed);
        if (!s.vectorised()) std::cout << "note: no AVX2 here, the batch is drawn one by one\n";
        for (int trial = 0; trial < 2000; ++trial) {
            const std::size_t n = 1 + static_cast<std::size_t>(trial) % PhiloxSampler::kBatch;
            std::uint64_t k[PhiloxSampler::kBatch];
            std::uint32_t b[PhiloxSampler::kBatch];
            PhiloxSampler::Block got[PhiloxSampler::kBatch];
            for (std::size_t i = 0; i < n; ++i) {
                k[i] = trial % 3 == 0 ? pick() : pick() % 1000000;
                b[i] = static_cast<std::uint32_t>(pick() % 70);
            }
            s.blocks(k, b, n, got);
            for (std::size_t i = 0; i < n; ++i) {
                const r123::Philox4x32::ctr_type ctr = {{static_cast<std::uint32_t>(k[i]),
                                                         static_cast<std::uint32_t>(k[i] >> 32), b[i],
                                                         PhiloxSampler::kCounterTag}};
                const r123::Philox4x32::key_type key = {
                    {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
                const auto want = r123::Philox4x32()(ctr, key);
                for (int w = 0; w < 4; ++w)
                    ASSERT_EQ(got[i][w], want.v[w]) << "seed " << seed << " photon " << k[i] << " block " << b[i]
                                                    << " word " << w << " (lane " << i << " of " << n << ")";
            }
        }
    }
}

// Pearson correlation of paired samples; under independence r * sqrt(n) ~ N(0, 1).
double correlation_z(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        syy += y[i] * y[i];
        sxy += x[i] * y[i];
    }
    const double cov = sxy / n - sx / n * sy / n;
    const double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
    return r * std::sqrt(n);
}

TEST(Philox, DifferentSeedsGiveDifferentStreams) {
    // Seeds differing in low bits, and only in the high 32 bits; photons differing only
    // in the high 32 bits of k must differ too.
    constexpr int N = 2000, D = 8;
    auto stream = [&](std::uint64_t seed, std::uint64_t k0) {
        PhiloxSampler s(seed);
        std::vector<double> v;
        for (int k = 0; k < N; ++k) {
            s.start_photon(k0 + k);
            for (int d = 0; d < D; ++d) v.push_back(s.next());
        }
        return v;
    };
    const auto a = stream(1, 0), b = stream(2, 0), c = stream(1 + (1ull << 32), 0), e = stream(1, 1ull << 32);
    for (const auto* other : {&b, &c, &e}) {
        int equal = 0;
        for (std::size_t i = 0; i < a.size(); ++i) equal += a[i] == (*other)[i];
        EXPECT_LE(equal, 1);                                 // each match has probability 2^-32
        EXPECT_LT(std::abs(correlation_z(a, *other)), 4.0);  // 4 sigma
    }
}

TEST(Philox, PairsOfDimensionsAndPhotonsAreIndependent) {
    // 2D chi-square on (dim d, dim d+1) of one photon, including the pair that straddles
    // a four-word block (3, 4), and on (photon k, photon k+1) at one dimension; plus
    // the correlation coefficient within 4 sigma.
    constexpr int N = 100000, nb = 16;
    PhiloxSampler s(7);
    std::vector<std::vector<double>> u(9, std::vector<double>(N));
    for (int k = 0; k < N; ++k) {
        s.start_photon(k);
        for (int d = 0; d < 9; ++d) u[d][k] = s.next();
    }
    auto check = [&](const std::vector<double>& x, const std::vector<double>& y, const std::string& what) {
        std::vector<std::int64_t> obs(nb * nb, 0);
        for (std::size_t i = 0; i < x.size(); ++i) obs[bin_of(x[i], nb) * nb + bin_of(y[i], nb)]++;
        expect_chi_square(obs, std::vector<double>(obs.size(), 1.0), what);
        const double z = correlation_z(x, y);
        EXPECT_LT(std::abs(z), 4.0) << what << ": correlation z = " << z;
    };
    for (int d = 0; d < 8; ++d)
        check(u[d], u[d + 1], "philox pair dims " + std::to_string(d) + "," + std::to_string(d + 1));
    const std::vector<double> x(u[0].begin(), u[0].end() - 1), y(u[0].begin() + 1, u[0].end());
    check(x, y, "philox pair photons k, k+1");
}

// --- Owen-scrambled Sobol points (sobol.hpp) ---

constexpr std::uint32_t kSobolTestDims = 40;  // emission (6) and the first 11 bounces (3 each)

TEST(Sobol, UnscrambledPointsAreBoostsSequence) {
    // Boost's engine yields x(g(n + 1)) after n points, g(m) = m ^ (m >> 1) (Gray code);
    // addressed by index, the sequence must give the same 32 bits, near the start and
    // after a jump past 2^31.
    const SobolSequence seq(kSobolTestDims);
    boost::random::sobol_engine<std::uint32_t, 32> engine(kSobolTestDims);
    for (const std::uint32_t start : {0u, (1u << 31) + 12345u}) {
        engine.seed(start);
        for (std::uint32_t n = start; n < start + 5000; ++n) {
            const std::uint32_t index = (n + 1) ^ ((n + 1) >> 1);
            for (std::uint32_t d = 0; d < kSobolTestDims; ++d)
                ASSERT_EQ(seq.point(index, d), engine()) << "point " << index << " dimension " << d;
        }
    }
}

// Whether the points, as 32-bit fractions, put exactly `per_box` into every box of the
// 2^a x 2^b grid of [0,1)^2.
bool stratified(const std::vector<std::uint32_t>& x, const std::vector<std::uint32_t>& y, int a, int b,
                std::size_t per_box) {
    std::vector<std::size_t> boxes(std::size_t{1} << (a + b), 0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const std::size_t bx = a == 0 ? 0 : x[i] >> (32 - a), by = b == 0 ? 0 : y[i] >> (32 - b);
        ++boxes[(bx << b) | by];
    }
    return std::all_of(boxes.begin(), boxes.end(), [&](std::size_t c) { return c == per_box; });
}

// The t-value of 2^m points in a 2-D projection: the smallest t for which every
// elementary box of volume 2^(t-m) holds exactly 2^t of them.
int t_value(const std::vector<std::uint32_t>& x, const std::vector<std::uint32_t>& y, int m) {
    for (int t = 0; t <= m; ++t) {
        bool ok = true;
        for (int a = 0; a <= m - t && ok; ++a) ok = stratified(x, y, a, m - t - a, std::size_t{1} << t);
        if (ok) return t;
    }
    return m + 1;
}

TEST(Sobol, ScramblingKeepsTheNetProperty) {
    // Each block of 2^m consecutive points from a multiple of 2^m puts one point in each
    // interval of length 2^-m in every dimension, scrambled or not; every 2-D projection
    // of the dimensions a photon uses keeps its t-value under scrambling, and dimensions
    // 0 and 1 form a (0, m, 2)-net. Scrambles that are not nested break these.
    constexpr int m = 10;
    constexpr std::uint32_t n = 1u << m;
    const SobolSequence seq(kSobolTestDims);
    for (const std::uint32_t first : {0u, 7u * n}) {
        std::vector<std::vector<std::uint32_t>> plain(kSobolTestDims), mixed(kSobolTestDims);
        for (std::uint32_t d = 0; d < kSobolTestDims; ++d) {
            const std::uint32_t s = SobolSequence::scramble_seed(2024, 3, d);
            for (std::uint32_t i = first; i < first + n; ++i) {
                plain[d].push_back(seq.point(i, d));
                mixed[d].push_back(seq.scrambled(i, d, s));
            }
            EXPECT_TRUE(stratified(mixed[d], mixed[d], m, 0, 1)) << "dimension " << d << " from " << first;
        }
        EXPECT_EQ(t_value(mixed[0], mixed[1], m), 0);
        int worst = 0;
        for (std::uint32_t d1 = 0; d1 < kSobolTestDims; ++d1)
            for (std::uint32_t d2 = d1 + 1; d2 < kSobolTestDims; ++d2) {
                const int t = t_value(mixed[d1], mixed[d2], m);
                EXPECT_EQ(t, t_value(plain[d1], plain[d2], m)) << "dimensions " << d1 << ", " << d2;
                worst = std::max(worst, t);
            }
        std::printf("  2-D projections of %u dimensions, points %u..%u: worst t = %d of m = %d\n", kSobolTestDims,
                    first, first + n - 1, worst, m);
    }
}

TEST(Sobol, ScrambledPointIsUniformOverScrambles) {
    // Over random scrambles, any one point of any dimension is uniform on [0, 1): the
    // estimates of a scrambled sequence are unbiased. Chi-square, 64 bins, 40,000 seeds.
    constexpr int kSeeds = 40000, nb = 64;
    const SobolSequence seq(kSobolTestDims);
    for (const std::uint32_t index : {0u, 1u, 1000u, 123456789u})
        for (const std::uint32_t d : {0u, 1u, 5u, 39u}) {
            std::vector<std::int64_t> obs(nb, 0);
            for (int k = 0; k < kSeeds; ++k) {
                const std::uint32_t x = seq.scrambled(index, d, SobolSequence::scramble_seed(k, 0, d));
                ++obs[x >> 26];
            }
            expect_chi_square(obs, std::vector<double>(nb, 1.0),
                              "sobol point " + std::to_string(index) + " dim " + std::to_string(d));
        }
}

TEST(Sobol, IndependentScramblesGiveUncorrelatedEstimates) {
    // Two randomisations of one run (streams 0 and 1, the odd and even maps or two
    // replicates) must give uncorrelated estimates: over 3000 run seeds, the estimates of
    // the integral of f(x0, x1, x4) = x0 x1 + x4^2 from 256 points of each stream have a
    // correlation within 4 sigma of 0. The same scramble for both streams gives 1.
    constexpr int kRuns = 3000;
    constexpr std::uint32_t n = 256;
    const SobolSequence seq(kSobolTestDims);
    auto estimate = [&](std::uint64_t seed, std::uint32_t stream) {
        double sum = 0.0;
        std::uint32_t s[5];
        for (std::uint32_t d = 0; d < 5; ++d) s[d] = SobolSequence::scramble_seed(seed, stream, d);
        for (std::uint32_t i = 0; i < n; ++i) {
            const double x0 = PhiloxSampler::uniform(seq.scrambled(i, 0, s[0]));
            const double x1 = PhiloxSampler::uniform(seq.scrambled(i, 1, s[1]));
            const double x4 = PhiloxSampler::uniform(seq.scrambled(i, 4, s[4]));
            sum += x0 * x1 + x4 * x4;
        }
        return sum / n;
    };
    std::vector<double> a, b;
    for (int r = 0; r < kRuns; ++r) {
        a.push_back(estimate(r, 0));
        b.push_back(estimate(r, 1));
    }
    const double z = correlation_z(a, b);
    EXPECT_LT(std::abs(z), 4.0) << "streams 0 and 1: correlation z = " << z;
    EXPECT_GT(correlation_z(a, a), 50.0);  // the statistic sees a shared scramble
    // Unbiased: the mean over runs is the integral, 1/4 + 1/3, within 4 standard errors.
    double mean = 0.0, var = 0.0;
    for (double v : a) mean += v / kRuns;
    for (double v : a) var += (v - mean) * (v - mean) / (kRuns - 1);
    EXPECT_LT(std::abs(mean - (0.25 + 1.0 / 3.0)), 4.0 * std::sqrt(var / kRuns));
    std::printf("  correlation z = %.2f; mean %.7f (exact %.7f), sd of one estimate %.2e\n", z, mean, 0.25 + 1.0 / 3.0,
                std::sqrt(var));
}

TEST(PhotonSampler, SobolBlocksAreScrambledPointsOfTheirStreamInAnyOrder) {
    // Photon k is point k / R of stream k mod R; block 0 holds dimensions 0, 1, 4, 5,
    // block 1 dimensions 2, 3, block 2 + b dimensions 6 + 3b .. 8 + 3b, unused words 0,
    // and blocks past the Sobol dimensions are the photon's Philox blocks. The sampler
    // steps each dimension from the last point asked for, so it is asked in a random
    // order, in batches of 1 to 8, with indices near and far apart.
    constexpr std::uint64_t seed = 77;
    constexpr std::uint32_t R = PhotonSampler::kDefaultReplicates;
    PhotonSampler sampler(SamplerKind::sobol, seed);
    const SobolSequence seq(PhotonSampler::kSobolDimensions);
    const PhiloxSampler philox(seed);
    std::mt19937_64 pick(5);
    for (int trial = 0; trial < 20000; ++trial) {
        const std::size_t n = 1 + static_cast<std::size_t>(pick() % PhiloxSampler::kBatch);
        std::uint64_t k[PhiloxSampler::kBatch];
        std::uint32_t b[PhiloxSampler::kBatch];
        PhotonSampler::Block got[PhiloxSampler::kBatch];
        for (std::size_t i = 0; i < n; ++i) {
            k[i] = trial % 4 == 0 ? pick() % (std::uint64_t{1} << 34) : 1000 + pick() % 64;
            b[i] = static_cast<std::uint32_t>(pick() % (4 + PhotonSampler::kSobolBounces));
        }
        sampler.blocks(k, b, n, got);
        for (std::size_t i = 0; i < n; ++i) {
            PhotonSampler::Block want{};
            const auto stream = static_cast<std::uint32_t>(k[i] % R);
            const auto index = static_cast<std::uint32_t>(k[i] / R);
            auto word = [&](std::uint32_t d) {
                return seq.scrambled(index, d, SobolSequence::scramble_seed(seed, stream, d));
            };
            if (b[i] >= 2 + PhotonSampler::kSobolBounces) want = philox.block(k[i], b[i]);
            else if (b[i] == 0) want = {word(0), word(1), word(4), word(5)};
            else if (b[i] == 1) want = {word(2), word(3), 0, 0};
            else want = {word(6 + 3 * (b[i] - 2)), word(7 + 3 * (b[i] - 2)), word(8 + 3 * (b[i] - 2)), 0};
            ASSERT_EQ(got[i], want) << "photon " << k[i] << " block " << b[i] << " (trial " << trial << ")";
        }
    }
    // Past 2^32 points a stream goes on with a fresh scramble (stream number + R per epoch).
    const std::uint64_t far = (std::uint64_t{3} << 32) * R + 13;  // epoch 3, point 1, stream 5
    const std::uint32_t far_stream = 5 + 3 * R;
    EXPECT_EQ(sampler.block(far, 0),
              (PhotonSampler::Block{seq.scrambled(1, 0, SobolSequence::scramble_seed(seed, far_stream, 0)),
                                    seq.scrambled(1, 1, SobolSequence::scramble_seed(seed, far_stream, 1)),
                                    seq.scrambled(1, 4, SobolSequence::scramble_seed(seed, far_stream, 4)),
                                    seq.scrambled(1, 5, SobolSequence::scramble_seed(seed, far_stream, 5))}));
    EXPECT_EQ(sampler.block(12345, 3),
              (PhotonSampler::Block{seq.scrambled(12345 / R, 9, SobolSequence::scramble_seed(seed, 12345 % R, 9)),
                                    seq.scrambled(12345 / R, 10, SobolSequence::scramble_seed(seed, 12345 % R, 10)),
                                    seq.scrambled(12345 / R, 11, SobolSequence::scramble_seed(seed, 12345 % R, 11)),
                                    0}));
}

TEST(PhotonSampler, RandomBlocksArePhiloxBlocksAndReplicatesAreChecked) {
    PhotonSampler random(SamplerKind::random, 9);
    const PhiloxSampler philox(9);
    for (std::uint64_t k = 0; k < 100; ++k)
        for (std::uint32_t b = 0; b < 5; ++b) ASSERT_EQ(random.block(k, b), philox.block(k, b));
    // R must be even (odd photons, the odd map, then come from odd streams only).
    for (const std::uint32_t bad : {0u, 1u, 3u, 7u, 2048u})
        EXPECT_THROW(PhotonSampler(SamplerKind::sobol, 1, bad), InputError);
    EXPECT_NO_THROW(PhotonSampler(SamplerKind::sobol, 1, 6));  // even, not a power of two
    EXPECT_EQ(sampler_kind("sobol"), SamplerKind::sobol);
    EXPECT_THROW(sampler_kind("halton"), InputError);
}

TEST(Replicates, SpreadOfReplicateMeansIsAnHonestErrorForQmcAndPerPhotonVarianceIsNot) {
    // 2000 runs of a QMC estimate of the integral of f(x0, x1, x4) = x0 x1 + x4^2 (1/4 +
    // 1/3) over R = 8 streams of 256 Owen-scrambled Sobol points each, dimensions as the
    // photon sampler maps them. The replicate estimate's sigma^2 averaged over runs
    // matches the observed variance of the run means (within 20 %: 4.5 sigma at 2000
    // runs); |mean - exact| < t(0.975, 7) sigma in 95 % of runs (binomial, +-2.2 %); and
    // eq. (8)'s per-point variance over N, which assumes independent points, would
    // overstate the error several times over, so a test built on it could not pass.
    constexpr int kRuns = 2000;
    constexpr std::uint32_t R = 8, n = 256;
    constexpr double exact = 0.25 + 1.0 / 3.0, t975_7 = 2.364624;
    const SobolSequence seq(6);
    std::vector<double> means;
    double sum_var = 0.0, sum_iid_var = 0.0;
    int covered = 0;
    for (int run = 0; run < kRuns; ++run) {
        std::vector<double> sums(R, 0.0);
        double sum_f2 = 0.0;
        for (std::uint32_t r = 0; r < R; ++r) {
            const std::uint32_t s0 = SobolSequence::scramble_seed(run, r, 0),
                                s1 = SobolSequence::scramble_seed(run, r, 1),
                                s4 = SobolSequence::scramble_seed(run, r, 4);
            for (std::uint32_t i = 0; i < n; ++i) {
                const double f = PhiloxSampler::uniform(seq.scrambled(i, 0, s0)) *
                                     PhiloxSampler::uniform(seq.scrambled(i, 1, s1)) +
                                 std::pow(PhiloxSampler::uniform(seq.scrambled(i, 4, s4)), 2);
                sums[r] += f;
                sum_f2 += f * f;
            }
        }
        const std::vector<std::uint64_t> photons(R, n);
        const ReplicateEstimate e = replicate_estimate(sums, photons);
        ASSERT_EQ(e.dof, 7);
        means.push_back(e.mean);
        sum_var += e.sigma * e.sigma;
        covered += std::abs(e.mean - exact) < t975_7 * e.sigma;
        const double N = double(R * n);
        sum_iid_var += (sum_f2 / N - e.mean * e.mean) / N;  // eq. (8)'s view: independent points
    }
    double m = 0.0, v = 0.0;
    for (double x : means) m += x / kRuns;
    for (double x : means) v += (x - m) * (x - m) / (kRuns - 1);
    const double ratio = (sum_var / kRuns) / v, iid_ratio = std::sqrt((sum_iid_var / kRuns) / v);
    const double coverage = double(covered) / kRuns;
    std::printf("  estimated / observed variance %.3f; coverage %.3f; eq. (8)-style sigma / observed %.1f\n", ratio,
                coverage, iid_ratio);
    EXPECT_GT(ratio, 0.8);
    EXPECT_LT(ratio, 1.2);
    EXPECT_NEAR(coverage, 0.95, 0.022);
    EXPECT_GT(iid_ratio, 3.0);
    EXPECT_LT(std::abs(m - exact), 4.0 * std::sqrt(v / kRuns));
}

TEST(Replicates, UnequalReplicateSizesAndTooFewReplicates) {
    // Equal sizes: s^2 / R with s^2 the sample variance of the replicate means.
    const std::vector<double> sums = {10.0, 14.0, 12.0, 8.0};
    const std::vector<std::uint64_t> equal = {10, 10, 10, 10};
    const ReplicateEstimate e = replicate_estimate(sums, equal);
    // means 1.0, 1.4, 1.2, 0.8: mean 1.1, sample variance 0.0666..., over R = 4.
    EXPECT_NEAR(e.mean, 1.1, 1e-12);
    EXPECT_NEAR(e.sigma, std::sqrt((0.01 + 0.09 + 0.01 + 0.09) / 3.0 / 4.0), 1e-12);
    EXPECT_EQ(e.dof, 3);
    // A stop in the middle of a round: the pooled mean weighs every photon alike.
    const std::vector<std::uint64_t> unequal = {11, 10, 10, 10};
    EXPECT_NEAR(replicate_estimate(sums, unequal).mean, 44.0 / 41.0, 1e-12);
    EXPECT_TRUE(std::isnan(replicate_estimate(std::vector<double>{1.0}, std::vector<std::uint64_t>{5}).sigma));
    EXPECT_TRUE(std::isnan(replicate_estimate(sums, std::vector<std::uint64_t>{10, 0, 10, 10}).sigma));
}

}  // namespace
}  // namespace luxtrace

// The alias table gives each cell its probability (chi-square over many draws on random
// tables with empty cells), never an empty cell, and a uniform position within the cell.
TEST(AliasTable, CellsComeWithTheirProbabilityAndUniformPositions) {
    using namespace luxtrace;
    PhiloxSampler s(77);
    s.start_photon(0);
    for (int trial = 0; trial < 6; ++trial) {
        const int n = 1 + static_cast<int>(s.next() * 300);
        std::vector<double> w(static_cast<std::size_t>(n));
        double sum = 0.0;
        for (double& x : w) sum += (x = s.next() < 0.3 ? 0.0 : s.next());
        if (sum == 0.0) sum += (w[0] = 1.0);
        const AliasTable table(w);
        for (int i = 0; i < n; ++i) EXPECT_NEAR(table.probability(i), w[i] / sum, 1e-6) << "cell " << i;
        constexpr int kDraws = 400000;
        std::vector<std::int64_t> obs(static_cast<std::size_t>(n), 0), pos(10, 0);
        PhiloxSampler draw(1000 + trial);
        for (int k = 0; k < kDraws; ++k) {
            draw.start_photon(static_cast<std::uint64_t>(k));
            const AliasTable::Pick p = table.sample(draw.next());
            ASSERT_GT(w[p.cell], 0.0) << "an empty cell was drawn";
            ASSERT_TRUE(p.t >= 0.0 && p.t < 1.0) << p.t;
            ++obs[p.cell];
            ++pos[std::min(9, static_cast<int>(p.t * 10))];
        }
        expect_chi_square(obs, w, "alias cells");
        expect_chi_square(pos, std::vector<double>(10, 1.0), "position in the cell");
    }
}
