#pragma once
// The typed reader of result and checkpoint files, for the C++ code that reads them
// (render, export-xdmf, run --restart, the bench): it knows the file's paths and tells
// the format versions apart here and nowhere else. Format 1 (luxtrace 0.2) has one
// surface map for both sides of a triangle, [T, B]; format 2 one per side, [T, 2, B].
// Attributes the typed accessors do not cover (the summary's metrics and glare figures)
// are read by path through raw(), the ResultReader (result_reader.hpp) underneath. To read a new group of datasets
// (e.g. per light group): a struct here and one method that reads it in result_data.cpp, next to the writer's part in
// result_parts.hpp (as light_groups() reads what result_light_scenes.cpp writes).
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/io/result_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {

// The shape of the surface maps: [triangles][sides][bands], sides 2 (front 0, back 1) in
// format 2 and 1 in format 1, whose one map holds both sides together.
struct SurfaceShape {
    std::size_t triangles = 0, sides = 2, bands = 0;
    // Where (t, side, b) is in a map of this shape: a format-1 map serves both sides.
    std::size_t index(std::size_t t, std::size_t side, std::size_t b) const {
        return (t * sides + (sides == 1 ? 0 : side)) * bands + b;
    }
    std::size_t size() const { return triangles * sides * bands; }
};

// /global's illuminance maps, lx.
struct SurfaceIlluminance {
    SurfaceShape shape;
    std::vector<double> total_lx;   // all arrivals
    std::vector<double> direct_lx;  // first arrivals from a light
};

// /global's counts (SPEC §3: odd and even photons' arrivals, first arrivals).
struct SurfaceCounts {
    SurfaceShape shape;
    std::vector<std::uint64_t> count_odd, count_even, direct_odd, direct_even;
    std::vector<std::uint64_t> sumsq;            // sum over photons of arrivals squared; empty in format 1
    std::vector<std::uint64_t> replicate_count;  // sobol: [T][2][B][R] arrivals per replicate; else empty
};

struct MeshShape {
    std::size_t vertices = 0, triangles = 0;
};

// /detectors/NAME (not an observer's eye detector).
struct DetectorData {
    std::string name, type, units;
    std::size_t nx = 0, ny = 0, bands = 0;
    std::vector<std::uint64_t> count, sumsq;  // [ny][nx][bands]
    std::vector<double> value, sigma_rel;     // [ny][nx][bands]
    double mean_value = 0.0, mean_sigma_rel = 0.0;
    std::uint64_t photons_received = 0;
    // daylight_factor detectors (empty otherwise): DF and its standard error per cell, %,
    // [ny][nx] band-summed, and the E_h,ext they are relative to.
    std::vector<double> daylight_factor_pct, daylight_factor_sigma_pct;
    double daylight_reference_lx = 0.0;
};

// One light group's own counts of a detector (/light_groups/NAME/detectors/DET), from which
// a combination of groups is recombined after the run (issue 22).
struct LightGroupDetector {
    std::vector<std::uint64_t> count, sumsq;  // [ny][nx][bands]
    std::uint64_t photons_received = 0, total_count = 0, total_sumsq = 0;
    std::vector<std::uint64_t> replicate_count;  // sobol: [R][ny][nx][bands]; empty for random
    std::vector<double> replicate_total;         // sobol: [R] the grid's count per replicate
};

// /light_groups/NAME: the group's own surface counts (absent when the run kept one map for
// all groups) and detector counts, by detector name in detector_names() order.
struct LightGroupData {
    std::string name;
    std::size_t index = 0;
    double flux_lm = 0.0;
    std::optional<SurfaceCounts> surface;
    std::vector<std::pair<std::string, LightGroupDetector>> detectors;
};

class ResultFile {
public:
    // Opens and checks `path` (seal, format) and reads its root attributes; throws InputError.
    explicit ResultFile(const std::filesystem::path& path);

    const std::filesystem::path& path() const { return reader_.path(); }
    // The file by HDF5 path, for what has no typed accessor.
    const ResultReader& raw() const { return reader_; }
    bool is_checkpoint() const { return checkpoint_; }
    std::uint64_t format_version() const { return format_version_; }
    // The surface maps' side axis: 2 in format 2, 1 in format 1 (SurfaceShape).
    std::size_t surface_sides() const { return format_version_ >= 2 ? TallyLayout::kSides : 1; }
    // How the run was made, from the root attributes (and /history's target names); an
    // attribute that older files lack is left at its default.
    const RunInfo& run_info() const { return info_; }
    const std::string& scene_name() const { return scene_name_; }
    const std::vector<std::string>& bands() const { return bands_; }  // empty in files without them
    std::uint64_t replicates() const { return replicates_; }          // sobol's R; 0 for random

    // Counted from /mesh's datasets without reading the surface maps.
    MeshShape mesh_shape() const;
    std::vector<double> vertices() const;        // [V][3], m
    std::vector<double> triangle_areas() const;  // [T], m^2
    // /mesh/material_names, or nothing in files without it.
    std::optional<std::vector<std::string>> material_names() const;

    // Whether /global has the illuminance maps, and the band-summed odd/even difference
    // map (files before luxtrace 0.2 lack it).
    bool has_surface_illuminance() const;
    bool has_odd_even_difference() const;
    // The illuminance maps of /global, or of a light scene's map ("/light_scenes/NAME/global").
    SurfaceIlluminance surface_illuminance(const std::string& group = "/global") const;
    SurfaceCounts surface_counts() const;

    std::vector<std::string> detector_names() const;
    DetectorData detector(const std::string& name) const;

    // /light_groups in index order; empty for a run with one light group.
    std::vector<LightGroupData> light_groups() const;
    // Photons per sobol replicate (root attribute replicate_photons); empty for random.
    std::vector<std::uint64_t> replicate_photons() const;

    // A checkpoint's photon budget (throws InputError for a result file).
    std::uint64_t checkpoint_budget() const;

private:
    SurfaceShape surface_shape(const std::string& dataset, const std::vector<std::size_t>& dims) const;
    SurfaceCounts surface_counts_at(const std::string& group) const;

    ResultReader reader_;
    bool checkpoint_ = false;
    std::uint64_t format_version_ = 1;
    RunInfo info_;
    std::string scene_name_;
    std::vector<std::string> bands_;
    std::uint64_t replicates_ = 0;
};

}  // namespace luxtrace
