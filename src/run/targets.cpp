#include "luxtrace/run/targets.hpp"

#include "luxtrace/estimate/annual_estimate.hpp"
#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxtrace {

TargetKind kind_of(const Target& t) {
    if (t.photons_received > 0.0) return TargetKind::photons_received;
    if (t.absolute_error > 0.0) return TargetKind::absolute_error;
    return TargetKind::relative_error;
}

namespace {

// The error of a grid's annual metric from kAnnualTargetReplicates replicate years: a
// stop criterion needs its size, not the last digit of it, and rank 0 evaluates it after
// every reduction.
constexpr int kAnnualTargetReplicates = 8;

double annual_metric_error(const Target& t, const Scene& scene, const TallyLayout& layout,
                           std::span<const std::uint64_t> data, double e0, std::uint64_t photons, bool relative,
                           const AnnualDirect& direct) {
    if (photons == 0) return std::numeric_limits<double>::quiet_NaN();
    const auto it = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                 [&](const Detector& d) { return d.name == t.detector; });
    const std::size_t d = static_cast<std::size_t>(it - scene.detectors.begin());
    const AnnualEstimate e =
        estimate_annual_grid(scene, d, layout, data, e0, photons, kAnnualTargetReplicates, false, direct).metrics;
    const auto figure = std::find_if(std::begin(kAnnualTargetFigures), std::end(kAnnualTargetFigures),
                                     [&](const AnnualGridFigure& f) { return t.annual_metric == f.name; });
    // The loader accepts only these names (run_loader.cpp).
    const SimexEstimate m = e.figure(figure != std::end(kAnnualTargetFigures) ? figure->member : &AnnualMetrics::sda);
    // Sigma and the bias together: a bias shrinks with photons as well.
    const double u = m.uncertainty();
    return relative ? u / std::abs(m.value) : u;
}

}  // namespace

GlobalRequests global_requests(const Scene& scene) {
    GlobalRequests r;
    r.weights.emplace_back();
    for (const Target& t : scene.run.targets) {
        r.of_target.push_back(0);
        if (!t.detector.empty() || !t.annual_metric.empty() || t.light_scene.empty()) continue;
        for (const LightScene& ls : scene.light_scenes)
            if (ls.name == t.light_scene) {
                r.of_target.back() = r.weights.size();
                r.weights.push_back(ls.weights);
            }
    }
    return r;
}

TargetStatus evaluate_target(const Target& t, const Scene& scene, const TallyLayout& layout,
                             std::span<const std::uint64_t> data, double e0, std::uint64_t photons,
                             const GlobalEstimate& g, const AnnualDirect& direct) {
    TargetStatus s;
    s.kind = kind_of(t);
    const bool arith = t.averaging == Averaging::arithmetic;
    s.label = t.on;
    // A target on a [[light_scene]] reads the groups' tallies weighted by its dimming.
    std::vector<double> weights;
    if (!t.light_scene.empty()) {
        s.label += "@" + t.light_scene;
        for (const LightScene& ls : scene.light_scenes)
            if (ls.name == t.light_scene) weights = ls.weights;
    }
    const WeightedTallies tallies(layout, data, weights);
    switch (s.kind) {
    case TargetKind::relative_error:
        s.goal = t.relative_error;
        s.label += arith ? " rel(arith)" : " rel(quad)";
        break;
    case TargetKind::absolute_error:
        s.goal = t.absolute_error;
        s.label += " abs";
        break;
    case TargetKind::photons_received:
        s.goal = t.photons_received;
        s.label += " received";
        break;
    }
    if (!t.annual_metric.empty()) {
        s.value = annual_metric_error(t, scene, layout, data, e0, photons, s.kind == TargetKind::relative_error,
                                      direct);
    } else if (t.detector.empty()) {
        s.value = s.kind == TargetKind::absolute_error ? g.target_sigma_lx() : g.target_sigma_rel(arith);
    } else {
        const auto it = std::find_if(scene.detectors.begin(), scene.detectors.end(),
                                     [&](const Detector& d) { return d.name == t.detector; });
        const std::size_t di = static_cast<std::size_t>(it - scene.detectors.begin());
        const DetectorEstimate e = estimate_detector(*it, di, tallies, e0, photons, {t.i0, t.i1, t.j0, t.j1});
        const bool whole = t.i0 == 0 && t.j0 == 0 && t.i1 == it->nx && t.j1 == it->ny;
        switch (s.kind) {
        case TargetKind::relative_error: s.value = arith ? e.sigma_rel_arithmetic : e.sigma_rel_quadratic; break;
        case TargetKind::absolute_error: s.value = e.sigma_abs; break;
        // A cell range counts registrations in its cells; the whole grid counts photons.
        case TargetKind::photons_received:
            s.value = static_cast<double>(whole ? e.photons_received : e.registrations);
            break;
        }
    }
    if (s.kind == TargetKind::photons_received) s.met = s.value >= s.goal;
    else s.met = std::isfinite(s.value) && s.value > 0.0 && s.value <= s.goal;
    return s;
}

}  // namespace luxtrace
