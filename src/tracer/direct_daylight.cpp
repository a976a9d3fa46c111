#include "luxtrace/tracer/direct_daylight.hpp"

#include "luxtrace/light/site.hpp"
#include "luxtrace/light/sun_light.hpp"
#include "luxtrace/light/uniform_sampling.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/cell_geometry.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/portal_openings.hpp"
#include "luxtrace/tracer/shadow_ray.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace luxtrace {

namespace {

// Keeps the direct rays' random numbers apart from the photons' (same seed, other key).
constexpr std::uint64_t kDirectKey = 0xD1AEC7DA7115B0ADull;
// The ground's strata per side (one entry as large as the sky's half).
constexpr int kGroundSide = 16;
// The normals whose facings a pass computes once for all its cells (facings_of).
constexpr std::size_t kSharedNormals = 8;
// Rays per cell over the sky patches, about, when DirectDaylightOptions::sky_rays is 0.
constexpr double kSkyRaysPerCell = 9216.0;

int side_of(int rays) { return static_cast<int>(std::lround(std::sqrt(static_cast<double>(rays)))); }

// A (sin altitude, azimuth) rectangle of the sky frame: sin(altitude) in [mu_lo, mu_hi],
// azimuth from az_lo over az_width (radians).
struct Region {
    double mu_lo = 0.0, mu_hi = 1.0, az_lo = 0.0, az_width = 2.0 * kPi;
    double solid_angle_sr() const { return (mu_hi - mu_lo) * az_width; }
    Vec3 direction(double u1, double u2) const {
        const double mu = mu_lo + u1 * (mu_hi - mu_lo), az = az_lo + u2 * az_width;
        const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
        return Vec3(s * std::sin(az), s * std::cos(az), mu);
    }
    // Stratum (a, b) of side x side.
    Region stratum(int a, int b, int side) const {
        const double dmu = (mu_hi - mu_lo) / side, daz = az_width / side;
        return {mu_lo + a * dmu, mu_lo + (a + 1) * dmu, az_lo + b * daz, daz};
    }
    // Integral of the direction over the region, dw = d(sin alt) d(az): cos(alt) integrates
    // to S = [(mu sqrt(1 - mu^2) + asin mu) / 2], so the integral of n . w is n . this.
    Vec3 direction_integral() const {
        auto f = [](double mu) { return 0.5 * (mu * std::sqrt(std::max(0.0, 1.0 - mu * mu)) + std::asin(mu)); };
        const double s = f(mu_hi) - f(mu_lo), a1 = az_lo + az_width;
        return {s * (std::cos(az_lo) - std::cos(a1)), s * (std::sin(a1) - std::sin(az_lo)),
                0.5 * (mu_hi * mu_hi - mu_lo * mu_lo) * az_width};
    }
    // A cone (axis in the sky frame, cosine of its half-angle) holding every direction of
    // the region: the axis at its middle altitude and azimuth; the half-angle at most half
    // the altitude's span plus the longest half parallel (a path along the meridian, then
    // the parallel, is no shorter than the arc), and a little for rounding.
    std::pair<Vec3, double> bounding_cone() const {
        const double alt_lo = std::asin(std::clamp(mu_lo, -1.0, 1.0)), alt_hi = std::asin(std::clamp(mu_hi, -1.0, 1.0));
        const double alt = 0.5 * (alt_lo + alt_hi), az = az_lo + 0.5 * az_width;
        const double widest = mu_lo <= 0.0 && mu_hi >= 0.0 ? 1.0
                                                           : std::cos(std::min(std::abs(alt_lo), std::abs(alt_hi)));
        const double half = 0.5 * (alt_hi - alt_lo) + widest * 0.5 * az_width + 1e-9;
        const Vec3 axis(std::cos(alt) * std::sin(az), std::cos(alt) * std::cos(az), std::sin(alt));
        return {axis, half >= kPi ? -1.0 : std::cos(half)};
    }
    bool contains(const Vec3& w) const {
        if (w.z < mu_lo || w.z > mu_hi) return false;
        double az = std::atan2(w.x, w.y);
        while (az < az_lo) az += 2.0 * kPi;
        return az <= az_lo + az_width;
    }
    // The least and the greatest n . w over the region (n in the sky frame). n . w is linear
    // in w, so inside it has no extreme but at +-n; on the edges it is a sinusoid
    // A cos(t - t0) + C of the azimuth (rows) or of the altitude (meridians).
    std::pair<double, double> cos_range(const Vec3& n) const {
        double lo = 1.0, hi = -1.0;
        auto take = [&](double v) {
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        };
        // A cos(t - t0) + C over [t1, t2]: its ends, and its crests inside.
        auto sinusoid = [&](double a, double t0, double c, double t1, double t2) {
            take(a * std::cos(t1 - t0) + c);
            take(a * std::cos(t2 - t0) + c);
            for (const double crest : {t0, t0 + kPi})
                for (double t = crest - 4.0 * kPi; t <= t2; t += 2.0 * kPi)
                    if (t >= t1) take(a * std::cos(t - t0) + c);
        };
        const double r_xy = std::hypot(n.x, n.y), phi = std::atan2(n.x, n.y);
        for (const double mu : {mu_lo, mu_hi})  // rows: mu n_z + cos(alt) r_xy cos(az - phi)
            sinusoid(std::sqrt(std::max(0.0, 1.0 - mu * mu)) * r_xy, phi, mu * n.z, az_lo, az_lo + az_width);
        for (const double az : {az_lo, az_lo + az_width}) {  // meridians: h cos(alt) + n_z sin(alt)
            const double h = n.x * std::sin(az) + n.y * std::cos(az);
            sinusoid(std::hypot(h, n.z), std::atan2(n.z, h), 0.0, std::asin(mu_lo), std::asin(mu_hi));
        }
        if (contains(n)) hi = 1.0;
        if (contains(-n)) lo = -1.0;
        return {lo, hi};
    }
};

struct Entry {
    Region region;
    double luminance_cd_m2 = 0.0;  // what its group emits
    int side = 2;                  // side x side strata
};

struct Sun {
    Frame frame = Frame::around(Vec3(0, 0, 1));  // around the direction toward the sun
    double normal_lx = 0.0;
    // Four points of its rim (world), at 0.98 of the disc's radius: with the centre, the
    // fixed rays that tell whether a point sees the disc whole, cut or not at all.
    std::array<Vec3, 4> rim{};
};

// What a stratum of a sky entry is, whatever the cell: its region, the integral of the
// direction over it (sky frame) and a cone holding it (world).
struct Stratum {
    Region region;
    Vec3 integral{0.0};
    Vec3 cone_axis{0.0, 0.0, 1.0};
    double cone_cos_half = -1.0;
};

// The sky entries (the patches, then the ground: the lower hemisphere) and the suns.
struct Targets {
    std::vector<Entry> entries;
    std::vector<Sun> suns;
    Frame horizon;
    double cos_half_sun = 1.0;
    int sun_side = 2;

