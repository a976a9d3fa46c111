// The result's mesh and surface map (/mesh, /global).
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

void write_mesh(hid_t file, const Scene& scene) {
    const std::size_t T = scene.triangle_count();
    const Id mesh = create_group(file, "mesh", "group /mesh");
    std::vector<double> v;
    for (const Vec3& p : scene.vertices) v.insert(v.end(), {p.x, p.y, p.z});
    dataset(mesh, "vertices", {scene.vertices.size(), 3}, v.data());
    std::vector<std::uint32_t> t;
    for (const glm::uvec3& tri : scene.triangles) t.insert(t.end(), {tri.x, tri.y, tri.z});
    dataset(mesh, "triangles", {T, 3}, t.data());
    dataset(mesh, "area", {T}, scene.triangle_area_m2.data());
    dataset(mesh, "material", {T}, scene.triangle_material.data());
    std::vector<std::string> names;
    for (const Material& m : scene.materials) names.push_back(m.name);
    attr_strings(mesh, "material_names", names, false);
    // Also as a dataset, so the index in /mesh/material names a dataset row.
    string_dataset(mesh, "material_names", names);
}

void write_surface_map(hid_t file, const Scene& scene, const TallyLayout& L, const std::vector<std::uint64_t>& data,
                       const ResultEstimates& est) {
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    // Every surface dataset has a side axis, [T, 2, B] (side 0 the front).
    const Id glob = create_group(file, "global", "group /global");
    constexpr std::size_t kS = TallyLayout::kSides;
    const std::vector<hsize_t> dims{T, kS, B};
    // The plain run's counts: every light group's together.
    auto slot_of = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        std::uint64_t n = 0;
        for (std::size_t g = 0; g < L.map_groups(); ++g) n += data[L.surface(t, side, b, s, g)];
        return n;
    };
    const std::pair<const char*, TallyLayout::SurfaceSlot> slots[] = {{"count_odd", TallyLayout::kCountOdd},
                                                                      {"count_even", TallyLayout::kCountEven},
                                                                      {"direct_odd", TallyLayout::kDirectOdd},
                                                                      {"direct_even", TallyLayout::kDirectEven}};
    std::vector<std::uint64_t> buf(T * kS * B);
    for (const auto& [name, slot] : slots) {
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b) buf[(t * kS + side) * B + b] = slot_of(t, side, b, slot);
        dataset(glob, name, dims, buf.data());
    }
    // Sum over photons of (arrivals on the side)^2 = arrivals + repeats (tally.hpp).
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b)
                buf[(t * kS + side) * B + b] = slot_of(t, side, b, TallyLayout::kCountOdd) +
                                               slot_of(t, side, b, TallyLayout::kCountEven) +
                                               slot_of(t, side, b, TallyLayout::kRepeats);
    dataset(glob, "sumsq", dims, buf.data());
    const SurfaceMaps& m = est.surface;
    dataset(glob, "illuminance", dims, m.illuminance_lx.data());
    dataset(glob, "illuminance_direct", dims, m.illuminance_direct_lx.data());
    // Per side, band-summed: float maps the XDMF companion can show as they are.
    dataset(glob, "odd_even_difference_lx", {T, kS}, m.odd_even_difference_lx.data());
    dataset(glob, "sigma_lx", {T, kS}, m.sigma_lx.data());
    if (L.replicates() > 0) {
        // sobol: each side's arrivals per replicate (all groups), and the side's error
        // from their spread.
        const std::size_t R = L.replicates();
        std::vector<std::uint64_t> rep(T * kS * B * R, 0);
        for (std::size_t t = 0; t < T; ++t)
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b)
                    for (std::size_t g = 0; g < L.map_groups(); ++g)
                        for (std::size_t r = 0; r < R; ++r)
                            rep[((t * kS + side) * B + b) * R + r] +=
                                data[L.map_replicate(L.side_index(t, side), L.map_column(b, g), r)];
        dataset(glob, "replicate_count", {T, kS, B, R}, rep.data());
        dataset(glob, "replicate_sigma_lx", {T, kS}, m.replicate_sigma_lx.data());
    }
    const GlobalEstimate& g = est.global;
    attr(glob, "sigma_lx", g.sigma_lx);
    attr(glob, "sigma_rel_arithmetic", g.sigma_rel_arithmetic);
    attr(glob, "sigma_rel_quadratic", g.sigma_rel_quadratic);
    attr(glob, "odd_even_rms_lx", g.odd_even_rms_lx);
    attr(glob, "moment_sigma_lx", g.moment_sigma_lx);
    attr(glob, "moment_sigma_rel_arithmetic", g.moment_sigma_rel_arithmetic);
    attr(glob, "moment_sigma_rel_quadratic", g.moment_sigma_rel_quadratic);
    if (L.replicates() > 0) {
        attr(glob, "replicate_sigma_lx", g.replicate_sigma_lx);
        attr(glob, "replicate_sigma_rel_arithmetic", g.replicate_sigma_rel_arithmetic);
        attr(glob, "replicate_sigma_rel_quadratic", g.replicate_sigma_rel_quadratic);
    }
    attr(glob, "error_estimator", g.estimator_name());
    attr(glob, "lit_area_m2", g.lit_area_m2);
    attr(glob, "lit_sides", g.lit_sides);
    attr(glob, "mean_arithmetic_lx", g.mean_arithmetic_lx);
    attr(glob, "mean_quadratic_lx", g.mean_quadratic_lx);
    attr(glob, "photons_escaped", data[L.counter(TallyLayout::kEscaped)]);
    attr(glob, "photons_absorbed", data[L.counter(TallyLayout::kAbsorbed)]);
    attr(glob, "photons_truncated", data[L.counter(TallyLayout::kTruncated)]);
}

}  // namespace luxtrace::result_parts
