#include "luxtrace/tracer/tracer.hpp"

#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/surface_table.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace luxtrace {

PhotonTracer::PhotonTracer(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces,
                           const TallyLayout& layout, PhotonSampler sampler)
    : scene_(scene), embree_(embree), surfaces_(surfaces), layout_(layout), sampler_(std::move(sampler)) {
    // The tallies keep per-replicate counts for exactly the sampler's streams.
    const std::size_t streams = sampler_.kind() == SamplerKind::sobol ? sampler_.replicates() : 0;
    if (layout_.replicates() != streams)
        throw std::logic_error("tally layout for " + std::to_string(layout_.replicates()) +
                               " replicates, sampler with " + std::to_string(streams));
    for (std::uint32_t i = 0; i < scene.detectors.size(); ++i) {
        const Detector& d = scene.detectors[i];
        if (d.type == DetectorType::luminance) luminance_dets_.push_back(i);
        else if (d.cylinders()) cylinder_dets_.push_back(i);
        else (d.indirect_only ? indirect_dets_ : illuminance_dets_).push_back(i);
    }
    for (Photon& p : flight_) {
        p.regs.reserve(32);
        p.arrivals.reserve(64);
    }
}

void PhotonTracer::check_luminance(Photon& p, const Vec3& point) {
    for (std::uint32_t di : luminance_dets_) {
        const int cell = scene_.detectors[di].leaving(point, p.direction);
        if (cell >= 0) p.regs.push_back({layout_.detector_n(di, cell, p.band), di});
    }
}

void PhotonTracer::check_cylinders(Photon& p, double t_max) {
    const Vec3 o = embree_.to_scene(p.origin);
    for (std::uint32_t di : cylinder_dets_) {
        cylinder_cells_.clear();
        scene_.detectors[di].cylinder_entries(o, p.direction, t_max, cylinder_cells_);
        for (int cell : cylinder_cells_) p.regs.push_back({layout_.detector_n(di, cell, p.band), di});
    }
}

const PhotonSampler::Block& PhotonTracer::start_block(std::uint64_t k) {
    if (start_base_ == UINT64_MAX || k < start_base_ || k - start_base_ >= PhiloxSampler::kBatch) {
        std::uint64_t ks[PhiloxSampler::kBatch];
        const std::uint32_t zero[PhiloxSampler::kBatch] = {};
        for (std::size_t i = 0; i < PhiloxSampler::kBatch; ++i) ks[i] = k + i;
        sampler_.blocks(ks, zero, PhiloxSampler::kBatch, start_blocks_.data());
        start_base_ = k;
    }
    return start_blocks_[k - start_base_];
}

void PhotonTracer::start(Photon& p, std::uint64_t k, const PhotonSampler::Block& b0) {
    p.k = k;
    p.bounce = 0;
    p.regs.clear();
    p.arrivals.clear();
    const LightSet& lights = scene_.lights;
    const std::size_t li = lights.pick_light(PhiloxSampler::uniform(b0[0]));
    p.band = lights.pick_band(li, PhiloxSampler::uniform(b0[1]));
    const Light& light = lights.lights()[li];
    double u_pos1 = 0.5, u_pos2 = 0.5;
    if (light.type == LightType::area || light.type == LightType::directional ||
        light.opening.shape != LuminousOpening::Shape::point) {
        const auto b1 = sampler_.block(k, 1);
        u_pos1 = PhiloxSampler::uniform(b1[0]);
        u_pos2 = PhiloxSampler::uniform(b1[1]);
    }
    const EmittedRay ray = light.emit(u_pos1, u_pos2, PhiloxSampler::uniform(b0[2]), PhiloxSampler::uniform(b0[3]));
    // The ray's origin in Embree's local float frame; detectors and scattering work in
    // scene coordinates.
    p.origin = embree_.to_local(ray.origin);
    p.direction = ray.direction;
    if (ray.emitter_triangle >= 0) {
        const TriangleRecord& t = surfaces_.triangle(static_cast<std::size_t>(ray.emitter_triangle));
        p.origin = spawn_origin(point_on_triangle(t.p0, t.p1, t.p2, static_cast<float>(ray.emitter_u),
                                                  static_cast<float>(ray.emitter_v), t.margin, t.min_height),
                                t.normal, t.margin);
        if (!luminance_dets_.empty()) check_luminance(p, ray.origin);
    }
}

