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

class CellGatherer {
public:
    CellGatherer(const Scene& scene, const EmbreeScene& embree, std::size_t det, const SensorGatherOptions& o)
        : scene_(scene), embree_(embree), geometry_{scene.detectors[det]}, sampler_(o.seed ^ kGatherKey),
          side_(static_cast<int>(std::lround(std::sqrt(static_cast<double>(o.rays))))), det_(det),
          step_m_(4.0 * scene.ray_epsilon_m()), patches_(o.patches),
          sites_per_side_(o.patches != nullptr ? o.patches->count() : scene.triangle_count()), form_(o.rays_form) {}

    // Cell c's (site, weight) pairs, merged by site; with `form`, the rays' variance as a
    // quadratic form in the sites' luminances (SensorGather::form), merged by site pair.
    std::vector<std::pair<std::uint32_t, double>> cell(std::size_t c, std::vector<FormTerm>* form) {
        hits_.clear();
        terms_.clear();
        std::size_t pair_first = 0;  // the first hit of the stratum pair's first stratum
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
                if (b % 2 == 0) pair_first = before;
                follow(p, d, 0.0, weight, 0);
                // Strata (a, 2j) and (a, 2j + 1) collapsed into a pair: sum over pairs of
                // (f1 - f2)^2, f a stratum's sum of w L over its hits, estimates the
                // variance of the gathered sum (conservative where the pair's means differ);
                // as a form in L, each pair adds s_h s_k w_h w_k L_h L_k over its hits h, k
                // (s = +1 in the first stratum, -1 in the second).
                if (form != nullptr && b % 2 == 1) add_pair(pair_first, before);
            }
        if (form != nullptr) merge_form(*form);
        std::sort(hits_.begin(), hits_.end());
        std::vector<std::pair<std::uint32_t, double>> merged;
        for (const auto& [s, x] : hits_) {
            if (!merged.empty() && merged.back().first == s) merged.back().second += x;
            else merged.emplace_back(s, x);
        }
        return merged;
    }

private:
    // The form's terms of the stratum pair whose hits are [first, hits_.size()), the second
    // stratum's from `second`.
    void add_pair(std::size_t first, std::size_t second) {
        for (std::size_t h = first; h < hits_.size(); ++h)
            for (std::size_t k = h; k < hits_.size(); ++k) {
                const double sign = (h < second) == (k < second) ? 1.0 : -1.0;
                const double coef = sign * hits_[h].second * hits_[k].second * (h == k ? 1.0 : 2.0);
                const std::uint32_t x = hits_[h].first, y = hits_[k].first;
                terms_.push_back({std::min(x, y), std::max(x, y), coef});
            }
    }
    // The terms merged by site pair (pairs of one site with one weight cancel, and go).
    void merge_form(std::vector<FormTerm>& form) {
        std::sort(terms_.begin(), terms_.end(),
                  [](const FormTerm& l, const FormTerm& r) { return l.a != r.a ? l.a < r.a : l.b < r.b; });
        form.clear();
        for (const FormTerm& t : terms_) {
            if (!form.empty() && form.back().a == t.a && form.back().b == t.b) form.back().coef += t.coef;
            else form.push_back(t);
        }
        std::erase_if(form, [](const FormTerm& t) { return std::abs(t.coef) < 1e-18; });
    }

    // The ray o + t d, t >= t_near, carrying `weight`: the first surface it meets takes it,
    // but a pane of glazing passes it on, reflected and straight through, each times the
    // pane's share at the ray's incidence (an open hole, straight on whole).
    void follow(const Vec3& o, const Vec3& d, double t_near, double weight, int panes) {
        const Hit h = embree_.intersect(o, d, static_cast<float>(t_near));
        if (!h.found || !(weight > 0.0)) return;  // the sky: the direct light's
        const Material& m = scene_.materials[scene_.triangle_material[h.triangle]];
        const Vec3& n = scene_.triangle_normal[h.triangle];
        const double along = glm::dot(d, n);
        if (!gather_pane(m)) {
            const std::size_t side = along < 0.0 ? 0 : 1;  // the side the ray arrives on
            const std::size_t patch = patches_ != nullptr ? patches_->patch(h.triangle, h.u, h.v) : h.triangle;
            hits_.emplace_back(static_cast<std::uint32_t>(side * sites_per_side_ + patch), weight);
            return;
        }
        if (panes >= kGatherPanes) return;
        const double t_on = h.t + std::max(1e-6 * h.t, step_m_);
        if (m.type == MaterialType::glass) {  // a hole
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
    bool form_;
    std::vector<FormTerm> terms_;
    std::vector<std::pair<std::uint32_t, double>> hits_;
};

}  // namespace

bool gather_pane(const Material& m) {
    return (m.type == MaterialType::glazing && m.glazing) || (m.type == MaterialType::glass && m.ior == 1.0);
}

SensorGather sensor_gather(const Scene& scene, const EmbreeScene& embree, std::size_t det,
                           const SensorGatherOptions& options, std::size_t first, std::size_t last) {
    if (!AnnualOptions::valid_direct_rays(options.rays))
        throw std::logic_error("sensor_gather: rays per cell must be the square of an even number");
    if (det >= scene.detectors.size() || first > last || last > static_cast<std::size_t>(scene.detectors[det].cells()))
        throw std::logic_error("sensor_gather: cells beyond the detector");
    std::vector<std::vector<std::pair<std::uint32_t, double>>> per_cell(last - first);
    std::vector<std::vector<FormTerm>> forms(options.rays_form ? last - first : 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        CellGatherer g(scene, embree, det, options);
        for (std::size_t c = r.begin(); c < r.end(); ++c)
            per_cell[c - first] = g.cell(c, options.rays_form ? &forms[c - first] : nullptr);
    });
    SensorGather out;
    out.first = first;
    out.cells = last - first;
    if (options.rays_form) {
        out.form_offset.push_back(0);
        for (const std::vector<FormTerm>& f : forms) {
            out.form.insert(out.form.end(), f.begin(), f.end());
            out.form_offset.push_back(out.form.size());
        }
    }
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
