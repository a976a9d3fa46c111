// Tests of the dielectric Fresnel term against independent formulas and known numbers,
// and of analog scattering: event frequencies match the material's probabilities
// (binomial z-scores within 4 sigma), directions obey reflection and Snell's law,
// and a clear glass slab transmits (1 - R) / (1 + R).
#include "luxtrace/material/material.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kSigmas = 4.0;  // z-score bound for every binomial check here

double sq(double x) { return x * x; }

// Unpolarised reflectance from the Snell angles in the sine/tangent forms of the
// Fresnel equations (not the cosine form the library uses); n1 on the incident side.
double fresnel_reference(double theta_i, double n1, double n2) {
    const double sin_t = n1 / n2 * std::sin(theta_i);
    if (sin_t >= 1.0) return 1.0;
    if (theta_i == 0.0) return sq((n1 - n2) / (n1 + n2));
    const double tt = std::asin(sin_t);
    const double rs = sq(std::sin(theta_i - tt) / std::sin(theta_i + tt));
    const double rp = sq(std::tan(theta_i - tt) / std::tan(theta_i + tt));
    return 0.5 * (rs + rp);
}

TEST(Fresnel, MatchesSineTangentFormsOverAngles) {
    const std::vector<std::pair<double, double>> media = {{1.0, 1.5}, {1.0, 1.333}, {1.0, 2.42},
                                                          {1.5, 1.0}, {1.333, 1.0}, {1.5, 1.333}};
    for (const auto& [n1, n2] : media)
        for (int deg = 1; deg < 90; ++deg) {
            const double ti = deg * kDeg;
            if (n1 > n2 && std::sin(ti) >= n2 / n1) continue;  // TIR: its own test
            EXPECT_NEAR(fresnel_dielectric(std::cos(ti), n1 / n2), fresnel_reference(ti, n1, n2), 1e-12)
                << "n1 " << n1 << " n2 " << n2 << " angle " << deg;
        }
}

TEST(Fresnel, KnownValues) {
    // Normal incidence ((n-1)/(n+1))^2, from either side.
    EXPECT_NEAR(fresnel_dielectric(1.0, 1.0 / 1.5), 0.04, 1e-15);
    EXPECT_NEAR(fresnel_dielectric(1.0, 1.5), 0.04, 1e-15);
    EXPECT_NEAR(fresnel_dielectric(1.0, 1.0 / 1.333), sq(0.333 / 2.333), 1e-15);
    EXPECT_NEAR(fresnel_dielectric(1.0, 1.0), 0.0, 1e-15);
    // Brewster angle atan(n2/n1): Rp = 0, so R = Rs / 2 with Rs = ((n^2-1)/(n^2+1))^2
    // there (from both sides, the ratio inverted).
    for (const double n : {1.5, 1.333, 2.42}) {
        const double rs = sq((n * n - 1.0) / (n * n + 1.0));
        EXPECT_NEAR(fresnel_dielectric(std::cos(std::atan(n)), 1.0 / n), 0.5 * rs, 1e-12) << n;
        EXPECT_NEAR(fresnel_dielectric(std::cos(std::atan(1.0 / n)), n), 0.5 * rs, 1e-12) << n;
    }
    // Grazing incidence from air reflects everything in the limit.
    EXPECT_GT(fresnel_dielectric(1e-6, 1.0 / 1.5), 0.9999);
}

TEST(Fresnel, TotalInternalReflectionAboveCriticalAngle) {
    const double n = 1.5, critical = std::asin(1.0 / n);  // 41.81 deg, glass to air
    for (double t = critical + 1e-6; t < 0.5 * kPi; t += 0.01)
        EXPECT_EQ(fresnel_dielectric(std::cos(t), n), 1.0) << t / kDeg;
    EXPECT_EQ(fresnel_dielectric(0.0, n), 1.0);
    EXPECT_LT(fresnel_dielectric(std::cos(critical - 0.5 * kDeg), n), 1.0);
    // R rises continuously to 1 at the critical angle.
    EXPECT_GT(fresnel_dielectric(std::cos(critical - 1e-7), n), 0.99);
}