bool PhotonTracer::step(Photon& p, const PhotonSampler::Block& u, TallyBuffer& out) {
    const Hit& hit = p.hit;
    const double t_max = hit.found ? static_cast<double>(hit.t) : std::numeric_limits<double>::infinity();
    // Illuminance detectors the flight crosses.
    auto cross = [&](const std::vector<std::uint32_t>& dets) {
        const Vec3 o = embree_.to_scene(p.origin);
        for (std::uint32_t di : dets) {
            const int cell = scene_.detectors[di].crossing(o, p.direction, t_max);
            if (cell >= 0) p.regs.push_back({layout_.detector_n(di, cell, p.band), di});
        }
    };
    if (!illuminance_dets_.empty()) cross(illuminance_dets_);
    if (!cylinder_dets_.empty()) check_cylinders(p, t_max);
    // Indirect only: the flight from the light (bounce 0) is the direct one.
    if (!indirect_dets_.empty() && p.bounce > 0) cross(indirect_dets_);
    if (!hit.found) {
        finish(p, TallyLayout::kEscaped, out);
        return false;
    }
    // SPEC §3: odd photons feed the odd map; the first arrival is the direct one. Each side
    // of a triangle keeps its own counts: a photon travelling against the normal arrives on
    // the front.
    const TriangleRecord& t = surfaces_.triangle(hit.triangle);
    const Vec3 ng(t.normal);
    const bool front = glm::dot(p.direction, ng) < 0.0;
    const std::size_t side = front ? 0 : 1;
    const bool odd = (p.k & 1u) != 0;
    const std::size_t side_i = layout_.side_index(hit.triangle, side);
    const std::size_t counts = layout_.side_slot(side_i, p.band, TallyLayout::kCountOdd);
    out.add(counts + (odd ? TallyLayout::kCountOdd : TallyLayout::kCountEven), 1);
    if (p.bounce == 0) out.add(counts + (odd ? TallyLayout::kDirectOdd : TallyLayout::kDirectEven), 1);
    p.arrivals.push_back(layout_.side_slot(side_i, p.band, TallyLayout::kRepeats));

    const Scattered s = scatter(surfaces_.model(t.material, p.band), p.direction, ng, PhiloxSampler::uniform(u[0]),
                                PhiloxSampler::uniform(u[1]), PhiloxSampler::uniform(u[2]));
    if (s.event == ScatterEvent::absorbed) {
        finish(p, TallyLayout::kAbsorbed, out);
        return false;
    }
    // Leave the surface on the side the photon goes to, just past the hit point's
    // rounding error.
    const SurfacePoint sp = point_on_triangle(t.p0, t.p1, t.p2, hit.u, hit.v, t.margin, t.min_height);
    const Vec3 n_in = front ? ng : -ng;
    p.origin = spawn_origin(sp, Vec3f(static_cast<double>(s.side) * n_in), t.margin);
    p.direction = s.direction;
    if (!luminance_dets_.empty()) check_luminance(p, embree_.to_scene(sp.p));
    if (++p.bounce >= scene_.run.max_bounces) {
        finish(p, TallyLayout::kTruncated, out);
        return false;
    }
    return true;
}