    Targets(const Scene& scene, const DirectDaylightOptions& o) : horizon(scene.site.horizon()) {
        const AnnualSky& sky = *scene.annual->sky;
        const SkyPatches& patches = sky.patches();
        const std::vector<double>& yearly = sky.yearly_luminance();
        const int side = o.sky_rays > 0 ? side_of(o.sky_rays) : sky_side(patches.count());
        for (std::size_t i = 0; i < patches.count(); ++i) {
            const SkyPatches::Patch& p = patches.patch(i);
            entries.push_back({{std::sin(p.alt_lo_deg * kPi / 180.0), std::sin(p.alt_hi_deg * kPi / 180.0),
                                p.az_lo_deg * kPi / 180.0, (p.az_hi_deg - p.az_lo_deg) * kPi / 180.0},
                               yearly[i],
                               side});
        }
        entries.push_back({{-1.0, 0.0, 0.0, 2.0 * kPi}, yearly[sky.ground_entry()], kGroundSide});
        cos_half_sun = std::cos(kSunHalfAngleDeg * kPi / 180.0);
        sun_side = side_of(o.sun_rays);
        const double rim = 0.98 * std::sqrt(1.0 - cos_half_sun * cos_half_sun);
        for (const std::size_t h : sky.suns()) {
            const AnnualHour& hour = sky.hours()[h];
            Sun sun{Frame::around(horizon.to_world(sky_direction_deg(hour.sun_altitude_deg, hour.sun_azimuth_deg))),
                    hour.direct_normal_lx};
            for (int i = 0; i < 4; ++i) {
                const double phi = 0.5 * kPi * i;
                sun.rim[static_cast<std::size_t>(i)] = glm::normalize(
                    sun.frame.to_world(Vec3(rim * std::cos(phi), rim * std::sin(phi), 1.0)));
            }
            suns.push_back(sun);
        }
        // Every entry's strata, once for all cells (their trigonometry would otherwise be
        // most of the pass's arithmetic).
        for (const Entry& e : entries) {
            first_stratum.push_back(strata.size());
            for (int a = 0; a < e.side; ++a)
                for (int b = 0; b < e.side; ++b) {
                    Stratum s;
                    s.region = e.region.stratum(a, b, e.side);
                    s.integral = s.region.direction_integral();
                    const auto [axis, cos_half] = s.region.bounding_cone();
                    s.cone_axis = horizon.to_world(axis);
                    s.cone_cos_half = cos_half;
                    strata.push_back(s);
                }
        }
    }
    std::vector<Stratum> strata;             // every entry's, entry by entry, row-major (a, b)
    std::vector<std::size_t> first_stratum;  // per entry
    // An even side whose square is about kSkyRaysPerCell / patches, at least 2.
    static int sky_side(std::size_t patches) {
        const int side = 2 * static_cast<int>(std::lround(std::sqrt(kSkyRaysPerCell / patches) / 2.0));
        return std::max(2, side);
    }
};

// Which side of a cell's plane every entry and stratum lies on (facing: +1 in front, -1
// behind, 0 across), for one normal; the cells of a grid share a few normals.
struct Facings {
    Vec3 normal{0.0};  // world
    std::vector<std::int8_t> entry, stratum;
};

// +1: the whole region lies in front of the plane of normal n_sky (sky frame), -1: behind
// it, 0: across it.
int facing(const Region& r, const Vec3& n_sky) {
    const auto [lo, hi] = r.cos_range(n_sky);
    if (lo >= 0.0) return 1;
    if (hi <= 0.0) return -1;
    return 0;
}

Facings facings_of(const Targets& t, const Vec3& normal) {
    Facings f;
    f.normal = normal;
    const Vec3 n_sky = t.horizon.to_local(normal);
    for (const Entry& e : t.entries) f.entry.push_back(static_cast<std::int8_t>(facing(e.region, n_sky)));
    f.stratum.resize(t.strata.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, t.strata.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i)
                              f.stratum[i] = static_cast<std::int8_t>(facing(t.strata[i].region, n_sky));
                      });
    return f;
}

