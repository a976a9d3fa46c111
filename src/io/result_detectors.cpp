// The result's detectors (/detectors/NAME), with their metrics, task areas and cylinders.
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {

// Cylindrical and semicylindrical detectors: the cylinders, and for a cylindrical one
// with a `horizontal` detector the modelling ratio per point and of the grid means.
void write_cylinders(hid_t g, const Detector& d, std::size_t bands, const std::optional<ModellingRatio>& modelling) {
    attr(g, "radius_m", d.radius_m);
    attr(g, "height_m", d.height_m);
    attr(g, "lateral_area_m2", d.lateral_area_m2());
    if (d.type == DetectorType::semicylindrical)
        attr(g, "facing", std::vector<double>{d.facing.x, d.facing.y, d.facing.z});
    if (!modelling) return;
    const ModellingRatio& m = *modelling;
    const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), bands};
    dataset(g, "modelling_ratio", dims, m.ratio.data());
    dataset(g, "modelling_ratio_sigma_rel", dims, m.sigma_rel.data());
    attr(g, "horizontal", d.horizontal);
    attr(g, "modelling_ratio_mean", m.mean);
    attr(g, "modelling_ratio_mean_sigma_rel", m.mean_sigma_rel);
    attr(g, "modelling_ratio_min", m.min);
    attr(g, "modelling_ratio_max", m.max);
}

// Points detectors: each sensor's position and direction, [n, 3], row k = cell k, and the
// disc every sensor counts on.
void write_sensors(hid_t g, const Detector& d) {
    const std::size_t n = d.sensors.size();
    std::vector<double> pos(3 * n), dir(3 * n);
    for (std::size_t k = 0; k < n; ++k)
        for (int c = 0; c < 3; ++c) {
            pos[3 * k + c] = d.sensors.positions()[k][c];
            dir[3 * k + c] = d.sensors.directions()[k][c];
        }
    dataset(g, "positions", {n, 3}, pos.data());
    dataset(g, "directions", {n, 3}, dir.data());
    attr(g, "points_file", d.points_file);
    attr(g, "radius_m", d.radius_m);
    attr(g, "disc_area_m2", d.cell_area_m2());
}

}  // namespace

// Eavg, Emin, Emax, U0 of a grid or task area (illuminance_metrics.hpp), initial and
// maintained.
static void write_metrics(hid_t g, const IlluminanceMetrics& initial, const IlluminanceMetrics& maint) {
    attr(g, "metrics_cells", initial.cells);
    using Named = std::pair<std::string, const IlluminanceMetrics&>;
    for (const auto& [suffix, m] : {Named{"", initial}, Named{"_maintained", maint}}) {
        attr(g, "E_avg" + suffix + "_lx", m.avg_lx);
        attr(g, "E_avg" + suffix + "_sigma_lx", m.avg_sigma_lx);
        attr(g, "E_min" + suffix + "_lx", m.min_lx);
        attr(g, "E_min" + suffix + "_sigma_lx", m.min_sigma_lx);
        attr(g, "E_min" + suffix + "_bias_lx", m.min_bias_lx);
        attr(g, "E_max" + suffix + "_lx", m.max_lx);
        attr(g, "E_max" + suffix + "_sigma_lx", m.max_sigma_lx);
        attr(g, "E_max" + suffix + "_bias_lx", m.max_bias_lx);
    }
    attr(g, "E_min_cell",
         std::vector<std::uint64_t>{static_cast<std::uint64_t>(initial.min_i),
                                    static_cast<std::uint64_t>(initial.min_j)});
    attr(g, "E_max_cell",
         std::vector<std::uint64_t>{static_cast<std::uint64_t>(initial.max_i),
                                    static_cast<std::uint64_t>(initial.max_j)});
    attr(g, "E_min_competitors", initial.min_competitors);
    attr(g, "E_max_competitors", initial.max_competitors);
    attr(g, "U0", initial.u0);
    attr(g, "U0_sigma", initial.u0_sigma);
    attr(g, "U0_bias", initial.u0_bias);
    attr(g, "E_min_over_max", initial.min_over_max);
    attr(g, "E_min_over_max_sigma", initial.min_over_max_sigma);
    attr(g, "E_min_over_max_bias", initial.min_over_max_bias);
    attr(g, "U0_unreliable", std::uint64_t{initial.unreliable ? 1u : 0u});
}

