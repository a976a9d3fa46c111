#include "floor_tracer.hpp"

#include "luxtrace/material/material.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace luxtrace::bench {

FloorTracer::FloorTracer(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces,
                         std::uint64_t seed)
    : embree_(embree), surfaces_(surfaces), sampler_(seed),
      light_(embree.to_local(scene.lights.lights().front().emit(0.5, 0.5, 0.5, 0.5).origin)),
      max_bounces_(scene.run.max_bounces) {
    for (const Material& m : scene.materials) {
        const ScatterModel sm = scatter_model(m, 0);
        reflectance_.push_back(static_cast<float>(sm.diffuse_reflection + sm.specular_reflection));
    }
}

std::uint64_t FloorTracer::trace(std::uint64_t first, std::uint64_t last, std::vector<std::uint32_t>& counts,
                                 std::vector<RecordedRay>* record) {
    struct P {
        std::uint64_t k = 0;
        std::uint32_t bounce = 0;
        Vec3f o, d;
        Hit hit;
    };
    constexpr int kN = PhotonTracer::kInFlight;
    constexpr std::uint64_t kDone = UINT64_MAX;
    P flight[kN];
    std::uint64_t ks[kN]{}, next = first, rays = 0;  // zeroed: GCC cannot see the lambdas fill them first
    std::uint32_t bs[kN]{};
    PhiloxSampler::Block u[kN];
    int fresh[kN], n_fresh = 0, active = 0;
    auto begin = [&](int i) {
        flight[i].k = next++;
        flight[i].bounce = 0;
        fresh[n_fresh++] = i;
    };
    // The photons started since the last draw take their block 0 together.
    auto emit_fresh = [&] {
        for (int j = 0; j < n_fresh; ++j) {
            ks[j] = flight[fresh[j]].k;
            bs[j] = 0;
        }
        sampler_.blocks(ks, bs, static_cast<std::size_t>(n_fresh), u);
        for (int j = 0; j < n_fresh; ++j) {
            P& p = flight[fresh[j]];
            const float z = 1.0f - 2.0f * to_float(u[j][0]), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const float phi = 6.2831853f * to_float(u[j][1]);
            p.o = light_;
            p.d = Vec3f(r * std::cos(phi), r * std::sin(phi), z);
        }
        n_fresh = 0;
    };
    while (active < kN && next < last) begin(active++);
    emit_fresh();
    while (active > 0) {
        for (int i = 0; i < active; ++i) {
            P& p = flight[i];
            if (record != nullptr) record->push_back({p.o, p.d, 0.0f});
            p.hit = embree_.intersect_local(p.o, p.d);
            if (p.hit.found) __builtin_prefetch(&surfaces_.triangle(p.hit.triangle));
            ks[i] = p.k;
            bs[i] = 2 + p.bounce;
        }
        rays += static_cast<std::uint64_t>(active);
        sampler_.blocks(ks, bs, static_cast<std::size_t>(active), u);
        for (int i = 0; i < active; ++i) {
            P& p = flight[i];
            bool alive = p.hit.found;
            if (alive) {
                ++counts[p.hit.triangle];
                const TriangleRecord& t = surfaces_.triangle(p.hit.triangle);
                alive = to_float(u[i][0]) < reflectance_[t.material] &&
                        ++p.bounce < static_cast<std::uint32_t>(max_bounces_);
                if (alive) {
                    // Cosine direction in the frame of Frame::around (math.hpp), in float.
                    const Vec3f n = glm::dot(p.d, t.normal) < 0.0f ? t.normal : -t.normal;
                    const float r2 = to_float(u[i][1]), r = std::sqrt(r2), phi = 6.2831853f * to_float(u[i][2]);
                    const float sign = std::copysign(1.0f, n.z), a = -1.0f / (sign + n.z), b = n.x * n.y * a;
                    const Vec3f tx(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
                    const Vec3f ty(b, sign + n.y * n.y * a, -n.y);
                    // Off the surface by a few margins: not leak-proof like spawn_origin,
                    // and not meant to be; the floor's own rays are what it is timed against.
                    p.o = p.o + p.hit.t * p.d + 4.0f * t.margin * n;
                    p.d = r * std::cos(phi) * tx + r * std::sin(phi) * ty + std::sqrt(std::max(0.0f, 1.0f - r2)) * n;
                }
            }
            if (!alive) {
                if (next < last) begin(i);
                else p.k = kDone;
            }
        }
        emit_fresh();
        for (int i = 0; i < active;) {
            if (flight[i].k == kDone) flight[i] = flight[--active];
            else ++i;
        }
    }
    return rays;
}

Timed run_floor(const Scene& scene, const EmbreeScene& embree, const SurfaceTable& surfaces, std::uint64_t photons,
                int threads, std::uint64_t* arrivals) {
    constexpr std::uint64_t kChunk = 256;
    std::atomic<std::uint64_t> next{0}, rays{0}, counted{0};
    auto worker = [&] {
        FloorTracer floor(scene, embree, surfaces, scene.run.seed);
        std::vector<std::uint32_t> counts(scene.triangle_count(), 0);
        std::uint64_t mine = 0;
        for (std::uint64_t first; (first = next.fetch_add(kChunk)) < photons;)
            mine += floor.trace(first, std::min(photons, first + kChunk), counts, nullptr);
        rays += mine;
        std::uint64_t sum = 0;
        for (std::uint32_t c : counts) sum += c;
        counted += sum;
    };
    Timed t = run_on_threads(threads, worker);
    *arrivals = counted.load();
    t.rays = rays.load();
    return t;
}

}  // namespace luxtrace::bench
