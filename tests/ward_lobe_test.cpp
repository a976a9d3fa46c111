// The glossy lobe (ward_lobe.hpp, docs/MATERIALS.md#glossy-reflection): its albedo is
// the integral of its BRDF, it is reciprocal, photons leave along f cos / a and survive
// with a, and a glossy material reflects rho_d + rho_s a(cos_i) of what arrives.
#include "luxtrace/material/ward_lobe.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/material/material.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/scene/scene.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace luxtrace;

namespace {

constexpr double kSigmas = 4.0;  // z-score bound for the binomial checks

const Vec3 kN(0.0, 0.0, 1.0);

// The unit vector at polar angle theta from kN, azimuth phi.
Vec3 polar(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Integral of f cos(theta_o) over the hemisphere, straight from the BRDF: polar angle
// beta about the mirror direction on a grid dense near it (beta = pi t^2), azimuth gamma
// about it, midpoint in t and gamma.
double hemisphere_integral(const WardLobe& lobe, double theta_i) {
    const Vec3 wi = polar(theta_i, 0.0);
    const Vec3 r = 2.0 * wi.z * kN - wi;
    const Frame f = Frame::around(r);
    constexpr int kT = 3000, kG = 720;
    double sum = 0.0;
    for (int i = 0; i < kT; ++i) {
        const double t = (i + 0.5) / kT;
        const double beta = kPi * t * t, dbeta = 2.0 * kPi * t / kT;
        for (int j = 0; j < kG; ++j) {
            const double gamma = 2.0 * kPi * (j + 0.5) / kG;
            const Vec3 wo = f.to_world(polar(beta, gamma));
            if (wo.z <= 0.0) continue;
            sum += lobe.brdf(wi, wo, kN) * wo.z * std::sin(beta) * dbeta;
        }
    }
    return sum * 2.0 * kPi / kG;
}

TEST(WardLobe, AlbedoIsTheIntegralOfTheBrdf) {
    for (double alpha : {0.05, 0.1, 0.2, 0.4, 0.8}) {
        const WardLobe lobe(alpha);
        for (double deg : {0.0, 30.0, 60.0, 80.0}) {
            const double theta = deg * kPi / 180.0;
            const double direct = hemisphere_integral(lobe, theta);
            EXPECT_NEAR(ward_albedo_quadrature(alpha, std::cos(theta)), direct, 1e-3)
                << "alpha " << alpha << ", " << deg << " deg";
            EXPECT_NEAR(lobe.albedo(std::cos(theta)), direct, 1e-3) << "alpha " << alpha << ", " << deg << " deg";
        }
    }
}

TEST(WardLobe, NormalIncidenceAlbedoInClosedForm) {
    // At cos_i = 1 the weight W4 is 1 - tan^2(theta_h) below 45 degrees, and tan^2 is
    // exponential with mean alpha^2: a = 1 - alpha^2 (1 - exp(-1 / alpha^2)).
    for (double alpha : {0.02, 0.1, 0.3, 0.6, 1.0}) {
        const double exact = 1.0 - alpha * alpha * (1.0 - std::exp(-1.0 / (alpha * alpha)));
        EXPECT_NEAR(ward_albedo_quadrature(alpha, 1.0), exact, 1e-4) << alpha;  // midpoint in u1: 3e-5 at alpha 0.3
        EXPECT_NEAR(WardLobe(alpha).albedo(1.0), exact, 1e-4) << alpha;
    }
}

TEST(WardLobe, AlbedoNeverExceedsOneAndTheTableHoldsBetweenNodes) {
    for (double alpha : {0.01, 0.03, 0.1, 0.25, 0.5, 1.0}) {
        const WardLobe lobe(alpha);
        double worst = 0.0;
        for (int k = 0; k <= 400; ++k) {
            const double c = k / 400.0;
            const double q = ward_albedo_quadrature(alpha, c);
            EXPECT_LE(q, 1.0) << "alpha " << alpha << ", cos_i " << c;
            EXPECT_GT(q, 0.3) << "alpha " << alpha << ", cos_i " << c;
            worst = std::max(worst, std::abs(lobe.albedo(c) - q));
        }
        EXPECT_LT(worst, 2e-3) << "table against quadrature, alpha " << alpha;
    }
}

TEST(WardLobe, Reciprocal) {
    PhiloxSampler s(7);
    for (double alpha : {0.05, 0.3, 1.0}) {
        const WardLobe lobe(alpha);
        for (std::uint64_t k = 0; k < 2000; ++k) {
            s.start_photon(k);
            const Vec3 wi = polar(std::acos(s.next()), 2.0 * kPi * s.next());
            const Vec3 wo = polar(std::acos(s.next()), 2.0 * kPi * s.next());
            const double a = lobe.brdf(wi, wo, kN), b = lobe.brdf(wo, wi, kN);
            EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, a)) << alpha;
        }
    }
}