// A stratified estimate sum_k w_k Z_k, Z_k what the scene lets through along stratum k's
// sample (0 to 1), and its variance by collapsed strata: strata (2j, 2j + 1) of a row form
// a pair, each pair adding ((w_a + w_b) / 2)^2 (Z_a - Z_b)^2. That is conservative (it
// takes the two strata's difference for noise) and exactly 0 where both saw the same, as
// in the open sky or behind a wall.
struct StrataSum {
    double value = 0.0, variance = 0.0;
    double pending_w = 0.0, pending_z = 0.0;
    bool open = false;
    void add(double w, double z) {
        value += w * z;
        if (open) {
            const double m = 0.5 * (w + pending_w), d = z - pending_z;
            variance += m * m * d * d;
        } else {
            pending_w = w;
            pending_z = z;
        }
        open = !open;
    }
};

class CellTracer {
public:
    CellTracer(const Scene& scene, const EmbreeScene& embree, std::size_t det, const DirectDaylightOptions& o,
               const Targets& targets, const PortalOpenings& openings)
        : geometry_{scene.detectors[det]},
          shadow_(scene, embree, 4.0 * scene.ray_epsilon_m(), openings.empty() ? nullptr : &openings.triangles()),
          openings_(openings), sampler_(o.seed ^ kDirectKey), targets_(targets), det_(det),
          eps_(scene.ray_epsilon_m()) {}