TEST(Fresnel, ReciprocityAcrossTheInterface) {
    for (const double n : {1.5, 1.333, 2.42})
        for (int deg = 0; deg < 90; ++deg) {
            const double ti = deg * kDeg, tt = std::asin(std::sin(ti) / n);
            EXPECT_NEAR(fresnel_dielectric(std::cos(ti), 1.0 / n), fresnel_dielectric(std::cos(tt), n), 1e-12)
                << n << " " << deg;
        }
}

// ---- analog scattering -------------------------------------------------------------

constexpr int kEvents = 6;  // ScatterEvent values

struct Outcome {
    std::int64_t n = 0;
    std::array<std::int64_t, kEvents> count{};
    std::int64_t bad_unit = 0, bad_side = 0, bad_side_flag = 0, bad_mirror = 0, bad_snell = 0, bad_straight = 0;
    double cos_sum = 0.0;  // diffuse events: cos to the outgoing side's normal
    std::int64_t cos_n = 0;
};

// Direction at angle theta to the normal on the side given by `front`, travelling
// toward the surface.
Vec3 incoming(const Vec3& ng, double theta, bool front) {
    const Vec3 t = glm::normalize(glm::cross(ng, Vec3(1, 0, 0)));
    const Vec3 n_in = front ? ng : -ng;
    return -std::cos(theta) * n_in + std::sin(theta) * t;
}

Outcome run_scatter(const Material& m, int band, const Vec3& dir, const Vec3& ng, std::uint64_t seed, int photons) {
    Outcome o;
    PhiloxSampler s(seed);
    const bool front = glm::dot(dir, ng) < 0.0;
    const Vec3 n_in = front ? ng : -ng;                               // normal on the incoming side
    const double n1 = front ? 1.0 : m.ior, n2 = front ? m.ior : 1.0;  // glass only
    const Vec3 tan_in = dir - glm::dot(dir, n_in) * n_in;
    for (int k = 0; k < photons; ++k) {
        s.start_photon(static_cast<std::uint64_t>(k));
        const double u = s.next(), u1 = s.next(), u2 = s.next();
        const Scattered r = scatter(m, band, dir, ng, u, u1, u2);
        ++o.n;
        ++o.count[static_cast<int>(r.event)];
        if (r.event == ScatterEvent::absorbed) continue;
        const Vec3& d = r.direction;
        o.bad_unit += std::abs(glm::length(d) - 1.0) > 1e-12;
        const bool reflected = r.event == ScatterEvent::diffuse_reflection ||
                               r.event == ScatterEvent::specular_reflection;
        o.bad_side_flag += r.side != (reflected ? 1 : -1);
        const double c = glm::dot(d, n_in);
        o.bad_side += reflected ? !(c > 0.0) : !(c < 0.0);
        const Vec3 tan_out = d - c * n_in;
        switch (r.event) {
        case ScatterEvent::specular_reflection:  // angle out = angle in, same plane
            o.bad_mirror += std::abs(c + glm::dot(dir, n_in)) > 1e-12 || glm::length(tan_out - tan_in) > 1e-12;
            break;
        case ScatterEvent::refraction: {  // n1 sin ti = n2 sin tt, in the plane of incidence
            const double sin_i = glm::length(tan_in), sin_t = glm::length(tan_out);
            o.bad_snell += std::abs(n1 * sin_i - n2 * sin_t) > 1e-12 || glm::length(n2 * tan_out - n1 * tan_in) > 1e-12;
            break;
        }
        case ScatterEvent::specular_transmission: o.bad_straight += glm::length(d - dir) > 1e-12; break;
        case ScatterEvent::diffuse_reflection:
        case ScatterEvent::diffuse_transmission:
            o.cos_sum += std::abs(c);
            ++o.cos_n;
            break;
        case ScatterEvent::absorbed: break;
        }
    }
    return o;
}

const char* event_name(int e) {
    static const char* names[kEvents] = {"absorbed",
                                         "diffuse_reflection",
                                         "specular_reflection",
                                         "diffuse_transmission",
                                         "specular_transmission",
                                         "refraction"};
    return names[e];
}

