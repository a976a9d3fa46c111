#include "luxtrace/tracer/shadow_ray.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

namespace {

// A surface a straight path passes (glass of index 1 is an open hole, material.hpp).
bool lets_straight_through(const Material& m) {
    return (m.type == MaterialType::glazing && m.glazing) ||
           (m.type == MaterialType::general && !m.specular_transmittance.empty()) ||
           (m.type == MaterialType::glass && m.ior == 1.0);
}

}  // namespace

ShadowRay::ShadowRay(const Scene& scene, const EmbreeScene& embree, double step_m,
                     const std::vector<std::uint8_t>* openings)
    : scene_(scene), embree_(embree), bands_(scene.band_count()), step_m_(step_m), openings_(openings) {
    for (const Material& m : scene.materials) see_through_ = see_through_ || lets_straight_through(m);
}

bool ShadowRay::passes(const Vec3& o, const Vec3& d, double t_far, double* share, double t_near) const {
    std::fill(share, share + bands_, 1.0);
    const float far = std::isfinite(t_far) ? static_cast<float>(t_far) : std::numeric_limits<float>::infinity();
    float near = static_cast<float>(t_near);
    auto stopped = [&] {
        std::fill(share, share + bands_, 0.0);
        return false;
    };
    // Without glass, an occlusion test says all. With it, the first hit decides as well
    // (nothing: through; an opaque surface: stopped) at the cost of one traversal, where an
    // occlusion test first would take two for every ray that meets something.
    if (!see_through_ && openings_ == nullptr)
        return !embree_.occluded_local(embree_.to_local(o), Vec3f(d), far, near) || stopped();
    // Follow the ray through each pane it meets, times the pane's transmittance there.
    bool crossed = openings_ == nullptr;
    for (int pane = 0; pane < 64; ++pane) {
        const Hit h = embree_.intersect(o, d, near, far);
        if (!h.found) return crossed || stopped();
        const Material& m = scene_.materials[scene_.triangle_material[h.triangle]];
        if (!lets_straight_through(m)) return stopped();
        if (!crossed) crossed = (*openings_)[h.triangle] != 0;
        const double cos_i = std::abs(glm::dot(d, scene_.triangle_normal[h.triangle]));
        for (int b = 0; b < bands_; ++b) {
            const auto band = static_cast<std::size_t>(b);
            if (m.type == MaterialType::glazing) share[b] *= (*m.glazing)[band].at(cos_i).transmittance;
            else if (m.type == MaterialType::glass) share[b] *= m.transmittance.empty() ? 1.0 : m.transmittance[band];
            else share[b] *= m.specular_transmittance[band];
        }
        near = h.t + std::max(1e-6f * h.t, static_cast<float>(step_m_));
    }
    return stopped();
}

}  // namespace luxtrace