void PhotonTracer::add_repeats(std::vector<std::size_t>& arrivals, TallyBuffer& out) {
    // Sum over sides of n (n - 1), n this photon's arrivals on the side (kRepeats). Most
    // paths are short: compare pairs; a long one (a mirror trap) is sorted instead.
    const std::size_t m = arrivals.size();
    if (m < 2) return;
    if (m > 32) {
        std::sort(arrivals.begin(), arrivals.end());
        for (std::size_t i = 0; i < m;) {
            std::size_t j = i + 1;
            while (j < m && arrivals[j] == arrivals[i]) ++j;
            if (const std::uint64_t n = j - i; n > 1) out.add(arrivals[i], n * (n - 1));
            i = j;
        }
        return;
    }
    // Each pair (i < j) on one side adds 2: sum over pairs of 2 = n (n - 1).
    for (std::size_t i = 1; i < m; ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (arrivals[j] == arrivals[i]) out.add(arrivals[i], 2);
}

void PhotonTracer::finish(Photon& p, TallyLayout::Counter fate, TallyBuffer& out) {
    out.add(layout_.counter(fate), 1);
    // sobol: the photon's replicate (its stream, photon_sampler.hpp) keeps its own counts.
    const std::size_t R = layout_.replicates();
    const std::size_t replicate = R > 0 ? sampler_.stream_of(p.k) : 0;
    if (R > 0) out.add(layout_.replicate_photons(replicate), 1);
    if (p.arrivals.size() > 1) add_repeats(p.arrivals, out);  // a photon arriving once repeats nothing
    p.arrivals.clear();
    if (p.regs.empty()) return;
    // E_i of eq. (6): how many times this photon registered in each cell.
    std::vector<Registration>& regs = p.regs;
    std::sort(regs.begin(), regs.end(), [](const Registration& a, const Registration& b) { return a.index < b.index; });
    std::uint32_t last_detector = UINT32_MAX;
    std::uint64_t in_detector = 0;  // this photon's registrations in last_detector
    auto close_detector = [&] {
        if (last_detector == UINT32_MAX) return;
        out.add(layout_.detector_received(last_detector), 1);
        out.add(layout_.detector_total_n(last_detector), in_detector);
        out.add(layout_.detector_total_q(last_detector), in_detector * in_detector);
        if (R > 0) out.add(layout_.detector_replicate_total_n(last_detector, replicate), in_detector);
    };
    for (std::size_t i = 0; i < regs.size();) {
        std::size_t j = i;
        while (j < regs.size() && regs[j].index == regs[i].index) ++j;
        const std::uint64_t e = j - i;
        out.add(regs[i].index, e);          // n_c
        out.add(regs[i].index + 1, e * e);  // q_c
        if (R > 0) out.add(layout_.detector_replicate_of(regs[i].detector, regs[i].index, replicate), e);
        // Detectors occupy disjoint ascending index ranges, so sorted order groups them.
        if (regs[i].detector != last_detector) {
            close_detector();
            last_detector = regs[i].detector;
            in_detector = 0;
        }
        in_detector += e;
        i = j;
    }
    close_detector();
    regs.clear();
}

void PhotonTracer::trace(std::uint64_t first, std::uint64_t last, TallyBuffer& out) {
    std::uint64_t next = first;
    int active = 0;
    while (active < kInFlight && next < last) {
        start(flight_[active++], next, start_block(next));
        ++next;
    }
    std::uint64_t ks[kInFlight];
    std::uint32_t bs[kInFlight];
    int slot[kInFlight];
    // An escaped photon's arrival block is never computed; zero, not indeterminate, when
    // the end of the range moves it with its photon.
    PhotonSampler::Block arrival[kInFlight] = {}, packed[kInFlight];
    while (active > 0) {
        for (int i = 0; i < active; ++i) {
            Photon& p = flight_[i];
            const Vec3f d(p.direction);
            if (record_ != nullptr) record_->push_back({p.origin, d, 0.0f});
            p.hit = embree_.intersect_local(p.origin, d);
            if (p.hit.found) __builtin_prefetch(&surfaces_.triangle(p.hit.triangle));
        }
        // The arrival blocks of the photons that arrived somewhere, together (an escaped
        // photon reads none: a block is a pure function of (k, b), so which are computed
        // changes no number).
        int arrived = 0;
        for (int i = 0; i < active; ++i)
            if (flight_[i].hit.found) {
                ks[arrived] = flight_[i].k;
                bs[arrived] = 2 + static_cast<std::uint32_t>(flight_[i].bounce);
                slot[arrived++] = i;
            }
        sampler_.blocks(ks, bs, static_cast<std::size_t>(arrived), packed);
        for (int a = 0; a < arrived; ++a) arrival[slot[a]] = packed[a];
        for (int i = 0; i < active;) {
            if (step(flight_[i], arrival[i], out)) {
                ++i;
            } else if (next < last) {
                start(flight_[i++], next, start_block(next));
                ++next;
            } else {
                // Keep the photons in flight at the front; the one moved into slot i has
                // not taken its step yet, so its arrival block moves with it.
                --active;
                std::swap(flight_[i], flight_[active]);
                arrival[i] = arrival[active];
            }
        }
    }
}

}  // namespace luxtrace