    // `facings` for the cell's normal (facings_of), or computed here.
    void cell(std::size_t c, const std::vector<Facings>& facings, DirectCoefficients& out) {
        const Vec3 n = geometry_.normal(c);
        const Vec3 n_sky = targets_.horizon.to_local(n);
        const std::vector<Vec3> corners = geometry_.corners(c);
        const Facings* f = nullptr;
        for (const Facings& k : facings)
            if (k.normal == n) f = &k;
        if (f == nullptr) {
            own_facings_ = facings_of(targets_, n);
            f = &own_facings_;
        }
        std::uint32_t block = 0;
        for (std::size_t e = 0; e < targets_.entries.size(); ++e) {
            const Entry& entry = targets_.entries[e];
            const std::uint32_t first = block;
            block += static_cast<std::uint32_t>(entry.side * entry.side);
            if (!(entry.luminance_cd_m2 > 0.0) || f->entry[e] < 0) continue;
            if (!reaches_opening(entry.region, corners)) continue;  // dark, as its rays would say
            const StrataSum sum = patch(c, first, e, n, n_sky, corners, *f);
            out.sky_lx[out.at(e, c)] = entry.luminance_cd_m2 * sum.value;
            out.sky_var[out.at(e, c)] = entry.luminance_cd_m2 * entry.luminance_cd_m2 * sum.variance;
        }
        const int sun_rays = targets_.sun_side * targets_.sun_side;
        for (std::size_t s = 0; s < targets_.suns.size(); ++s, block += static_cast<std::uint32_t>(sun_rays)) {
            const Sun& sun = targets_.suns[s];
            if (!(sun.normal_lx > 0.0) || glm::dot(sun.frame.n, n) <= -0.01) continue;
            // No ray of the cell's can reach an opening: dark, as its rays would say.
            if (!openings_.empty() && !openings_.may_pass(corners, sun.frame.n, targets_.cos_half_sun)) continue;
            const StrataSum sum = disc(c, block, sun, n, corners);
            out.sun_lx[out.at(s, c)] = sun.normal_lx * sum.value;
            out.sun_var[out.at(s, c)] = sun.normal_lx * sun.normal_lx * sum.variance;
        }
    }

private:
    // Whether some ray from the cell towards the region may reach a portal's opening
    // (always, without portals): where none can, the region is dark (portal_openings.hpp).
    bool reaches_opening(const Region& r, const std::vector<Vec3>& corners) const {
        if (openings_.empty()) return true;
        const auto [axis, cos_half] = r.bounding_cone();
        return openings_.may_pass(corners, targets_.horizon.to_world(axis), cos_half);
    }

    // Cell c's Philox key: its detector above any cell index.
    std::uint64_t key(std::size_t c) const { return (static_cast<std::uint64_t>(det_) << 40) | c; }

    // What passes along d from the cell (its point, or a point of its area from w[2], w[3]).
    // The ray starts at the point itself, and surfaces closer than a ray epsilon along it are
    // passed by: a sensor lying on a floor does not shade itself, and one in the air is not
    // moved (moving it up by the epsilon would enlarge what it sees through an opening).
    double through(std::size_t c, const PhiloxSampler::Block& w, const Vec3& d) {
        return through_from(geometry_.position(c, PhiloxSampler::uniform(w[2]), PhiloxSampler::uniform(w[3])), d);
    }
    double through_from(const Vec3& p, const Vec3& d) {
        double share[16];
        return shadow_.passes(p, d, std::numeric_limits<double>::infinity(), share, eps_) ? share[0] : 0.0;
    }

    // A sky entry: per stratum, its exact integral of cos dw (where it lies wholly in front)
    // times what passes along its sample. Where a stratum lies across the cell's plane, its
    // sample's own cos+ times the stratum's solid angle.
    StrataSum patch(std::size_t c, std::uint32_t first, std::size_t e, const Vec3& n, const Vec3& n_sky,
                    const std::vector<Vec3>& corners, const Facings& facings) {
        StrataSum sum;
        const int side = targets_.entries[e].side;
        const std::size_t first_stratum = targets_.first_stratum[e];
        const std::uint64_t k = key(c);
        for (int a = 0; a < side; ++a)
            for (int b = 0; b < side; ++b) {
                const std::size_t i = first_stratum + static_cast<std::size_t>(a * side + b);
                const int f = facings.stratum[i];
                if (f < 0) {
                    sum.add(0.0, 0.0);
                    continue;
                }
                const Stratum& s = targets_.strata[i];
                const auto w = sampler_.block(k, first + static_cast<std::uint32_t>(a * side + b));
                const Vec3 d = targets_.horizon.to_world(
                    s.region.direction(PhiloxSampler::uniform(w[0]), PhiloxSampler::uniform(w[1])));
                const double cos_n = glm::dot(d, n);
                const double weight = f > 0 ? glm::dot(n_sky, s.integral)
                                            : s.region.solid_angle_sr() * std::max(0.0, cos_n);
                const bool reaches = openings_.empty() || openings_.may_pass(corners, s.cone_axis, s.cone_cos_half);
                sum.add(weight, weight > 0.0 && reaches ? through(c, w, d) : 0.0);
            }
        return sum;
    }

