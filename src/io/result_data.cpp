#include "luxtrace/io/result_data.hpp"

#include "luxtrace/core/error.hpp"

#include <algorithm>

namespace luxtrace {

namespace {

constexpr const char* kRoot = "/";

// Root attributes that older files may lack keep the default.
template <class T, class Read>
void optional_attr(const ResultReader& r, const char* name, T& out, Read read) {
    if (r.has_attr(kRoot, name)) out = read(name);
}

}  // namespace

ResultFile::ResultFile(const std::filesystem::path& path) : reader_(path) {
    const ResultReader& r = reader_;
    checkpoint_ = r.attr_str(kRoot, "format") == "luxtrace-checkpoint";
    auto u64 = [&](const char* n) { return r.attr_u64(kRoot, n); };
    auto f64 = [&](const char* n) { return r.attr_f64(kRoot, n); };
    auto str = [&](const char* n) { return r.attr_str(kRoot, n); };
    optional_attr(r, "format_version", format_version_, u64);
    RunInfo& i = info_;
    optional_attr(r, "luxtrace_version", i.luxtrace_version, str);
    optional_attr(r, "scene_file", i.scene_file, str);
    if (r.has_attr(kRoot, "radiance_models")) i.radiance_models = r.attr_strs(kRoot, "radiance_models");
    optional_attr(r, "radiance_sensors", i.radiance_sensors, str);
    optional_attr(r, "radiance_sensor_radius_m", i.radiance_sensor_radius_m, f64);
    optional_attr(r, "radiance_scale", i.radiance_scale, f64);
    optional_attr(r, "seed", i.seed, u64);
    optional_attr(r, "ranks", i.ranks, [&](const char* n) { return static_cast<int>(u64(n)); });
    optional_attr(r, "threads_per_rank", i.threads_per_rank, [&](const char* n) { return static_cast<int>(u64(n)); });
    optional_attr(r, "photons", i.photons, u64);
    optional_attr(r, "flux_per_photon_lm", i.flux_per_photon_lm, f64);
    optional_attr(r, "elapsed_s", i.elapsed_s, f64);
    optional_attr(r, "load_s", i.load_s, f64);
    optional_attr(r, "bvh_build_s", i.bvh_build_s, f64);
    optional_attr(r, "stop_reason", i.stop_reason, str);
    optional_attr(r, "sampler", i.sampler, str);
    optional_attr(r, "photon_layout", i.photon_layout, u64);
    optional_attr(r, "reductions", i.reductions, u64);
    optional_attr(r, "reduction_stall_s", i.reduction_stall_s, f64);
    optional_attr(r, "reduction_wait_s", i.reduction_wait_s, f64);
    optional_attr(r, "reduction_message_words", i.reduction_message_words, u64);
    optional_attr(r, "reduction_message_bytes", i.reduction_message_bytes, u64);
    optional_attr(r, "reduction_work_s", i.reduction_work_s, f64);
    optional_attr(r, "gather_s", i.gather_s, f64);
    optional_attr(r, "tracing_busy", i.tracing_busy, f64);
    if (r.has_attr("/history", "target_labels")) {
        i.target_labels = r.attr_strs("/history", "target_labels");
        i.target_goals = r.f64_attr_array("/history", "target_goals");
    }
    optional_attr(r, "scene_name", scene_name_, str);
    optional_attr(r, "bands", bands_, [&](const char* n) { return r.attr_strs(kRoot, n); });
    optional_attr(r, "replicates", replicates_, u64);
}

MeshShape ResultFile::mesh_shape() const {
    std::vector<std::size_t> vshape, tshape;
    // Only small datasets are read, for their shapes.
    reader_.f64("/mesh/vertices", &vshape);
    reader_.f64("/mesh/area", &tshape);
    if (vshape.size() != 2 || vshape[1] != 3 || tshape.size() != 1)
        throw InputError(path().string() + ": not a complete luxtrace result (mesh or /global maps missing)");
    return {vshape[0], tshape[0]};
}

std::vector<double> ResultFile::vertices() const {
    std::vector<std::size_t> shape;
    std::vector<double> v = reader_.f64("/mesh/vertices", &shape);
    if (shape.size() != 2 || shape[1] != 3) throw InputError(path().string() + ": /mesh/vertices is not [V, 3]");
    return v;
}

std::vector<double> ResultFile::triangle_areas() const {
    std::vector<std::size_t> shape;
    std::vector<double> a = reader_.f64("/mesh/area", &shape);
    if (shape.size() != 1) throw InputError(path().string() + ": /mesh/area is not [T]");
    return a;
}

std::optional<std::vector<std::string>> ResultFile::material_names() const {
    if (!reader_.has("/mesh/material_names")) return std::nullopt;
    return reader_.attr_strs("/mesh", "material_names");
}

bool ResultFile::has_surface_illuminance() const {
    return reader_.has("/global/illuminance") && reader_.has("/global/illuminance_direct");
}

bool ResultFile::has_odd_even_difference() const { return reader_.has("/global/odd_even_difference_lx"); }

// The one place the surface maps' shape is told by the format version.
SurfaceShape ResultFile::surface_shape(const std::string& dataset, const std::vector<std::size_t>& dims) const {
    const bool two_sided = surface_sides() == 2;
    const bool ok = two_sided ? dims.size() == 3 && dims[1] == TallyLayout::kSides : dims.size() == 2;
    if (!ok)
        throw InputError(path().string() + ": " + dataset + " has not the shape of a format-" +
                         std::to_string(format_version_) + " map (" + (two_sided ? "[T, 2, B]" : "[T, B]") + ")");
    return {dims[0], surface_sides(), dims.back()};
}

SurfaceIlluminance ResultFile::surface_illuminance(const std::string& group) const {
    const std::string total = group + "/illuminance", direct = group + "/illuminance_direct";
    for (const std::string& ds : {total, direct})
        if (!reader_.has(ds)) throw InputError(path().string() + ": has no dataset " + ds);
    SurfaceIlluminance s;
    std::vector<std::size_t> dims, direct_dims;
    s.total_lx = reader_.f64(total, &dims);
    s.direct_lx = reader_.f64(direct, &direct_dims);
    s.shape = surface_shape(total, dims);
    if (direct_dims != dims) throw InputError(path().string() + ": " + direct + " differs in shape from " + total);
    return s;
}

SurfaceCounts ResultFile::surface_counts() const { return surface_counts_at("/global"); }

// The counts of the map in `group`: /global, or a light group's own.
SurfaceCounts ResultFile::surface_counts_at(const std::string& group) const {
    SurfaceCounts s;
    std::vector<std::size_t> dims;
    const std::string odd = group + "/count_odd";
    s.count_odd = reader_.u64(odd, &dims);
    s.shape = surface_shape(odd, dims);
    const std::pair<const char*, std::vector<std::uint64_t>*> others[] = {{"/count_even", &s.count_even},
                                                                          {"/direct_odd", &s.direct_odd},
                                                                          {"/direct_even", &s.direct_even}};
    for (const auto& [name, out] : others) {
        std::vector<std::size_t> d;
        *out = reader_.u64(group + name, &d);
        if (d != dims) throw InputError(path().string() + ": " + group + name + " differs in shape from " + odd);
    }
    if (surface_sides() == 2) {  // format 1 has no sumsq
        std::vector<std::size_t> d;
        s.sumsq = reader_.u64(group + "/sumsq", &d);
        if (d != dims) throw InputError(path().string() + ": " + group + "/sumsq differs in shape from " + odd);
    }
    if (reader_.has(group + "/replicate_count")) {  // sobol
        std::vector<std::size_t> d;
        s.replicate_count = reader_.u64(group + "/replicate_count", &d);
        if (d.size() != 4 || d[0] != dims[0] || d[1] != dims[1] || d[2] != dims[2] || d[3] != replicates_)
            throw InputError(path().string() + ": " + group +
                             "/replicate_count is not [T, 2, B, R] with R = " + std::to_string(replicates_));
    }
    return s;
}

std::vector<LightGroupData> ResultFile::light_groups() const {
    std::vector<LightGroupData> groups;
    if (!reader_.has("/light_groups")) return groups;
    for (const std::string& name : reader_.children("/light_groups")) {
        const std::string g = "/light_groups/" + name;
        LightGroupData lg;
        lg.name = name;
        lg.index = reader_.attr_u64(g, "index");
        lg.flux_lm = reader_.attr_f64(g, "flux_lm");
        if (reader_.has(g + "/count_odd")) lg.surface = surface_counts_at(g);
        for (const std::string& det : detector_names()) {
            const std::string gd = g + "/detectors/" + det;
            if (!reader_.has(gd)) throw InputError(path().string() + ": " + g + " has no detector " + det);
            LightGroupDetector d;
            std::vector<std::size_t> dims, qdims;
            d.count = reader_.u64(gd + "/count", &dims);
            d.sumsq = reader_.u64(gd + "/sumsq", &qdims);
            if (dims.size() != 3 || qdims != dims)
                throw InputError(path().string() + ": " + gd + "/count and sumsq are not both [ny, nx, B]");
            d.photons_received = reader_.attr_u64(gd, "photons_received");
            d.total_count = reader_.attr_u64(gd, "total_count");
            d.total_sumsq = reader_.attr_u64(gd, "total_sumsq");
            if (reader_.has(gd + "/replicate_count")) {
                d.replicate_count = reader_.u64(gd + "/replicate_count");
                d.replicate_total = reader_.f64_attr_array(gd, "replicate_total");
            }
            lg.detectors.emplace_back(det, std::move(d));
        }
        groups.push_back(std::move(lg));
    }
    std::sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
    for (std::size_t i = 0; i < groups.size(); ++i)
        if (groups[i].index != i)
            throw InputError(path().string() + ": /light_groups: the groups' indices are not 0 to " +
                             std::to_string(groups.size() - 1));
    return groups;
}

std::vector<std::uint64_t> ResultFile::replicate_photons() const {
    std::vector<std::uint64_t> n;
    if (!reader_.has_attr(kRoot, "replicate_photons")) return n;
    for (double x : reader_.f64_attr_array(kRoot, "replicate_photons")) n.push_back(static_cast<std::uint64_t>(x));
    return n;
}

std::vector<std::string> ResultFile::detector_names() const { return reader_.children("/detectors"); }

DetectorData ResultFile::detector(const std::string& name) const {
    const std::string g = "/detectors/" + name;
    if (!reader_.has(g)) throw InputError(path().string() + ": has no detector " + name);
    DetectorData d;
    d.name = name;
    std::vector<std::size_t> dims;
    d.count = reader_.u64(g + "/count", &dims);
    if (dims.size() != 3) throw InputError(path().string() + ": " + g + "/count is not [ny, nx, B]");
    d.ny = dims[0];
    d.nx = dims[1];
    d.bands = dims[2];
    auto same_shape = [&](const std::string& dataset, const std::vector<std::size_t>& shape) {
        if (shape != dims)
            throw InputError(path().string() + ": " + dataset + " differs in shape from " + g + "/count");
    };
    std::vector<std::size_t> shape;
    d.sumsq = reader_.u64(g + "/sumsq", &shape);
    same_shape(g + "/sumsq", shape);
    d.value = reader_.f64(g + "/value", &shape);
    same_shape(g + "/value", shape);
    d.sigma_rel = reader_.f64(g + "/sigma_rel", &shape);
    same_shape(g + "/sigma_rel", shape);
    d.type = reader_.attr_str(g, "type");
    d.units = reader_.attr_str(g, "units");
    d.mean_value = reader_.attr_f64(g, "mean_value");
    d.mean_sigma_rel = reader_.attr_f64(g, "mean_sigma_rel");
    d.photons_received = reader_.attr_u64(g, "photons_received");
    if (reader_.has(g + "/daylight_factor")) {
        const std::vector<std::size_t> map_dims{d.ny, d.nx};
        for (auto [dataset, out] : {std::pair{"/daylight_factor", &d.daylight_factor_pct},
                                    std::pair{"/daylight_factor_sigma", &d.daylight_factor_sigma_pct}}) {
            *out = reader_.f64(g + dataset, &shape);
            if (shape != map_dims) throw InputError(path().string() + ": " + g + dataset + " is not [ny, nx]");
        }
        d.daylight_reference_lx = reader_.attr_f64(g, "daylight_reference_lx");
    }
    return d;
}

std::uint64_t ResultFile::checkpoint_budget() const {
    if (!checkpoint_) throw InputError(path().string() + ": not a checkpoint");
    return reader_.attr_u64("/checkpoint", "budget");
}

}  // namespace luxtrace