// A daylight_factor detector's DF figures of a grid or task area (daylight_metrics.hpp):
// the quantiles EN 17037 reads, with their errors and biases, and its verdicts when asked.
static void write_daylight_metrics(hid_t g, const DaylightAreaMetrics& m) {
    attr(g, "DF_cells_without_photons", m.cells_without_photons);
    attr(g, "DF_mean_pct", m.mean_df);
    attr(g, "DF_mean_sigma_pct", m.mean_df_sigma);
    using Named = std::pair<std::string, const QuantileEstimate&>;
    for (const auto& [name, q] : {Named{"DF_median", m.median}, Named{"DF_95", m.df_95}}) {
        attr(g, name + "_pct", q.value);
        attr(g, name + "_sigma_pct", q.sigma);
        attr(g, name + "_bias_pct", q.bias);
    }
    if (!m.has_targets) return;
    attr(g, "en17037_target_df_pct", m.targets.target_df);
    attr(g, "en17037_minimum_df_pct", m.targets.minimum_df);
    attr(g, "en17037_target_verdict", verdict_name(m.target_verdict.verdict));
    attr(g, "en17037_target_photons_factor", m.target_verdict.photons_factor);
    attr(g, "en17037_minimum_verdict", verdict_name(m.minimum_verdict.verdict));
    attr(g, "en17037_minimum_photons_factor", m.minimum_verdict.photons_factor);
    attr(g, "en17037_verdict", verdict_name(m.overall));
    attr(g, "en17037_photons_factor", m.overall_photons_factor);
}

void write_daylight_map(hid_t g, const Detector& d, const std::optional<DaylightEstimate>& daylight) {
    if (!daylight) return;
    const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx)};
    dataset(g, "daylight_factor", dims, daylight->df.data());
    dataset(g, "daylight_factor_sigma", dims, daylight->df_sigma.data());
    attr(g, "daylight_reference_lx", daylight->reference_lx);
}

// The whole grid's metrics on the detector's group, each task area's in task_areas/AREA.
void write_task_areas(hid_t g, const Detector& d, const std::vector<IlluminanceMetrics>& initial,
                      const std::vector<IlluminanceMetrics>& maint, const std::optional<DaylightEstimate>& daylight) {
    if (initial.empty()) return;
    write_metrics(g, initial.front(), maint.front());
    if (daylight) write_daylight_metrics(g, daylight->areas.front());
    if (initial.size() == 1) return;
    const Id areas = create_group(g, "task_areas", "group /detectors/" + d.name + "/task_areas");
    for (std::size_t k = 1; k < initial.size(); ++k) {
        const IlluminanceMetrics& m = initial[k];
        const Id a = create_group(areas, m.area, "group task_areas/" + m.area);
        attr(a, "cell_range",
             std::vector<std::uint64_t>{static_cast<std::uint64_t>(m.i0), static_cast<std::uint64_t>(m.i1),
                                        static_cast<std::uint64_t>(m.j0), static_cast<std::uint64_t>(m.j1)});
        write_metrics(a, m, maint[k]);
        if (daylight) write_daylight_metrics(a, daylight->areas[k]);
    }
}

std::vector<std::uint64_t> detector_sums(const TallyLayout& L, std::span<const std::uint64_t> data, std::size_t di,
                                         std::size_t cells, bool sumsq, std::size_t first_group,
                                         std::size_t last_group) {
    const std::size_t B = L.bands();
    std::vector<std::uint64_t> out(cells * B, 0);
    for (std::size_t lg = first_group; lg < last_group; ++lg)
        for (std::size_t c = 0; c < cells; ++c)
            for (std::size_t b = 0; b < B; ++b)
                out[c * B + b] += data[sumsq ? L.detector_q(di, c, b, lg) : L.detector_n(di, c, b, lg)];
    return out;
}

