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
    : scene_(scene), embree_(embree), surfaces_(surfaces), layout_(layout), sampler_(std::move(sampler)),
      detectors_(scene.detectors), gather_(surfaces.gather()) {
    const auto& lights = scene.lights.lights();
    all_positioned_ = std::all_of(lights.begin(), lights.end(), [](const Light& l) { return l.draws_position(); });
    // The tallies keep per-replicate counts for exactly the sampler's streams.
    const std::size_t streams = sampler_.kind() == SamplerKind::sobol ? sampler_.replicates() : 0;
    if (layout_.replicates() != streams)
        throw std::logic_error("tally layout for " + std::to_string(layout_.replicates()) +
                               " replicates, sampler with " + std::to_string(streams));
    if (layout_.groups() != scene.light_groups.size())
        throw std::logic_error("tally layout for " + std::to_string(layout_.groups()) + " light groups, scene with " +
                               std::to_string(scene.light_groups.size()));
}

const PhotonSampler::Block& PhotonTracer::batched_block(BlockBatch& batch, std::uint64_t k, std::uint32_t b) {
    if (batch.base == UINT64_MAX || k < batch.base || k - batch.base >= PhiloxSampler::kBatch) {
        std::uint64_t ks[PhiloxSampler::kBatch];
        std::uint32_t bs[PhiloxSampler::kBatch];
        for (std::size_t i = 0; i < PhiloxSampler::kBatch; ++i) {
            ks[i] = k + i;
            bs[i] = b;
        }
        sampler_.blocks(ks, bs, PhiloxSampler::kBatch, batch.blocks.data());
        batch.base = k;
    }
    return batch.blocks[k - batch.base];
}

bool PhotonTracer::start(Photon& p, std::uint64_t k, const PhotonSampler::Block& b0, TallyBuffer& out) {
    p.k = k;
    p.bounce = 0;
    p.direct = true;
    p.after_diffuse = false;
    p.panes = 0;
    const LightSet& lights = scene_.lights;
    const std::size_t li = lights.pick_light(PhiloxSampler::uniform(b0[0]));
    p.band = lights.pick_band(li, PhiloxSampler::uniform(b0[1]));
    const Light& light = lights.lights()[li];
    // The photon's bin: its band, its light's group, its replicate (sobol's stream,
    // photon_sampler.hpp) and its parity (SPEC §3).
    const std::size_t replicate = layout_.replicates() > 0 ? sampler_.stream_of(k) : 0;
    p.tally.begin(layout_.bin(static_cast<std::size_t>(p.band), light.group, replicate, (k & 1u) != 0));
    double u_pos1 = 0.5, u_pos2 = 0.5;
    if (light.draws_position()) {
        const auto b1 = all_positioned_ ? batched_block(position_batch_, k, 1) : sampler_.block(k, 1);
        u_pos1 = PhiloxSampler::uniform(b1[0]);
        u_pos2 = PhiloxSampler::uniform(b1[1]);
    }
    const EmittedRay ray = light.emit(u_pos1, u_pos2, PhiloxSampler::uniform(b0[2]), PhiloxSampler::uniform(b0[3]));
    if (ray.missed) {  // a sky patch's photon past its portal (light.hpp)
        end(p, TallyLayout::kEscaped, out);
        return false;
    }
    // The ray's origin in Embree's local float frame; detectors and scattering work in
    // scene coordinates.
    p.origin = embree_.to_local(ray.origin);
    p.direction = ray.direction;
    if (ray.emitter_triangle >= 0) {
        const TriangleRecord& t = surfaces_.triangle(static_cast<std::size_t>(ray.emitter_triangle));
        p.origin = spawn_origin(point_on_triangle(t.p0, t.p1, t.p2, static_cast<float>(ray.emitter_u),
                                                  static_cast<float>(ray.emitter_v), t.margin, t.min_height),
                                ray.emitter_side > 0 ? t.normal : -t.normal, t.margin);
        if (ray.through_portal) return sees_sky(p, out);
        depart(p, ray.origin);
    }
    return true;
}

bool PhotonTracer::sees_sky(Photon& p, TallyBuffer& out) {
    // Back out through the opening towards the sky element the photon came from: anything
    // in the way blocks it (portal.hpp). The obstruction's own reflections are not traced.
    if (!embree_.occluded_local(p.origin, -Vec3f(p.direction))) return true;
    end(p, TallyLayout::kAbsorbed, out);
    return false;
}

