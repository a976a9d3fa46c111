// The result's /annual group (scenes with [annual], docs/REFERENCE.md §4, docs/ANNUAL.md):
// the year's hours and skies, and per sensor grid every hour's illuminance and direct sun
// with their errors, the daylight coefficients' counts, and the annual metrics with theirs.
#include "luxtrace/estimate/annual_estimate.hpp"
#include "luxtrace/scene/scene.hpp"
#include "result_parts.hpp"

#include <limits>

namespace luxtrace::result_parts {

using namespace hdf5;

namespace {

// Hours x cells as 32-bit floats: seven digits, far below any run's error. From the
// estimate, or, where it holds none, from where the post-processing put them (a slab of
// hours at a time).
void hourly(hid_t g, const std::string& name, const AnnualSeries& s, const std::vector<double>& values,
            const AnnualSeriesSource& source, std::size_t det, AnnualSeriesKind kind) {
    if (!values.empty() || !source) {
        write_dataset(g, name, {s.hours, s.sensors}, H5T_IEEE_F32LE, H5T_NATIVE_DOUBLE, values.data());
        return;
    }
    write_float_rows(g, name, {s.hours, s.sensors}, [&](hsize_t first, hsize_t count, std::span<float> out) {
        source.read_hours(det, kind, first, first + count, out);
    });
}

void write_hours(hid_t g, const AnnualSetup& annual, const AnnualHours& counted) {
    const std::vector<AnnualHour>& hours = annual.sky->hours();
    const std::size_t n = hours.size();
    std::vector<std::uint32_t> month, day, occupied, daylit, en17037;
    std::vector<double> mid, altitude, azimuth, diffuse, direct, global, diffuse_w, direct_w, dew;
    std::vector<std::uint64_t> sun_group;
    for (std::size_t h = 0; h < n; ++h) {
        const AnnualHour& a = hours[h];
        month.push_back(static_cast<std::uint32_t>(a.month));
        day.push_back(static_cast<std::uint32_t>(a.day));
        mid.push_back(a.hour_mid);
        occupied.push_back(a.occupied ? 1 : 0);
        daylit.push_back(a.daylit ? 1 : 0);
        en17037.push_back(counted.en17037_hours[h]);
        altitude.push_back(a.sun_altitude_deg);
        azimuth.push_back(a.sun_azimuth_deg);
        diffuse.push_back(a.diffuse_horizontal_lx);
        direct.push_back(a.direct_normal_lx);
        global.push_back(a.daylit ? a.global_horizontal_lx() : 0.0);
        diffuse_w.push_back(a.diffuse_horizontal_w_m2);
        direct_w.push_back(a.direct_normal_w_m2);
        dew.push_back(a.dew_point_c);
        sun_group.push_back(a.sun >= 0 ? annual.sun_group(a.sun) : ~std::uint64_t{0});
    }
    dataset(g, "month", {n}, month.data());
    dataset(g, "day", {n}, day.data());
    dataset(g, "hour", {n}, mid.data());
    dataset(g, "occupied", {n}, occupied.data());
    dataset(g, "daylit", {n}, daylit.data());
    dataset(g, "en17037_hour", {n}, en17037.data());
    dataset(g, "sun_altitude_deg", {n}, altitude.data());
    dataset(g, "sun_azimuth_deg", {n}, azimuth.data());
    dataset(g, "diffuse_horizontal_lx", {n}, diffuse.data());
    dataset(g, "direct_normal_lx", {n}, direct.data());
    dataset(g, "global_horizontal_lx", {n}, global.data());
    dataset(g, "sun_group", {n}, sun_group.data());
    dataset(g, "weather_diffuse_horizontal_w_m2", {n}, diffuse_w.data());
    dataset(g, "weather_direct_normal_w_m2", {n}, direct_w.data());
    dataset(g, "weather_dew_point_c", {n}, dew.data());
}

void write_sky(hid_t g, const AnnualSetup& annual) {
    const AnnualSky& sky = *annual.sky;
    const SkyPatches& p = sky.patches();
    std::vector<double> bounds, solid, projected;
    for (std::size_t i = 0; i < p.count(); ++i) {
        const SkyPatches::Patch& b = p.patch(i);
        bounds.insert(bounds.end(), {b.alt_lo_deg, b.alt_hi_deg, b.az_lo_deg, b.az_hi_deg});
        solid.push_back(p.solid_angle_sr(i));
        projected.push_back(p.projected_solid_angle_sr(i));
    }
    dataset(g, "patch_bounds_deg", {p.count(), 4}, bounds.data());
    dataset(g, "patch_solid_angle_sr", {p.count()}, solid.data());
    dataset(g, "patch_projected_solid_angle_sr", {p.count()}, projected.data());
    const std::size_t rows = sky.daylit_hours(), entries = sky.sky_entries();
    write_dataset(g, "sky_vectors_cd_m2", {rows, entries}, H5T_IEEE_F32LE, H5T_NATIVE_DOUBLE, sky.sky_vector(0));
    dataset(g, "yearly_luminance_cd_m2_h", {entries}, sky.yearly_luminance().data());
}

void write_metrics(hid_t g, const AnnualEstimate& e, std::size_t cells) {
    using S = AnnualMetrics::Sensors;
    const std::pair<const char*, std::vector<double> S::*> per_sensor[] = {{"da", &S::da},
                                                                           {"continuous_da", &S::continuous_da},
                                                                           {"udi_fell_short", &S::udi_fell_short},
                                                                           {"udi_useful", &S::udi_useful},
                                                                           {"udi_exceeded", &S::udi_exceeded},
                                                                           {"ase_hours", &S::ase_hours}};
    for (const auto& [name, member] : per_sensor) {
        const std::string n = name;
        dataset(g, n, {cells}, (e.value.sensors.*member).data());
        if (e.replicates == 0) continue;
        dataset(g, n + "_sigma", {cells}, (e.sigma.sensors.*member).data());
        dataset(g, n + "_bias", {cells}, (e.bias.sensors.*member).data());
    }
    const std::pair<const char*, double AnnualMetrics::*> grid[] =
        {{"sda", &AnnualMetrics::sda},
         {"ase", &AnnualMetrics::ase},
         {"mean_da", &AnnualMetrics::mean_da},
         {"mean_continuous_da", &AnnualMetrics::mean_continuous_da},
         {"mean_udi_fell_short", &AnnualMetrics::mean_udi_fell_short},
         {"mean_udi_useful", &AnnualMetrics::mean_udi_useful},
         {"mean_udi_exceeded", &AnnualMetrics::mean_udi_exceeded}};
    for (const auto& [name, member] : grid) {
        const std::string n = name;
        attr(g, n, e.value.*member);
        if (e.replicates == 0) continue;
        attr(g, n + "_sigma", e.sigma.*member);
        attr(g, n + "_bias", e.bias.*member);
    }
    attr(g, "replicates", static_cast<std::uint64_t>(e.replicates));
    for (std::size_t l = 0; l < kEn17037Levels.size(); ++l) {
        const std::string n = std::string("en17037_") + kEn17037Levels[l].name;
        attr(g, n + "_target_hours", e.value.en17037_target_hours[l]);
        attr(g, n + "_minimum_hours", e.value.en17037_minimum_hours[l]);
        if (e.replicates == 0) {  // a checkpoint: the verdict on the values, no probability
            const bool pass = e.value.en17037_target_hours[l] >= kEn17037HoursShare &&
                              e.value.en17037_minimum_hours[l] >= kEn17037HoursShare;
            attr(g, n + "_pass", static_cast<std::uint32_t>(pass ? 1 : 0));
            attr(g, n + "_flip_probability", std::numeric_limits<double>::quiet_NaN());
            continue;
        }
        attr(g, n + "_target_hours_sigma", e.sigma.en17037_target_hours[l]);
        attr(g, n + "_minimum_hours_sigma", e.sigma.en17037_minimum_hours[l]);
        attr(g, n + "_target_hours_bias", e.bias.en17037_target_hours[l]);
        attr(g, n + "_minimum_hours_bias", e.bias.en17037_minimum_hours[l]);
        attr(g, n + "_pass", static_cast<std::uint32_t>(e.en17037[l].pass ? 1 : 0));
        attr(g, n + "_flip_probability", e.en17037[l].flip_probability);
    }
}

void write_coefficients(hid_t g, const AnnualSetup& annual, const TallyLayout& layout,
                        std::span<const std::uint64_t> tallies, std::size_t det, std::size_t cells) {
    // [group][cell]: n_c and q_c of every light group, and the direct registrations.
    const std::size_t groups = layout.groups();
    std::vector<std::uint64_t> n(groups * cells), q(groups * cells), direct(groups * cells, 0);
    for (std::size_t grp = 0; grp < groups; ++grp)
        for (std::size_t c = 0; c < cells; ++c) {
            n[grp * cells + c] = tallies[layout.detector_n(det, c, 0, grp)];
            q[grp * cells + c] = tallies[layout.detector_q(det, c, 0, grp)];
            if (layout.direct_scores()) direct[grp * cells + c] = tallies[layout.detector_direct(det, c, grp)];
        }
    const Id cg = create_group(g, "coefficients", "group coefficients");
    dataset(cg, "count", {groups, cells}, n.data());
    dataset(cg, "sumsq", {groups, cells}, q.data());
    dataset(cg, "direct_count", {groups, cells}, direct.data());
    if (layout.gathered(det)) {
        // The gathered sums Y and sum of Y^2 / 2^24 (tally.hpp), in the gather's units.
        for (std::size_t grp = 0; grp < groups; ++grp)
            for (std::size_t c = 0; c < cells; ++c) {
                n[grp * cells + c] = tallies[layout.detector_gathered(det, c, grp)];
                q[grp * cells + c] = tallies[layout.detector_gathered(det, c, grp) + 1];
            }
        dataset(cg, "gathered", {groups, cells}, n.data());
        dataset(cg, "gathered_sumsq", {groups, cells}, q.data());
    }
    attr(cg, "first_patch_group", static_cast<std::uint64_t>(annual.first_patch_group));
    attr(cg, "ground_group", static_cast<std::uint64_t>(annual.ground_group));
    attr(cg, "first_sun_group", static_cast<std::uint64_t>(annual.first_sun_group));
}

}  // namespace

void write_annual(hid_t file, const Scene& scene, const TallyLayout& layout, std::span<const std::uint64_t> tallies,
                  const ResultEstimates& est) {
    if (!scene.annual) return;
    const AnnualSetup& annual = *scene.annual;
    const Id g = create_group(file, "annual", "group /annual");
    attr(g, "weather", annual.options.weather.string());
    attr(g, "latitude_deg", scene.site.sun_site.latitude_deg);
    attr(g, "longitude_deg", scene.site.sun_site.longitude_deg);
    attr(g, "utc_offset_h", scene.site.utc_offset_h);
    attr(g, "elevation_m", scene.site.sun_site.elevation_m);
    attr(g, "sky", annual.options.sky);
    if (annual.options.sky == "cie") attr(g, "cie_type", static_cast<std::uint64_t>(annual.options.cie_type));
    attr(g, "sky_mf", static_cast<std::uint64_t>(annual.options.sky_mf));
    attr(g, "ground_reflectance", annual.options.ground_reflectance);
    attr(g, "direct", annual.options.direct);
    attr(g, "indirect", annual.options.indirect);
    if (annual.options.gathers()) {
        attr(g, "gather_rays", static_cast<std::uint64_t>(annual.options.gather_rays));
        attr(g, "gather_patch_m", annual.options.gather_patch_m);
    }
    attr(g, "sun_group_days", static_cast<std::uint64_t>(annual.options.sun_group_days));
    attr(g, "occupied_hours", std::vector<double>{annual.options.occupied_from_h, annual.options.occupied_to_h});
    attr(g, "daylit_hours", static_cast<std::uint64_t>(annual.sky->daylit_hours()));
    attr(g, "sun_hours", static_cast<std::uint64_t>(annual.sky->suns().size()));
    attr(g, "clamped_hours", static_cast<std::uint64_t>(annual.sky->clamped_hours()));
    const AnnualHours counted = annual_hours(annual);
    write_hours(g, annual, counted);
    write_sky(g, annual);
    const Id dets = create_group(g, "detectors", "group /annual/detectors");
    for (std::size_t d = 0; d < est.annual.size(); ++d) {
        if (!est.annual[d]) continue;
        const AnnualDetectorEstimate& e = *est.annual[d];
        const Detector& det = scene.detectors[d];
        const Id dg = create_group(dets, det.name, "group /annual/detectors/" + det.name);
        hourly(dg, "illuminance_lx", e.value, e.value.total_lx, est.annual_series, d, AnnualSeriesKind::total);
        hourly(dg, "illuminance_sigma_lx", e.sigma, e.sigma.total_lx, est.annual_series, d,
               AnnualSeriesKind::total_sigma);
        hourly(dg, "direct_sun_lx", e.value, e.value.direct_lx, est.annual_series, d, AnnualSeriesKind::direct);
        hourly(dg, "direct_sun_sigma_lx", e.sigma, e.sigma.direct_lx, est.annual_series, d,
               AnnualSeriesKind::direct_sigma);
        write_metrics(dg, e.metrics, e.value.sensors);
        write_coefficients(dg, annual, layout, tallies, d, e.value.sensors);
        // The year's parts per cell, where the run has them: PREFIX_{sky,sun}[_sigma]_lx_h.
        auto year = [&](const std::string& prefix, const std::vector<double>& sky, const std::vector<double>& sky_sigma,
                        const std::vector<double>& sun, const std::vector<double>& sun_sigma) {
            if (sky.empty()) return;
            dataset(dg, prefix + "_sky_lx_h", {sky.size()}, sky.data());
            dataset(dg, prefix + "_sky_sigma_lx_h", {sky.size()}, sky_sigma.data());
            dataset(dg, prefix + "_sun_lx_h", {sun.size()}, sun.data());
            dataset(dg, prefix + "_sun_sigma_lx_h", {sun.size()}, sun_sigma.data());
        };
        year("shadow_direct", e.direct_sky_lx_h, e.direct_sky_sigma_lx_h, e.direct_sun_lx_h, e.direct_sun_sigma_lx_h);
        year("gathered", e.gather_sky_lx_h, e.gather_sky_sigma_lx_h, e.gather_sun_lx_h, e.gather_sun_sigma_lx_h);
        if (!e.gather_rays_sigma_rel.empty())
            dataset(dg, "gathered_rays_sigma_rel", {e.gather_rays_sigma_rel.size()}, e.gather_rays_sigma_rel.data());
    }
}

}  // namespace luxtrace::result_parts