    // A sun: its disc's exact mean cosine, sin(alt) (1 + cos a) / 2 for the horizontal, where
    // the whole disc lies in front (else each ray's own), times what passes. The disc's 0.53
    // degrees change the cosine by under 0.5 % tan(theta) across it: taking its mean for
    // the penumbra's rays errs far less than they do. A points sensor first looks along
    // five fixed rays, to the disc's centre and four points of its rim: where all five are
    // blocked or all pass, so does the whole disc (but for an edge that cuts the disc
    // between them), and the value is exact (their mean transmittance); where they differ,
    // the disc is cut, and its rays tell how much (penumbra). An illuminance grid's cell
    // samples its area and the disc together. `corners`: the cell's (CellGeometry::corners).
    StrataSum disc(std::size_t c, std::uint32_t first, const Sun& sun, const Vec3& n,
                   const std::vector<Vec3>& corners) {
        const double sin_half = std::sqrt(1.0 - targets_.cos_half_sun * targets_.cos_half_sun);
        const double cos_axis = glm::dot(sun.frame.n, n);
        const bool in_front = cos_axis > sin_half;
        const double mean_cos = cos_axis * (1.0 + targets_.cos_half_sun) / 2.0;
        bool cut = false;  // the disc is cut: the fixed rays disagreed (points), or the corners' (cells)
        if (geometry_.point() && in_front) {
            const PhiloxSampler::Block none{};
            double z[5];
            z[0] = through(c, none, sun.frame.n);
            for (std::size_t i = 0; i < 4; ++i) z[i + 1] = through(c, none, sun.rim[i]);
            // The same: all blocked, or all through (glazing's T differs a little between them).
            const bool seen = z[0] > 0.0;
            if (std::all_of(z + 1, z + 5, [&](double x) { return (x > 0.0) == seen; })) {
                StrataSum exact;
                exact.value = mean_cos * (z[0] + z[1] + z[2] + z[3] + z[4]) / 5.0;
                return exact;
            }
            cut = true;
        }
        // side x side strata: of the cone for a point; of the cell's area for a cell, where
        // a shadow's edge (its penumbra a few cm wide) is what cuts the light, each ray then
        // towards a point of the whole disc.
        StrataSum sum;
        const int side = targets_.sun_side;
        const double rays = side * side;
        terms_.clear();
        const std::uint64_t k = key(c);
        const bool point = geometry_.point();
        for (int a = 0; a < side; ++a)
            for (int b = 0; b < side; ++b) {
                const auto w = sampler_.block(k, first + static_cast<std::uint32_t>(a * side + b));
                const double s0 = PhiloxSampler::uniform(w[0]), s1 = PhiloxSampler::uniform(w[1]);
                const double s2 = PhiloxSampler::uniform(w[2]), s3 = PhiloxSampler::uniform(w[3]);
                const Vec3 d = sun.frame.to_world(sample_uniform_cone(targets_.cos_half_sun,
                                                                      point ? (a + s0) / side : s0,
                                                                      point ? (b + s1) / side : s1));
                const double weight = in_front ? mean_cos : std::max(0.0, glm::dot(d, n));
                const Vec3 p = geometry_.position(c, point ? s2 : (a + s2) / side, point ? s3 : (b + s3) / side);
                terms_.push_back(weight > 0.0 ? weight * through_from(p, d) : 0.0);
            }
        if (std::all_of(terms_.begin(), terms_.end(), [&](double t) { return t == terms_.front(); })) {
            sum.value = terms_.front();  // all alike: no rounding to call noise
        } else {
            for (const double t : terms_) sum.value += t;
            sum.value /= rays;
            if (std::all_of(terms_.begin(), terms_.end(), [](double t) { return t > 0.0; })) {
                // All passed, each ray's glass a little different (its T(theta)): the plain
                // variance of the mean of what the rays' directions drew.
                for (const double t : terms_) sum.variance += (t - sum.value) * (t - sum.value);
                sum.variance /= rays * (rays - 1.0);
            } else {
                sum.variance = crossed_strata_variance(side, point) / (rays * rays);
            }
        }
        // Rays that all passed (or were all blocked) say nothing of the part of a cut disc
        // they missed, however their glass's T differs between them: a points sensor's disc
        // is known to be cut when its fixed rays disagreed; an area cell's, when rays from
        // its corners towards the disc's rim disagree with its own rays. The variance of
        // a Bernoulli mean with Jeffreys' p = 1 / (2 (n + 1)) is then the least it has
        // (docs/VALIDATION.md §9.2: without it a penumbra's all-passing rays read as exact).
        const bool passed = terms_.front() > 0.0;
        if (std::all_of(terms_.begin(), terms_.end(), [&](double t) { return (t > 0.0) == passed; })) {
            if (!geometry_.point() && in_front) cut = corners_disagree(corners, sun, passed);
            if (cut) {
                const double p = 0.5 / (rays + 1.0);
                sum.variance = std::max(sum.variance, mean_cos * mean_cos * p * (1.0 - p) / rays);
            }
        }
        return sum;
    }