void write_detector_counts(hid_t g, const Detector& d, std::size_t di, std::size_t B, const TallyLayout& L,
                           std::span<const std::uint64_t> data, std::size_t first_group, std::size_t last_group) {
    const std::size_t cells = static_cast<std::size_t>(d.cells());
    const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
    dataset(g, "count", dims, detector_sums(L, data, di, cells, false, first_group, last_group).data());
    dataset(g, "sumsq", dims, detector_sums(L, data, di, cells, true, first_group, last_group).data());
    if (const std::size_t R = L.replicates(); R > 0) {
        // sobol: each replicate's counts and its sum over the grid (docs/QMC.md).
        std::vector<std::uint64_t> rn(R * cells * B, 0), rt(R, 0);
        for (std::size_t r = 0; r < R; ++r)
            for (std::size_t lg = first_group; lg < last_group; ++lg) {
                rt[r] += data[L.detector_replicate_total_n(di, r, lg)];
                for (std::size_t c = 0; c < cells; ++c)
                    for (std::size_t b = 0; b < B; ++b)
                        rn[(r * cells + c) * B + b] += data[L.detector_replicate_n(di, r, c, b, lg)];
            }
        dataset(g, "replicate_count", {R, static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B}, rn.data());
        attr(g, "replicate_total", rt);
    }
}

void write_detector_summary(hid_t g, const DetectorEstimate& e) {
    attr(g, "sigma_rel_arithmetic", e.sigma_rel_arithmetic);
    attr(g, "sigma_rel_quadratic", e.sigma_rel_quadratic);
    attr(g, "mean_arithmetic", e.mean_arithmetic);
    attr(g, "mean_quadratic", e.mean_quadratic);
    attr(g, "photons_received", e.photons_received);
    attr(g, "mean_value", e.mean_value);
    attr(g, "mean_sigma_rel", e.mean_sigma_rel);
}

void write_detectors(hid_t file, const Scene& scene, const TallyLayout& L, std::span<const std::uint64_t> data,
                     const ResultEstimates& est) {
    const Id dets = create_group(file, "detectors", "group /detectors");
    const std::size_t B = scene.bands.size();
    for (std::size_t di = 0; di < scene.detectors.size(); ++di) {
        const Detector& d = scene.detectors[di];
        if (d.observer >= 0) continue;  // an eye detector: /observers/NAME
        const DetectorEstimate& e = est.detectors[di];
        const Id g = create_group(dets, d.name, "group /detectors/" + d.name);
        const std::vector<hsize_t> dims{static_cast<hsize_t>(d.ny), static_cast<hsize_t>(d.nx), B};
        // The plain run's counts: every light group's together.
        write_detector_counts(g, d, di, B, L, data, 0, L.groups());
        dataset(g, "value", dims, e.value.data());
        dataset(g, "sigma_rel", dims, e.sigma_rel.data());
        attr(g, "type", detector_type_name(d.type));
        attr(g, "units", d.units());
        if (d.type == DetectorType::points) {
            write_sensors(g, d);
        } else {
            attr(g, "center", std::vector<double>{d.center.x, d.center.y, d.center.z});
            attr(g, "normal", std::vector<double>{d.normal.x, d.normal.y, d.normal.z});
            attr(g, "up", std::vector<double>{d.v_axis.x, d.v_axis.y, d.v_axis.z});
            attr(g, "size", std::vector<double>{d.size_u, d.size_v});
        }
        attr(g, "cells",
             std::vector<std::uint64_t>{static_cast<std::uint64_t>(d.nx), static_cast<std::uint64_t>(d.ny)});
        write_detector_summary(g, e);
        // What sigma_rel and the summaries are (docs/QMC.md): eq. (8) for independent
        // photons, or the spread of the R replicate means (sobol) with R - 1 dof.
        attr(g, "error_estimator", e.replicate_spread ? "replicate_spread" : "independent_photons_eq8");
        attr(g, "error_dof", static_cast<std::uint64_t>(e.dof));
        write_daylight_map(g, d, est.daylight[di]);
        write_task_areas(g, d, e.metrics, est.maintained_metrics[di], est.daylight[di]);
        if (d.type == DetectorType::luminance) {
            attr(g, "view_direction", std::vector<double>{d.cone_axis.x, d.cone_axis.y, d.cone_axis.z});
            attr(g, "half_angle_deg", d.half_angle_deg);
        }
        if (d.cylinders()) write_cylinders(g, d, B, est.modelling[di]);
    }
}

}  // namespace luxtrace::result_parts