// Every event's frequency against its probability (events not listed have p = 0), and
// every geometric check clean.
void expect_outcome(const Outcome& o, const std::vector<std::pair<ScatterEvent, double>>& probs,
                    const std::string& what) {
    std::array<double, kEvents> p{};
    for (const auto& [e, pe] : probs) p[static_cast<int>(e)] = pe;
    double total = 0.0;
    for (double pe : p) total += pe;
    EXPECT_NEAR(total, 1.0, 1e-12) << what << ": the test's probabilities";
    std::int64_t returned = 0;
    for (int e = 0; e < kEvents; ++e) {
        const std::int64_t c = o.count[e];
        if (e != static_cast<int>(ScatterEvent::absorbed)) returned += c;
        if (p[e] <= 0.0) {
            EXPECT_EQ(c, 0) << what << ": " << event_name(e);
            continue;
        }
        if (p[e] >= 1.0) {
            EXPECT_EQ(c, o.n) << what << ": " << event_name(e);
            continue;
        }
        const double np = static_cast<double>(o.n) * p[e];
        const double z = (static_cast<double>(c) - np) / std::sqrt(np * (1.0 - p[e]));
        EXPECT_LT(std::abs(z), kSigmas) << what << ": " << event_name(e) << " " << c << " of " << o.n << ", expected p "
                                        << p[e] << ", z " << z;
    }
    // Energy: the share of photons that leave the surface is 1 - p(absorbed), within
    // sigmas (binomial), or exactly all or none.
    const double p_return = 1.0 - p[static_cast<int>(ScatterEvent::absorbed)];
    if (p_return <= 0.0 || p_return >= 1.0) {
        EXPECT_EQ(returned, p_return <= 0.0 ? 0 : o.n) << what << ": photons leaving the surface";
    } else {
        const double np = static_cast<double>(o.n) * p_return;
        const double z = (static_cast<double>(returned) - np) / std::sqrt(np * (1.0 - p_return));
        EXPECT_LT(std::abs(z), kSigmas) << what << ": " << returned << " of " << o.n << " leave, expected p "
                                        << p_return << ", z " << z;
    }
    EXPECT_EQ(o.bad_unit, 0) << what << ": non-unit directions";
    EXPECT_EQ(o.bad_side, 0) << what << ": directions on the wrong side";
    EXPECT_EQ(o.bad_side_flag, 0) << what << ": wrong Scattered::side";
    EXPECT_EQ(o.bad_mirror, 0) << what << ": mirror reflection angle";
    EXPECT_EQ(o.bad_snell, 0) << what << ": Snell's law";
    EXPECT_EQ(o.bad_straight, 0) << what << ": straight-through transmission bent";
    if (o.cos_n > 0) {  // cosine lobe: E[cos] = 2/3, Var[cos] = 1/2 - 4/9 = 1/18
        const double mean = o.cos_sum / static_cast<double>(o.cos_n);
        const double z = (mean - 2.0 / 3.0) / std::sqrt(1.0 / 18.0 / static_cast<double>(o.cos_n));
        EXPECT_LT(std::abs(z), kSigmas) << what << ": diffuse mean cosine " << mean;
    }
}

const Vec3 kNormal = glm::normalize(Vec3(1.0, -2.0, 2.0));
constexpr int kPhotons = 100000;

Material make(MaterialType type) {
    Material m;
    m.type = type;
    m.name = "test";
    return m;
}

TEST(Scatter, DiffuseReflectsCosineLobeOnIncomingSide) {
    Material m = make(MaterialType::diffuse);
    m.diffuse_reflectance = {0.8, 0.35};
    for (const bool front : {true, false})
        for (const int band : {0, 1}) {
            const double rho = m.diffuse_reflectance[band];
            const Outcome o = run_scatter(m, band, incoming(kNormal, 35 * kDeg, front), kNormal, 21 + band, kPhotons);
            expect_outcome(o, {{ScatterEvent::diffuse_reflection, rho}, {ScatterEvent::absorbed, 1.0 - rho}},
                           std::string("diffuse ") + (front ? "front" : "back"));
        }
}

TEST(Scatter, MirrorReflectsAtTheIncidenceAngle) {
    Material m = make(MaterialType::mirror);
    m.specular_reflectance = {0.9, 0.6};
    for (const bool front : {true, false})
        for (const double deg : {0.0, 35.0, 85.0}) {
            const Outcome o = run_scatter(m, 1, incoming(kNormal, deg * kDeg, front), kNormal, 22, kPhotons);
            expect_outcome(o, {{ScatterEvent::specular_reflection, 0.6}, {ScatterEvent::absorbed, 0.4}},
                           "mirror " + std::to_string(deg));
        }
}

