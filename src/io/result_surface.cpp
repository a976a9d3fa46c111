// The result's mesh and surface map (/mesh, /global).
#include "luxtrace/core/parallel.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {
constexpr std::size_t kTriangleGrain = 4096;  // triangles per task
}  // namespace

void write_mesh(hid_t file, const Scene& scene) {
    const std::size_t T = scene.triangle_count();
    const Id mesh = create_group(file, "mesh", "group /mesh");
    // Vec3 and glm::uvec3 hold their three numbers and nothing else.
    static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(glm::uvec3) == 3 * sizeof(std::uint32_t));
    dataset(mesh, "vertices", {scene.vertices.size(), 3}, reinterpret_cast<const double*>(scene.vertices.data()));
    dataset(mesh, "triangles", {T, 3}, reinterpret_cast<const std::uint32_t*>(scene.triangles.data()));
    dataset(mesh, "area", {T}, scene.triangle_area_m2.data());
    dataset(mesh, "material", {T}, scene.triangle_material.data());
    std::vector<std::string> names;
    for (const Material& m : scene.materials) names.push_back(m.name);
    attr_strings(mesh, "material_names", names, false);
    // Also as a dataset, so the index in /mesh/material names a dataset row.
    string_dataset(mesh, "material_names", names);
}

void write_surface_counts(hid_t g, const Scene& scene, const TallyLayout& L, std::span<const std::uint64_t> data,
                          std::size_t first_group, std::size_t last_group) {
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    // Every surface dataset has a side axis, [T, 2, B] (side 0 the front).
    constexpr std::size_t kS = TallyLayout::kSides;
    const std::vector<hsize_t> dims{T, kS, B};
    auto slot_of = [&](std::size_t t, std::size_t side, std::size_t b, TallyLayout::SurfaceSlot s) {
        std::uint64_t n = 0;
        for (std::size_t lg = first_group; lg < last_group; ++lg) n += data[L.surface(t, side, b, s, lg)];
        return n;
    };
    const std::pair<const char*, TallyLayout::SurfaceSlot> slots[] = {{"count_odd", TallyLayout::kCountOdd},
                                                                      {"count_even", TallyLayout::kCountEven},
                                                                      {"direct_odd", TallyLayout::kDirectOdd},
                                                                      {"direct_even", TallyLayout::kDirectEven}};
    std::vector<std::uint64_t> buf(T * kS * B);
    for (const auto& [name, slot] : slots) {
        for_each_index(T, kTriangleGrain, [&](std::size_t t) {
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b) buf[(t * kS + side) * B + b] = slot_of(t, side, b, slot);
        });
        dataset(g, name, dims, buf.data());
    }
    // Sum over photons of (arrivals on the side)^2 = arrivals + repeats (tally.hpp).
    for_each_index(T, kTriangleGrain, [&](std::size_t t) {
        for (std::size_t side = 0; side < kS; ++side)
            for (std::size_t b = 0; b < B; ++b)
                buf[(t * kS + side) * B + b] = slot_of(t, side, b, TallyLayout::kCountOdd) +
                                               slot_of(t, side, b, TallyLayout::kCountEven) +
                                               slot_of(t, side, b, TallyLayout::kRepeats);
    });
    dataset(g, "sumsq", dims, buf.data());
    if (const std::size_t R = L.replicates(); R > 0) {
        // sobol: each side's arrivals per replicate.
        std::vector<std::uint64_t> rep(T * kS * B * R, 0);
        for_each_index(T, kTriangleGrain, [&](std::size_t t) {
            for (std::size_t side = 0; side < kS; ++side)
                for (std::size_t b = 0; b < B; ++b)
                    for (std::size_t lg = first_group; lg < last_group; ++lg)
                        for (std::size_t r = 0; r < R; ++r)
                            rep[((t * kS + side) * B + b) * R + r] +=
                                data[L.map_replicate(L.side_index(t, side), L.map_column(b, lg), r)];
        });
        dataset(g, "replicate_count", {T, kS, B, R}, rep.data());
    }
}

void write_surface_estimates(hid_t glob, const Scene& scene, const SurfaceMaps& m, const GlobalEstimate& g) {
    const std::size_t T = scene.triangle_count(), B = scene.bands.size();
    constexpr std::size_t kS = TallyLayout::kSides;
    dataset(glob, "illuminance", {T, kS, B}, m.illuminance_lx.data());
    dataset(glob, "illuminance_direct", {T, kS, B}, m.illuminance_direct_lx.data());
    // Per side, band-summed: float maps the XDMF companion can show as they are.
    dataset(glob, "odd_even_difference_lx", {T, kS}, m.odd_even_difference_lx.data());
    dataset(glob, "sigma_lx", {T, kS}, m.sigma_lx.data());
    const bool replicates = !m.replicate_sigma_lx.empty();  // sobol: the sides' errors from their replicates
    if (replicates) dataset(glob, "replicate_sigma_lx", {T, kS}, m.replicate_sigma_lx.data());
    attr(glob, "sigma_lx", g.sigma_lx);
    attr(glob, "sigma_rel_arithmetic", g.sigma_rel_arithmetic);
    attr(glob, "sigma_rel_quadratic", g.sigma_rel_quadratic);
    attr(glob, "odd_even_rms_lx", g.odd_even_rms_lx);
    attr(glob, "moment_sigma_lx", g.moment_sigma_lx);
    attr(glob, "moment_sigma_rel_arithmetic", g.moment_sigma_rel_arithmetic);
    attr(glob, "moment_sigma_rel_quadratic", g.moment_sigma_rel_quadratic);
    if (replicates) {
        attr(glob, "replicate_sigma_lx", g.replicate_sigma_lx);
        attr(glob, "replicate_sigma_rel_arithmetic", g.replicate_sigma_rel_arithmetic);
        attr(glob, "replicate_sigma_rel_quadratic", g.replicate_sigma_rel_quadratic);
    }
    attr(glob, "error_estimator", g.estimator_name());
    attr(glob, "lit_area_m2", g.lit_area_m2);
    attr(glob, "lit_sides", g.lit_sides);
    attr(glob, "mean_arithmetic_lx", g.mean_arithmetic_lx);
    attr(glob, "mean_quadratic_lx", g.mean_quadratic_lx);
}

void write_surface_map(hid_t file, const Scene& scene, const TallyLayout& L, std::span<const std::uint64_t> data,
                       const ResultEstimates& est) {
    const Id glob = create_group(file, "global", "group /global");
    // The plain run's counts: every light group's together.
    write_surface_counts(glob, scene, L, data, 0, L.map_groups());
    write_surface_estimates(glob, scene, est.surface, est.global);
    attr(glob, "photons_escaped", data[L.counter(TallyLayout::kEscaped)]);
    attr(glob, "photons_absorbed", data[L.counter(TallyLayout::kAbsorbed)]);
    attr(glob, "photons_truncated", data[L.counter(TallyLayout::kTruncated)]);
}

}  // namespace luxtrace::result_parts
