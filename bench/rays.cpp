#include "rays.hpp"

#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tracer/surface_table.hpp"

#include <algorithm>
#include <random>

namespace luxtrace::bench {

std::vector<RecordedRay> record_tracer_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                            std::uint64_t seed) {
    const TallyLayout layout = tally_layout(scene);
    TallyStore store(layout);
    std::vector<RecordedRay> rays;
    {
        const SurfaceTable surfaces(scene, embree);
        PhotonTracer tracer(scene, embree, surfaces, store.layout(),
                            PhotonSampler(sampler_kind(scene.run.sampler), seed));
        TallyBuffer buffer(store);
        tracer.trace_recording(0, n, buffer, rays);
    }
    return rays;
}

std::vector<RecordedRay> make_cosine_rays(const Scene& scene, const EmbreeScene& embree, std::uint64_t n,
                                          std::uint64_t seed) {
    std::vector<double> cdf(scene.triangle_count());
    double sum = 0.0;
    for (std::size_t t = 0; t < cdf.size(); ++t) cdf[t] = (sum += scene.triangle_area_m2[t]);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<RecordedRay> rays(n);
    for (RecordedRay& r : rays) {
        const auto it = std::upper_bound(cdf.begin(), cdf.end(), uni(rng) * sum);
        const auto t = static_cast<unsigned>(
            std::min<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), cdf.size() - 1));
        const double s = std::sqrt(uni(rng)), u2 = uni(rng);
        const SurfacePoint sp = point_on_triangle(embree.local_vertex(scene.triangles[t].x),
                                                  embree.local_vertex(scene.triangles[t].y),
                                                  embree.local_vertex(scene.triangles[t].z), float(u2 * s),
                                                  float(s - u2 * s), embree.self_hit_margin(t));
        const Vec3& normal = scene.triangle_normal[t];
        const double d1 = uni(rng), d2 = uni(rng);
        r = {spawn_origin(sp, Vec3f(normal), embree.self_hit_margin(t)),
             Vec3f(sample_cosine_hemisphere(normal, d1, d2)), 0.0f};
    }
    return rays;
}

}  // namespace luxtrace::bench