bool PhotonTracer::launch(Photon& p, std::uint64_t& next, std::uint64_t last, TallyBuffer& out) {
    while (next < last) {
        const std::uint64_t k = next++;
        if (start(p, k, start_block(k), out)) return true;
    }
    return false;
}

void PhotonTracer::depart(Photon& p, const Vec3& point) {
    if (detectors_.sees_departures()) detectors_.departure(point, p.direction, p.tally.registrations());
}

bool PhotonTracer::step(Photon& p, const PhotonSampler::Block& u, TallyBuffer& out) {
    const Hit& hit = p.hit;
    // The flight just intersected, through the detectors it crosses.
    if (detectors_.sees_flights()) {
        const double t_max = hit.found ? static_cast<double>(hit.t) : std::numeric_limits<double>::infinity();
        const Vec3 hit_normal = hit.found ? Vec3(surfaces_.triangle(hit.triangle).normal) : Vec3(0.0);
        std::vector<Registration>& regs = p.tally.registrations();
        const std::size_t before = regs.size();
        detectors_.flight(embree_.to_scene(p.origin), p.direction, t_max, hit_normal, p.direct, regs);
        if (p.after_diffuse)
            for (std::size_t i = before; i < regs.size(); ++i) regs[i].after_diffuse = true;
    }
    if (!hit.found) {
        end(p, TallyLayout::kEscaped, out);
        return false;
    }
    // The surface map: the side it arrives on (a photon travelling against the normal
    // arrives on the front); arrivals before any event turned it are direct.
    const TriangleRecord& t = surfaces_.triangle(hit.triangle);
    const Vec3 ng(t.normal);
    const bool front = glm::dot(p.direction, ng) < 0.0;
    p.tally.arrive(layout_, layout_.side_index(hit.triangle, front ? 0 : 1), p.direct, out);
    if (!gather_.empty()) gather(p, front, out);

    const Scattered s = scatter(surfaces_.model(t.material, p.band), p.direction, ng, PhiloxSampler::uniform(u[0]),
                                PhiloxSampler::uniform(u[1]), PhiloxSampler::uniform(u[2]));
    if (s.event == ScatterEvent::absorbed) {
        end(p, TallyLayout::kAbsorbed, out);
        return false;
    }
    // Leave the surface on the side the photon goes to, just past the hit point's
    // rounding error.
    const SurfacePoint sp = point_on_triangle(t.p0, t.p1, t.p2, hit.u, hit.v, t.margin, t.min_height);
    const Vec3 n_in = front ? ng : -ng;
    p.origin = spawn_origin(sp, Vec3f(static_cast<double>(s.side) * n_in), t.margin);
    p.direction = s.direction;
    p.direct = p.direct && s.event == ScatterEvent::specular_transmission;
    if (!gather_.empty()) follow_event(p, s.event, surfaces_.pane(t.material));
    if (detectors_.sees_departures()) depart(p, embree_.to_scene(sp.p));
    if (++p.bounce >= scene_.run.max_bounces) {
        end(p, TallyLayout::kTruncated, out);
        return false;
    }
    return true;
}

void PhotonTracer::follow_event(Photon& p, ScatterEvent e, bool pane) {
    if (e == ScatterEvent::diffuse_reflection) {
        p.after_diffuse = true;
        p.panes = 0;
    } else if (pane && p.after_diffuse && ++p.panes <= kGatherPanes) {
        // Through a pane, or reflected by it, as the gather's rays go on.
    } else {
        p.after_diffuse = false;
    }
}

template <class SeeRay>
void PhotonTracer::fly(std::uint64_t first, std::uint64_t last, TallyBuffer& out, SeeRay see_ray) {
    std::uint64_t next = first;
    int active = 0;
    while (active < kInFlight && launch(flight_[active], next, last, out)) ++active;
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
            see_ray(p.origin, d);
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
            } else if (launch(flight_[i], next, last, out)) {
                ++i;
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

void PhotonTracer::trace(std::uint64_t first, std::uint64_t last, TallyBuffer& out) {
    fly(first, last, out, [](const Vec3f&, const Vec3f&) {});
}

void PhotonTracer::trace_recording(std::uint64_t first, std::uint64_t last, TallyBuffer& out,
                                   std::vector<RecordedRay>& rays) {
    fly(first, last, out, [&rays](const Vec3f& origin, const Vec3f& direction) {
        rays.push_back({origin, direction, 0.0f});
    });
}

}  // namespace luxtrace