TEST(Scatter, GlassReflectsByFresnelAndRefractsBySnell) {
    Material clear = make(MaterialType::glass);
    clear.ior = 1.5;
    Material tinted = clear;
    tinted.transmittance = {0.9, 0.7};
    // Front: air into glass; back: glass into air below the critical angle (41.8 deg).
    const std::vector<std::pair<bool, double>> cases = {{true, 0.0},
                                                        {true, 35.0},
                                                        {true, 80.0},
                                                        {false, 20.0},
                                                        {false, 40.0}};
    for (const auto& [front, deg] : cases)
        for (const Material* m : {&clear, &tinted}) {
            const double n1 = front ? 1.0 : m->ior, n2 = front ? m->ior : 1.0;
            const double r = fresnel_reference(deg * kDeg, n1, n2);
            const double t = m->transmittance.empty() ? 1.0 : m->transmittance[1];
            const Outcome o = run_scatter(*m, 1, incoming(kNormal, deg * kDeg, front), kNormal, 23, kPhotons);
            expect_outcome(o,
                           {{ScatterEvent::specular_reflection, r},
                            {ScatterEvent::refraction, (1.0 - r) * t},
                            {ScatterEvent::absorbed, (1.0 - r) * (1.0 - t)}},
                           std::string("glass ") + (front ? "front " : "back ") + std::to_string(deg) +
                               (m == &clear ? " clear" : " tinted"));
        }
}

TEST(Scatter, GlassTotalInternalReflectionAlwaysReflects) {
    Material clear = make(MaterialType::glass);
    clear.ior = 1.5;
    Material tinted = clear;
    tinted.transmittance = {0.5, 0.5};
    for (const double deg : {42.0, 60.0, 89.0})
        for (const Material* m : {&clear, &tinted}) {
            const Outcome o = run_scatter(*m, 0, incoming(kNormal, deg * kDeg, false), kNormal, 24, 20000);
            expect_outcome(o, {{ScatterEvent::specular_reflection, 1.0}}, "glass TIR " + std::to_string(deg));
        }
}

TEST(Scatter, GeneralSplitsIntoFourEventsAndAbsorption) {
    Material m = make(MaterialType::general);
    m.diffuse_reflectance = {0.2, 0.1};
    m.specular_reflectance = {0.1, 0.15};
    m.diffuse_transmittance = {0.3, 0.25};
    m.specular_transmittance = {0.1, 0.2};
    for (const bool front : {true, false})
        for (const int band : {0, 1}) {
            const double dr = m.diffuse_reflectance[band], sr = m.specular_reflectance[band],
                         dt = m.diffuse_transmittance[band], st = m.specular_transmittance[band];
            const Outcome o = run_scatter(m, band, incoming(kNormal, 50 * kDeg, front), kNormal, 25 + band, kPhotons);
            expect_outcome(o,
                           {{ScatterEvent::diffuse_reflection, dr},
                            {ScatterEvent::specular_reflection, sr},
                            {ScatterEvent::diffuse_transmission, dt},
                            {ScatterEvent::specular_transmission, st},
                            {ScatterEvent::absorbed, 1.0 - dr - sr - dt - st}},
                           std::string("general ") + (front ? "front" : "back") + " band " + std::to_string(band));
        }
}

TEST(Scatter, BlackAbsorbsEverything) {
    const Material m = make(MaterialType::black);
    for (const bool front : {true, false}) {
        const Outcome o = run_scatter(m, 0, incoming(kNormal, 10 * kDeg, front), kNormal, 26, 10000);
        expect_outcome(o, {{ScatterEvent::absorbed, 1.0}}, "black");
    }
}