    // The variance of the strata's sum where a shadow's edge crosses them: a stratum the
    // edge crosses, a share q of it lit, adds w^2 q (1 - q), 0 for the others. A stratum
    // whose ray differs from a neighbour's lies by the edge ("flagged"); over straight edges
    // across 4 x 4 strata the true sum averages 0.098 w^2 per flagged stratum
    // (bench/direct_sun_strata.py), so each adds its largest squared difference from a
    // neighbour times that. A disc's strata are neighbours along the radius and around it
    // (`wrap`); a cell's, along its two sides. (The plain sample variance, which counts every
    // stratum's difference from the mean, read the hours' scatter 1.5 times too large:
    // docs/VALIDATION.md §9.2.)
    static constexpr double kFlaggedStratumVariance = 0.098;
    double crossed_strata_variance(int side, bool wrap) const {
        double sum = 0.0;
        auto term = [&](int a, int b) { return terms_[static_cast<std::size_t>(a * side + b)]; };
        for (int a = 0; a < side; ++a)
            for (int b = 0; b < side; ++b) {
                const double t = term(a, b);
                double worst = 0.0;
                auto compare = [&](int a2, int b2) {
                    if (wrap) b2 = (b2 + side) % side;
                    if (a2 >= 0 && a2 < side && b2 >= 0 && b2 < side)
                        worst = std::max(worst, (t - term(a2, b2)) * (t - term(a2, b2)));
                };
                compare(a - 1, b), compare(a + 1, b), compare(a, b - 1), compare(a, b + 1);
                sum += worst * kFlaggedStratumVariance;
            }
        return sum;
    }

    // Whether a ray from some corner of an area cell towards a point of the sun's rim
    // passes where `passed` says the cell's rays did not (or the other way round): the
    // rim, not the centre, so that a corner inside a shadow's penumbra says so.
    bool corners_disagree(const std::vector<Vec3>& corners, const Sun& sun, bool passed) {
        double share[16];
        for (const Vec3& p : corners)
            for (const Vec3& d : sun.rim)
                if (shadow_.passes(p, d, std::numeric_limits<double>::infinity(), share, eps_) != passed) return true;
        return false;
    }

    CellGeometry geometry_;
    std::vector<double> terms_;  // disc's scratch
    Facings own_facings_;        // a cell's normal that the shared facings lack
    ShadowRay shadow_;
    const PortalOpenings& openings_;
    PhiloxSampler sampler_;
    const Targets& targets_;
    std::size_t det_;
    double eps_;
};

}  // namespace

void direct_daylight(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                     const DirectDaylightOptions& options, std::size_t first, std::size_t last,
                     DirectCoefficients& out) {
    if (!scene.annual) throw std::logic_error("direct_daylight: not an annual scene");
    if ((options.sky_rays != 0 && !AnnualOptions::valid_direct_rays(options.sky_rays)) ||
        !AnnualOptions::valid_direct_rays(options.sun_rays))
        throw std::logic_error("direct_daylight: rays per target must be the square of an even number");
    if (scene.band_count() != 1) throw std::logic_error("direct_daylight: annual scenes have one band");
    const Targets targets(scene, options);
    const PortalOpenings openings(scene);
    if (out.entries != targets.entries.size() || out.suns != targets.suns.size() || !out.holds(first, last))
        throw std::logic_error("direct_daylight: coefficients sized for another detector or sky");
    // The facings of the grid's normals, up to a few (a points grid may have as many as
    // sensors: the others are the tracer's own business).
    const CellGeometry geometry{scene.detectors[det]};
    std::vector<Facings> facings;
    for (std::size_t c = first; c < last && facings.size() <= kSharedNormals; ++c) {
        const Vec3 n = geometry.normal(c);
        if (std::none_of(facings.begin(), facings.end(), [&](const Facings& f) { return f.normal == n; }))
            facings.push_back(facings_of(targets, n));
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        CellTracer tracer(scene, embree, det, options, targets, openings);
        for (std::size_t c = r.begin(); c < r.end(); ++c) tracer.cell(c, facings, out);
    });
}

}  // namespace luxtrace