// Upper tail of chi-square with `dof` degrees of freedom beyond x (Wilson-Hilferty).
double chi2_upper_tail(double x, double dof) {
    const double z = (std::cbrt(x / dof) - (1.0 - 2.0 / (9.0 * dof))) / std::sqrt(2.0 / (9.0 * dof));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// Reflected photons binned in (cos theta_o, phi_o) against f cos / a integrated over each
// bin; survivors against a (binomial).
void expect_lobe_distribution(double alpha, double theta_i_deg) {
    const WardLobe lobe(alpha);
    const double theta_i = theta_i_deg * kPi / 180.0;
    const Vec3 dir = -polar(theta_i, 0.0);
    const double a = lobe.albedo(std::cos(theta_i));
    constexpr int kC = 20, kP = 24, kSub = 12;
    constexpr std::uint64_t kPhotons = 400000;
    std::vector<double> observed(kC * kP, 0.0), expected(kC * kP, 0.0);
    PhiloxSampler s(11);
    std::uint64_t survived = 0;
    for (std::uint64_t k = 0; k < kPhotons; ++k) {
        s.start_photon(k);
        const double u = s.next(), u1 = s.next(), u2 = s.next();
        const auto wo = lobe.reflect(dir, kN, u, u1, u2);
        if (!wo) continue;
        ++survived;
        ASSERT_GT(wo->z, 0.0);
        ASSERT_NEAR(glm::length(*wo), 1.0, 1e-12);
        double phi = std::atan2(wo->y, wo->x);
        if (phi < 0.0) phi += 2.0 * kPi;
        const int ic = std::min(kC - 1, static_cast<int>(wo->z * kC));
        const int ip = std::min(kP - 1, static_cast<int>(phi / (2.0 * kPi) * kP));
        observed[static_cast<std::size_t>(ic * kP + ip)] += 1.0;
    }
    const double n = static_cast<double>(kPhotons);
    const double z = (static_cast<double>(survived) - n * a) / std::sqrt(n * a * (1.0 - a));
    EXPECT_LT(std::abs(z), kSigmas) << "survivors " << survived << " of " << kPhotons << ", albedo " << a;
    // Expected counts: f cos / a over each bin, midpoint on a sub-grid (d omega = dcos dphi).
    const Vec3 wi = -dir;
    for (int ic = 0; ic < kC; ++ic)
        for (int ip = 0; ip < kP; ++ip) {
            double sum = 0.0;
            for (int x = 0; x < kSub; ++x)
                for (int y = 0; y < kSub; ++y) {
                    const double c = (ic + (x + 0.5) / kSub) / kC;
                    const double phi = 2.0 * kPi * (ip + (y + 0.5) / kSub) / kP;
                    sum += lobe.brdf(wi, polar(std::acos(c), phi), kN) * c;
                }
            expected[static_cast<std::size_t>(ic * kP + ip)] = sum / (kSub * kSub) * (1.0 / kC) * (2.0 * kPi / kP) / a *
                                                               static_cast<double>(survived);
        }
    // Bins expecting fewer than 20 photons are pooled into one.
    double chi2 = 0.0, rest_o = 0.0, rest_e = 0.0;
    int bins = 0;
    for (std::size_t b = 0; b < observed.size(); ++b) {
        if (expected[b] < 20.0) {
            rest_o += observed[b];
            rest_e += expected[b];
            continue;
        }
        chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++bins;
    }
    if (rest_e >= 20.0) {
        chi2 += (rest_o - rest_e) * (rest_o - rest_e) / rest_e;
        ++bins;
    }
    ASSERT_GT(bins, 20) << "too few bins to test";
    const double p = chi2_upper_tail(chi2, bins - 1);
    EXPECT_GT(p, 1e-4) << "alpha " << alpha << ", " << theta_i_deg << " deg: chi2 " << chi2 << " over " << bins
                       << " bins";
}

TEST(WardLobe, SampledDirectionsFollowBrdfTimesCosine) {
    expect_lobe_distribution(0.3, 0.0);
    expect_lobe_distribution(0.3, 45.0);
    expect_lobe_distribution(0.2, 70.0);
    expect_lobe_distribution(0.6, 80.0);
}

// A general material with a glossy specular part: of the photons arriving at cos_i, the
// share that leaves is rho_d + rho_s a(cos_i), the rest absorbed (the energy balance of
// one wall of a closed box, at each incidence); roughness 0 keeps the mirror exactly.
TEST(WardLobe, GlossyMaterialReflectsRhoTimesAlbedo) {
    Material m;
    m.type = MaterialType::general;
    m.diffuse_reflectance = {0.2};
    m.specular_reflectance = {0.7};
    m.diffuse_transmittance = {0.0};
    m.specular_transmittance = {0.0};
    m.set_roughness(0.5);
    const ScatterModel model = scatter_model(m, 0);
    PhiloxSampler s(3);
    for (double deg : {0.0, 40.0, 75.0, 88.0}) {
        const Vec3 dir = -polar(deg * kPi / 180.0, 1.0);
        const double p = 0.2 + 0.7 * m.lobe->albedo(std::cos(deg * kPi / 180.0));
        constexpr std::uint64_t kPhotons = 200000;
        std::uint64_t left = 0;
        for (std::uint64_t k = 0; k < kPhotons; ++k) {
            s.start_photon(k);
            const double u = s.next(), u1 = s.next(), u2 = s.next();
            const Scattered r = scatter(model, dir, kN, u, u1, u2);
            if (r.event == ScatterEvent::absorbed) continue;
            ++left;
            ASSERT_GT(r.direction.z, 0.0);
        }
        const double n = static_cast<double>(kPhotons);
        const double z = (static_cast<double>(left) - n * p) / std::sqrt(n * p * (1.0 - p));
        EXPECT_LT(std::abs(z), kSigmas) << deg << " deg: " << left << " of " << kPhotons << " leave, expected " << p;
    }
    // Roughness 0: no lobe, the mirror direction exactly.
    m.set_roughness(0.0);
    EXPECT_EQ(m.lobe, nullptr);
    const Vec3 dir = -polar(0.5, 0.3);
    const Scattered r = scatter(scatter_model(m, 0), dir, kN, 0.5, 0.1, 0.2);
    EXPECT_EQ(r.event, ScatterEvent::specular_reflection);
    EXPECT_EQ(r.direction, dir - 2.0 * glm::dot(dir, kN) * kN);
}

// [[material]] roughness: read on mirror and general, refused out of [0, 1] and on the
// other types, with the key named.
TEST(WardLobe, SceneKeyRoughness) {
    namespace fs = std::filesystem;
    const fs::path file = fs::temp_directory_path() / ("luxtrace_ward_" + std::to_string(::getpid()) + ".toml");
    auto load = [&](const std::string& material) -> std::string {
        std::ofstream(file) << "[[material]]\nname = \"m\"\n"
                            << material
                            << "[[shape]]\ntype = \"rectangle\"\nsize = [1, 1]\nmaterial = \"m\"\n"
                               "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 10\n";
        try {
            const Scene scene = load_scene(file);
            const Material& m = scene.materials.at(0);
            return m.lobe ? "lobe " + std::to_string(m.lobe->alpha()) : "no lobe";
        } catch (const InputError& e) {
            return e.what();
        }
    };
    EXPECT_EQ(load("type = \"mirror\"\nspecular_reflectance = 0.9\nroughness = 0.25\n"), "lobe 0.250000");
    EXPECT_EQ(load("type = \"general\"\nspecular_reflectance = 0.5\nroughness = 0\n"), "no lobe");
    const std::string high = load("type = \"general\"\nspecular_reflectance = 0.5\nroughness = 1.5\n");
    EXPECT_NE(high.find("roughness"), std::string::npos) << high;
    EXPECT_NE(high.find("must lie in [0, 1]"), std::string::npos) << high;
    const std::string diffuse = load("reflectance = 0.5\nroughness = 0.1\n");
    EXPECT_NE(diffuse.find("'roughness' does not apply"), std::string::npos) << diffuse;
    fs::remove(file);
}

}  // namespace
