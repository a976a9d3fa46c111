#include "luxtrace/tracer/tracer.hpp"

#include "luxtrace/sampler/sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/ray_offset.hpp"

#include <algorithm>

namespace luxtrace {

PhotonTracer::PhotonTracer(const Scene& scene, const EmbreeScene& embree, const TallyLayout& layout)
    : scene_(scene), embree_(embree), layout_(layout) {
    for (std::uint32_t i = 0; i < scene.detectors.size(); ++i)
        (scene.detectors[i].type == DetectorType::illuminance ? illuminance_dets_ : luminance_dets_)
            .push_back(i);
    regs_.reserve(64);
}

void PhotonTracer::check_luminance(const Vec3& p, const Vec3& d, int band) {
    for (std::uint32_t di : luminance_dets_) {
        const int cell = scene_.detectors[di].leaving(p, d);
        if (cell >= 0) regs_.push_back({layout_.detector_n(di, cell, band), di});
    }
}

SurfacePoint PhotonTracer::surface_point(unsigned tri, float u, float v) const {
    const glm::uvec3 t = scene_.triangles[tri];
    return point_on_triangle(embree_.local_vertex(t.x), embree_.local_vertex(t.y), embree_.local_vertex(t.z), u, v,
                             embree_.self_hit_margin(tri));
}

void PhotonTracer::trace(std::uint64_t k, Sampler& sampler, TallyBuffer& out) {
    sampler.start_photon(k);
    const LightSet& lights = scene_.lights;
    const std::size_t li = lights.pick_light(sampler.next());
    const int band = lights.pick_band(li, sampler.next());
    const double p1 = sampler.next(), p2 = sampler.next();
    const double d1 = sampler.next(), d2 = sampler.next();
    const Light& light = lights.lights()[li];
    const EmittedRay ray = light.emit(p1, p2, d1, d2);
    // The ray's origin in Embree's local float coordinates; detectors and the photon's
    // scattering work in scene coordinates.
    Vec3f o = embree_.to_local(ray.origin);
    Vec3 d = ray.direction;
    if (ray.emitter_triangle >= 0) {
        const auto tri = static_cast<unsigned>(ray.emitter_triangle);
        o = spawn_origin(surface_point(tri, static_cast<float>(ray.emitter_u), static_cast<float>(ray.emitter_v)),
                         Vec3f(scene_.triangle_normal[tri]), embree_.self_hit_margin(tri));
        check_luminance(ray.origin, d, band);
    }
    // SPEC §3: odd photons feed the odd map.
    const bool odd = (k & 1u) != 0;
    const auto count_slot = odd ? TallyLayout::kCountOdd : TallyLayout::kCountEven;
    const auto direct_slot = odd ? TallyLayout::kDirectOdd : TallyLayout::kDirectEven;
    const int max_bounces = scene_.run.max_bounces;
    TallyLayout::Counter fate = TallyLayout::kTruncated;
    for (int bounce = 0; bounce < max_bounces; ++bounce) {
        if (record_ != nullptr) record_->push_back({o, Vec3f(d), 0.0f});
        const Hit hit = embree_.intersect_local(o, Vec3f(d));
        const double t_max = hit.found ? static_cast<double>(hit.t) : std::numeric_limits<double>::infinity();
        if (!illuminance_dets_.empty()) {
            const Vec3 o_scene = embree_.to_scene(o);
            for (std::uint32_t di : illuminance_dets_) {
                const int cell = scene_.detectors[di].crossing(o_scene, d, t_max);
                if (cell >= 0) regs_.push_back({layout_.detector_n(di, cell, band), di});
            }
        }
        if (!hit.found) { fate = TallyLayout::kEscaped; break; }
        const std::size_t tri = hit.triangle;
        out.add(layout_.surface(tri, band, count_slot), 1);
        if (bounce == 0) out.add(layout_.surface(tri, band, direct_slot), 1);

        sampler.set_dimension(6 + 3 * static_cast<std::uint32_t>(bounce));
        const double ue = sampler.next(), u1 = sampler.next(), u2 = sampler.next();
        const Vec3& ng = scene_.triangle_normal[tri];
        const Scattered s = scatter(scene_.materials[scene_.triangle_material[tri]], band, d, ng, ue, u1, u2);
        if (s.event == ScatterEvent::absorbed) { fate = TallyLayout::kAbsorbed; break; }
        // Leave the surface on the side the photon goes to, just past the hit point's
        // rounding error.
        const SurfacePoint sp = surface_point(hit.triangle, hit.u, hit.v);
        const Vec3 n_in = glm::dot(d, ng) < 0.0 ? ng : -ng;
        o = spawn_origin(sp, Vec3f(static_cast<double>(s.side) * n_in), embree_.self_hit_margin(hit.triangle));
        d = s.direction;
        if (!luminance_dets_.empty()) check_luminance(embree_.to_scene(sp.p), d, band);
    }
    out.add(layout_.counter(fate), 1);
    if (!regs_.empty()) finish_photon(out);
}

void PhotonTracer::finish_photon(TallyBuffer& out) {
    // E_i of eq. (6): how many times this photon registered in each cell.
    std::sort(regs_.begin(), regs_.end(),
              [](const Registration& a, const Registration& b) { return a.index < b.index; });
    std::uint32_t last_detector = UINT32_MAX;
    std::uint64_t in_detector = 0;  // this photon's registrations in last_detector
    auto close_detector = [&] {
        if (last_detector == UINT32_MAX) return;
        out.add(layout_.detector_received(last_detector), 1);
        out.add(layout_.detector_total_n(last_detector), in_detector);
        out.add(layout_.detector_total_q(last_detector), in_detector * in_detector);
    };
    for (std::size_t i = 0; i < regs_.size();) {
        std::size_t j = i;
        while (j < regs_.size() && regs_[j].index == regs_[i].index) ++j;
        const std::uint64_t e = j - i;
        out.add(regs_[i].index, e);      // n_c
        out.add(regs_[i].index + 1, e * e);  // q_c
        // Detectors occupy disjoint ascending index ranges, so sorted order groups them.
        if (regs_[i].detector != last_detector) {
            close_detector();
            last_detector = regs_[i].detector;
            in_detector = 0;
        }
        in_detector += e;
        i = j;
    }
    close_detector();
    regs_.clear();
}

}  // namespace luxtrace
