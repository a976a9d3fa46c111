#include "luxtrace/io/light_group_tallies.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_data.hpp"

#include <algorithm>

namespace luxtrace {

namespace {

Vec3 vec3_attr(const ResultReader& r, const std::string& object, const char* name) {
    const std::vector<double> v = r.f64_attr_array(object, name);
    if (v.size() != 3)
        throw InputError(r.path().string() + ": " + object + " attribute " + name + " is not three numbers");
    return {v[0], v[1], v[2]};
}

// /detectors/NAME as far as the estimates read it: its type and grid, the geometry of its
// value per count (Detector::value_per_lm) and whether it gives daylight factors.
Detector stored_detector(const ResultReader& r, const std::string& name) {
    const std::string g = "/detectors/" + name;
    Detector d;
    d.name = name;
    const std::string type = r.attr_str(g, "type");
    bool known = false;
    for (const DetectorType t : {DetectorType::illuminance, DetectorType::luminance, DetectorType::cylindrical,
                                 DetectorType::semicylindrical, DetectorType::points})
        if (type == detector_type_name(t)) {
            d.type = t;
            known = true;
        }
    const std::vector<double> cells = r.f64_attr_array(g, "cells");
    if (!known || cells.size() != 2)
        throw InputError(r.path().string() + ": " + g + " has no known type and cells [nx, ny]");
    d.nx = static_cast<int>(cells[0]);
    d.ny = static_cast<int>(cells[1]);
    if (d.type != DetectorType::points) {
        const std::vector<double> size = r.f64_attr_array(g, "size");
        if (size.size() != 2) throw InputError(r.path().string() + ": " + g + " attribute size is not two numbers");
        d.size_u = size[0];
        d.size_v = size[1];
        d.center = vec3_attr(r, g, "center");
        d.normal = vec3_attr(r, g, "normal");
        d.up = vec3_attr(r, g, "up");
    }
    if (d.type == DetectorType::points || d.cylinders()) d.radius_m = r.attr_f64(g, "radius_m");
    if (d.cylinders()) d.height_m = r.attr_f64(g, "height_m");
    if (d.type == DetectorType::luminance) {
        d.view_direction = vec3_attr(r, g, "view_direction");
        d.half_angle_deg = r.attr_f64(g, "half_angle_deg");
    }
    d.daylight_factor = r.has(g + "/daylight_factor");
    const Detector stored = d;
    d.finalize();
    // The file's normal and cone axis are the run's, normalised once: normalised again they
    // could move in the last bit, and the value per count with them.
    d.normal = stored.normal;
    if (d.type == DetectorType::luminance) d.cone_axis = stored.view_direction;
    return d;
}

// Group g's surface counts ([T][2][B]) in its own map column; sumsq = count + repeats
// (tally.hpp).
void add_surface(const LightGroupData& group, std::size_t g, std::span<std::uint64_t> data, const TallyLayout& L) {
    const SurfaceCounts& c = *group.surface;
    const SurfaceShape& shape = c.shape;
    const std::size_t R = L.replicates();
    if (shape.sides != TallyLayout::kSides || shape.triangles != L.triangles() || shape.bands != L.bands() ||
        c.sumsq.empty() || c.replicate_count.size() != shape.size() * R)
        throw InputError("/light_groups/" + group.name + ": its maps do not agree with /mesh and the other groups");
    for (std::size_t t = 0; t < shape.triangles; ++t)
        for (std::size_t side = 0; side < shape.sides; ++side)
            for (std::size_t b = 0; b < shape.bands; ++b) {
                const std::size_t i = shape.index(t, side, b), s = L.side_index(t, side);
                data[L.side_slot(s, b, TallyLayout::kCountOdd, g)] = c.count_odd[i];
                data[L.side_slot(s, b, TallyLayout::kCountEven, g)] = c.count_even[i];
                data[L.side_slot(s, b, TallyLayout::kDirectOdd, g)] = c.direct_odd[i];
                data[L.side_slot(s, b, TallyLayout::kDirectEven, g)] = c.direct_even[i];
                data[L.side_slot(s, b, TallyLayout::kRepeats, g)] = c.sumsq[i] - c.count_odd[i] - c.count_even[i];
                for (std::size_t r = 0; r < R; ++r)
                    data[L.map_replicate(s, L.map_column(b, g), r)] = c.replicate_count[i * R + r];
            }
}

// Group g's counts of detector di ([ny][nx][B], sobol's [R][ny][nx][B]) in its column.
void add_detector(const LightGroupData& group, std::size_t g, std::size_t di, std::size_t cells,
                  std::span<std::uint64_t> data, const TallyLayout& L) {
    const auto& [name, d] = group.detectors[di];
    const std::size_t B = L.bands(), R = L.replicates();
    if (d.count.size() != cells * B ||
        (R > 0 && (d.replicate_count.size() != R * cells * B || d.replicate_total.size() != R)))
        throw InputError("/light_groups/" + group.name + "/detectors/" + name +
                         ": its counts do not fit the detector's cells, the bands and the replicates");
    for (std::size_t c = 0; c < cells; ++c)
        for (std::size_t b = 0; b < B; ++b) {
            data[L.detector_n(di, c, b, g)] = d.count[c * B + b];
            data[L.detector_q(di, c, b, g)] = d.sumsq[c * B + b];
            for (std::size_t r = 0; r < R; ++r)
                data[L.detector_replicate_n(di, r, c, b, g)] = d.replicate_count[(r * cells + c) * B + b];
        }
    data[L.detector_received(di, g)] = d.photons_received;
    data[L.detector_total_n(di, g)] = d.total_count;
    data[L.detector_total_q(di, g)] = d.total_sumsq;
    for (std::size_t r = 0; r < R; ++r)
        data[L.detector_replicate_total_n(di, r, g)] = static_cast<std::uint64_t>(d.replicate_total[r]);
}

// /daylight: each daylight source's group and E_h (result_daylight.cpp).
std::vector<DaylightSource> stored_daylight(const ResultReader& r, std::size_t groups) {
    std::vector<DaylightSource> out;
    if (!r.has("/daylight/light_group")) return out;
    const std::vector<std::uint64_t> group = r.u64("/daylight/light_group");
    const std::vector<double> e = r.f64("/daylight/unobstructed_horizontal_lx");
    if (e.size() != group.size() || std::any_of(group.begin(), group.end(), [&](auto g) { return g >= groups; }))
        throw InputError(r.path().string() + ": /daylight: light_group and unobstructed_horizontal_lx do not agree");
    for (std::size_t i = 0; i < group.size(); ++i) out.push_back({group[i], e[i]});
    return out;
}

}  // namespace

LightGroupTallies read_light_group_tallies(const ResultFile& file) {
    LightGroupTallies t;
    const std::vector<LightGroupData> groups = file.light_groups();
    if (groups.empty()) return t;
    for (const LightGroupData& g : groups) {
        t.groups.push_back(g.name);
        t.group_flux_lm.push_back(g.flux_lm);
    }
    t.group_maps = std::all_of(groups.begin(), groups.end(), [](const auto& g) { return g.surface.has_value(); });
    t.e0 = file.run_info().flux_per_photon_lm;
    t.photons = file.run_info().photons;
    if (t.group_maps) t.triangle_area_m2 = file.triangle_areas();
    t.bands = std::max<std::size_t>(1, file.bands().size());
    std::vector<int> cells;
    for (const std::string& name : file.detector_names()) {
        t.detectors.push_back(stored_detector(file.raw(), name));
        cells.push_back(t.detectors.back().cells());
    }
    t.daylight = stored_daylight(file.raw(), groups.size());
    const std::vector<std::uint64_t> rep_photons = file.replicate_photons();
    const TallyDims dims{t.bands, groups.size(), t.group_maps ? groups.size() : 1, rep_photons.size(), false, {}, {},
                         0};
    t.layout = TallyLayout(t.triangle_area_m2.size(), dims, cells);
    t.data.assign(t.layout.size(), 0);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        if (t.group_maps) add_surface(groups[g], g, t.data, t.layout);
        for (std::size_t di = 0; di < cells.size(); ++di)
            add_detector(groups[g], g, di, static_cast<std::size_t>(cells[di]), t.data, t.layout);
    }
    for (std::size_t r = 0; r < rep_photons.size(); ++r) t.data[t.layout.replicate_photons(r)] = rep_photons[r];
    return t;
}

EstimateScene LightGroupTallies::scene() const {
    EstimateScene s;
    s.triangle_area_m2 = triangle_area_m2;
    s.bands = bands;
    s.detectors = detectors;
    s.group_flux_lm = group_flux_lm;
    s.daylight = daylight;
    return s;
}

}  // namespace luxtrace