TEST(Scatter, SurvivalAtNormalIncidenceMatchesAlbedoAndNeverExceedsOne) {
    // No material may return more than it receives: albedo <= 1, and the surviving
    // fraction of photons matches it.
    std::vector<Material> ms;
    ms.push_back(make(MaterialType::diffuse));
    ms.back().diffuse_reflectance = {0.7};
    ms.push_back(make(MaterialType::mirror));
    ms.back().specular_reflectance = {0.95};
    ms.push_back(make(MaterialType::glass));
    ms.push_back(make(MaterialType::glass));
    ms.back().transmittance = {0.6};
    ms.push_back(make(MaterialType::general));
    ms.back().diffuse_reflectance = {0.3};
    ms.back().specular_reflectance = {0.2};
    ms.back().diffuse_transmittance = {0.25};
    ms.back().specular_transmittance = {0.25};  // sums to exactly 1
    ms.push_back(make(MaterialType::black));
    const std::vector<double> want = {0.7, 0.95, 1.0, 0.04 + 0.96 * 0.6, 1.0, 0.0};
    for (std::size_t i = 0; i < ms.size(); ++i) {
        const double a = albedo(ms[i], 0);
        EXPECT_NEAR(a, want[i], 1e-12) << "material " << i;
        EXPECT_LE(a, 1.0);
        const Outcome o = run_scatter(ms[i], 0, -kNormal, kNormal, 27, kPhotons);
        const double survived = static_cast<double>(o.n - o.count[static_cast<int>(ScatterEvent::absorbed)]);
        if (want[i] <= 0.0 || want[i] >= 1.0) {
            EXPECT_EQ(survived, want[i] * static_cast<double>(o.n)) << "material " << i;
        } else {
            const double np = static_cast<double>(o.n) * want[i];
            EXPECT_LT(std::abs(survived - np) / std::sqrt(np * (1.0 - want[i])), kSigmas)
                << "material " << i << " survived " << survived;
        }
    }
}

// ---- a clear glass slab -------------------------------------------------------------

// Follows photons through an infinite slab between z = 0 (normal +z) and z = -1
// (normal -z), both faces with the air side in front. Returns the transmitted count
// and checks that transmitted photons leave parallel to the incoming direction.
std::int64_t slab_transmitted(double ior, double theta, int photons, std::int64_t* escaped) {
    Material glass = make(MaterialType::glass);
    glass.ior = ior;
    const Vec3 in(std::sin(theta), 0.0, -std::cos(theta));
    PhiloxSampler s(31);
    std::int64_t transmitted = 0, reflected = 0, bad_exit = 0, lost = 0;
    for (int k = 0; k < photons; ++k) {
        s.start_photon(static_cast<std::uint64_t>(k));
        Vec3 d = in;
        bool inside = false, done = false;
        for (std::uint32_t bounce = 0; bounce < 1000 && !done; ++bounce) {
            s.set_dimension(3 * bounce);
            const double u = s.next(), u1 = s.next(), u2 = s.next();
            // Outside, the photon can only meet the top face; inside, the face ahead.
            const Vec3 ng = (inside && d.z < 0.0) ? Vec3(0, 0, -1) : Vec3(0, 0, 1);
            const Scattered r = scatter(glass, 0, d, ng, u, u1, u2);
            if (r.event == ScatterEvent::absorbed) {
                ++lost;
                done = true;
                continue;
            }
            d = r.direction;
            if (r.side < 0) inside = !inside;
            if (!inside) {
                done = true;
                if (d.z < 0.0) {
                    ++transmitted;
                    bad_exit += glm::length(d - in) > 1e-12;
                } else {
                    ++reflected;
                }
            }
        }
        if (!done) ++lost;
    }
    EXPECT_EQ(lost, 0) << "clear glass lost photons";
    EXPECT_EQ(bad_exit, 0) << "a parallel slab must not deviate the beam";
    EXPECT_EQ(transmitted + reflected + lost, photons);
    *escaped = reflected;
    return transmitted;
}

TEST(Slab, TransmitsOneMinusROverOnePlusR) {
    // Sum over internal reflections: T = (1-R)^2 sum R^(2j) = (1-R)/(1+R); inside, the
    // reflectance is the same R by reciprocity, so this holds at oblique incidence too.
    constexpr double n = 1.5;
    constexpr int N = 200000;
    for (const double deg : {0.0, 50.0}) {
        const double R = fresnel_dielectric(std::cos(deg * kDeg), 1.0 / n);
        const double T = (1.0 - R) / (1.0 + R);
        std::int64_t reflected = 0;
        const std::int64_t t = slab_transmitted(n, deg * kDeg, N, &reflected);
        const double z = (static_cast<double>(t) - N * T) / std::sqrt(N * T * (1.0 - T));
        std::printf("  slab %4.1f deg: R = %.6f, T = %.6f, measured %.6f, z = %+.2f\n", deg, R, T,
                    static_cast<double>(t) / N, z);
        EXPECT_LT(std::abs(z), kSigmas) << "incidence " << deg << " transmitted " << t;
    }
}

}  // namespace
}  // namespace luxtrace
