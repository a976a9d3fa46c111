#include "luxtrace/tracer/sensor_gather.hpp"

#include "luxtrace/annual/annual_sky.hpp"
#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/cell_geometry.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/gather_patches.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace luxtrace {

namespace {

// Keeps the gather's random numbers apart from the photons' and the direct pass's.
constexpr std::uint64_t kGatherKey = 0x6A7E4E5C0FFEE0DDull;
// Panes a ray's branches may meet (reflected or passed) before what is behind counts no more.
constexpr int kMaxPanes = 4;

class CellGatherer {
public:
    CellGatherer(const Scene& scene, const EmbreeScene& embree, std::size_t det, const SensorGatherOptions& o)
        : scene_(scene), embree_(embree), geometry_{scene.detectors[det]}, sampler_(o.seed ^ kGatherKey),
          side_(static_cast<int>(std::lround(std::sqrt(static_cast<double>(o.rays))))), det_(det),
          step_m_(4.0 * scene.ray_epsilon_m()), patches_(o.patches),
          sites_per_side_(o.patches != nullptr ? o.patches->count() : scene.triangle_count()),
          luminance_(o.site_luminance) {}

    // Cell c's (site, weight) pairs, merged by site; with a luminance per site, the relative
    // variance of its gathered light by collapsed strata into `rel_var`.
    std::vector<std::pair<std::uint32_t, double>> cell(std::size_t c, double& rel_var) {
        hits_.clear();
        double sum = 0.0, pairs = 0.0, previous = 0.0;
        const Frame frame = Frame::around(geometry_.normal(c));
        const double weight = kPi / (side_ * side_);
        const std::uint64_t key = (static_cast<std::uint64_t>(det_) << 40) | c;
        for (int a = 0; a < side_; ++a)
            for (int b = 0; b < side_; ++b) {
                const auto w = sampler_.block(key, static_cast<std::uint32_t>(a * side_ + b));
                // Uniform over the unit disc in (r^2, phi), lifted onto the hemisphere.
                const double r2 = (a + PhiloxSampler::uniform(w[0])) / side_;
                const double phi = 2.0 * kPi * (b + PhiloxSampler::uniform(w[1])) / side_;
                const double r = std::sqrt(r2);
                const Vec3 d = frame.to_world(Vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - r2)));
                const Vec3 p = geometry_.position(c, PhiloxSampler::uniform(w[2]), PhiloxSampler::uniform(w[3]));
                const std::size_t before = hits_.size();
                follow(p, d, 0.0, weight, 0);
                if (luminance_ == nullptr) continue;
                // The stratum's light, and strata (a, 2j) and (a, 2j + 1) collapsed into a
                // pair: sum over pairs of (f1 - f2)^2 estimates the variance of the sum
                // (conservative where the pair's means differ).
                double f = 0.0;
                for (std::size_t i = before; i < hits_.size(); ++i)
                    f += hits_[i].second * (*luminance_)[hits_[i].first];
                sum += f;
                if (b % 2 == 1) pairs += (f - previous) * (f - previous);
                previous = f;
            }
        rel_var = sum > 0.0 ? pairs / (sum * sum) : 0.0;
        std::sort(hits_.begin(), hits_.end());
        std::vector<std::pair<std::uint32_t, double>> merged;
        for (const auto& [s, x] : hits_) {
            if (!merged.empty() && merged.back().first == s) merged.back().second += x;
            else merged.emplace_back(s, x);
        }
        return merged;
    }

private:
    // The ray o + t d, t >= t_near, carrying `weight`: the first surface it meets takes it,
    // but a pane of glazing passes it on, reflected and straight through, each times the
    // pane's share at the ray's incidence (an open hole, straight on whole).
    void follow(const Vec3& o, const Vec3& d, double t_near, double weight, int panes) {
        const Hit h = embree_.intersect(o, d, static_cast<float>(t_near));
        if (!h.found || !(weight > 0.0)) return;  // the sky: the direct light's
        const Material& m = scene_.materials[scene_.triangle_material[h.triangle]];
        const Vec3& n = scene_.triangle_normal[h.triangle];
        const double along = glm::dot(d, n);
        const bool glazing = m.type == MaterialType::glazing && m.glazing;
        const bool hole = m.type == MaterialType::glass && m.ior == 1.0;
        if (!glazing && !hole) {
            const std::size_t side = along < 0.0 ? 0 : 1;  // the side the ray arrives on
            const std::size_t patch = patches_ != nullptr ? patches_->patch(h.triangle, h.u, h.v) : h.triangle;
            hits_.emplace_back(static_cast<std::uint32_t>(side * sites_per_side_ + patch), weight);
            return;
        }
        if (panes >= kMaxPanes) return;
        const double t_on = h.t + std::max(1e-6 * h.t, step_m_);
        if (hole) {
            follow(o, d, t_on, weight, panes + 1);
            return;
        }
        const PaneOptics optics = (*m.glazing)[0].at(std::abs(along));
        follow(o, d, t_on, weight * optics.transmittance, panes + 1);
        const Vec3 hit = o + static_cast<double>(h.t) * d;
        follow(hit, d - 2.0 * along * n, step_m_, weight * optics.reflectance, panes + 1);
    }

    const Scene& scene_;
    const EmbreeScene& embree_;
    CellGeometry geometry_;
    PhiloxSampler sampler_;
    int side_;
    std::size_t det_;
    double step_m_;
    const GatherPatches* patches_;
    std::size_t sites_per_side_;
    const std::vector<double>* luminance_;
    std::vector<std::pair<std::uint32_t, double>> hits_;
};

}  // namespace

SensorGather sensor_gather(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                           const SensorGatherOptions& options, std::size_t first, std::size_t last) {
    if (!AnnualOptions::valid_direct_rays(options.rays))
        throw std::logic_error("sensor_gather: rays per cell must be the square of an even number");
    if (det >= scene.detectors.size() || first > last || last > static_cast<std::size_t>(scene.detectors[det].cells()))
        throw std::logic_error("sensor_gather: cells beyond the detector");
    std::vector<std::vector<std::pair<std::uint32_t, double>>> per_cell(last - first);
    std::vector<double> rel_var(last - first, 0.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        CellGatherer g(scene, embree, det, options);
        for (std::size_t c = r.begin(); c < r.end(); ++c) per_cell[c - first] = g.cell(c, rel_var[c - first]);
    });
    SensorGather out;
    out.first = first;
    out.cells = last - first;
    if (options.site_luminance != nullptr) out.rel_var = std::move(rel_var);
    out.offset.push_back(0);
    for (const auto& entries : per_cell) {
        for (const auto& [s, w] : entries) {
            out.site.push_back(s);
            out.weight_sr.push_back(w);
        }
        out.offset.push_back(out.site.size());
    }
    return out;
}

}  // namespace luxtrace
