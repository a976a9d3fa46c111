#include "luxtrace/annual/annual_sky.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/parallel.hpp"
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/light/site.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>

namespace luxtrace {

double AnnualHour::global_horizontal_lx() const {
    return diffuse_horizontal_lx + direct_normal_lx * std::sin(sun_altitude_deg * kPi / 180.0);
}

bool AnnualOptions::valid_direct_rays(std::int64_t rays) {
    const auto side = static_cast<std::int64_t>(
        std::llround(std::sqrt(static_cast<double>(std::max<std::int64_t>(rays, 0)))));
    return rays >= 4 && rays <= 4096 && side * side == rays && side % 2 == 0;
}

double hour_middle(const weather::WeatherHour& h, weather::WeatherFormat format) {
    return format == weather::WeatherFormat::epw ? h.hour - 0.5 : h.hour;
}

namespace {

std::string hour_name(const std::string& path, std::size_t index, const AnnualHour& h) {
    char when[64];
    std::snprintf(when, sizeof when, "%02d-%02d %05.2f h", h.month, h.day, h.hour_mid);
    return path + ": hour " + std::to_string(index + 1) + " (" + when + ")";
}

LocalStandardTime at(int year, int month, int day, double hour_mid, double utc_offset_h) {
    LocalStandardTime t;
    t.year = year;
    t.month = month;
    t.day = day;
    const double seconds = hour_mid * 3600.0;
    t.hour = static_cast<int>(seconds / 3600.0);
    t.minute = static_cast<int>((seconds - t.hour * 3600.0) / 60.0);
    t.second = seconds - t.hour * 3600.0 - t.minute * 60.0;
    t.utc_offset_h = utc_offset_h;
    return t;
}

// The weather file's hour as the year of skies keeps it, before its sun and sky.
AnnualHour annual_hour(const weather::WeatherHour& w, weather::WeatherFormat format, const AnnualOptions& options) {
    AnnualHour h;
    h.month = w.month;
    h.day = w.day;
    h.hour_mid = hour_middle(w, format);
    h.diffuse_horizontal_w_m2 = w.diffuse_horizontal_w_m2;
    h.direct_normal_w_m2 = w.direct_normal_w_m2;
    h.dew_point_c = w.dew_point_c;
    h.occupied = h.hour_mid >= options.occupied_from_h && h.hour_mid < options.occupied_to_h;
    return h;
}

// The sun at the middle of hour `index` of the weather file.
SunPosition hour_sun(const std::string& path, std::size_t index, const AnnualHour& h, int year, double utc_offset_h,
                     const SunSite& site) {
    try {
        return sun_position(at(year, h.month, h.day, h.hour_mid, utc_offset_h), site);
    } catch (const std::invalid_argument& e) {
        throw InputError(hour_name(path, index, h) + ": no sun position: " + e.what());
    }
}

// What a sky model needs of an hour with the sun up.
void require_sky_inputs(const std::string& path, std::size_t index, const AnnualHour& h,
                        const weather::WeatherHour& w) {
    auto need = [&](double v, const char* what) {
        if (!std::isfinite(v))
            throw InputError(hour_name(path, index, h) + ": the sun is up and its " + what + " is missing");
    };
    need(w.diffuse_horizontal_w_m2, "diffuse horizontal irradiance");
    need(w.direct_normal_w_m2, "direct normal irradiance");
    need(w.dew_point_c, "dew point");
}

PerezSkyInput perez_input(const weather::WeatherHour& w, const SunPosition& sun, int year) {
    PerezSkyInput in;
    in.sun_zenith_rad = (90.0 - sun.altitude_deg) * kPi / 180.0;
    in.sun_azimuth_rad = sun.azimuth_deg * kPi / 180.0;
    in.diffuse_horizontal_w_m2 = w.diffuse_horizontal_w_m2;
    in.direct_normal_w_m2 = w.direct_normal_w_m2;
    in.dew_point_c = w.dew_point_c;
    in.day_of_year = day_of_year(year, w.month, w.day);
    return in;
}

// The sky patches' luminances of one hour (cd/m2): the model's relative luminance
// averaged over each patch, scaled to the hour's diffuse horizontal illuminance.
// `quadrature`: the patches' nodes (patch_quadrature), the same every hour.
std::vector<double> patch_luminances(const SkyPatches& patches, const SkyPatches::Quadrature& quadrature,
                                     const SkyModel& model, const SunPosition& sun, double diffuse_horizontal_lx) {
    const auto luminance = [&](const Vec3& d) { return model.relative_luminance(d); };
    // The sun's patch is cut at the sun, where the luminance has its kink.
    const Vec3 sun_dir = sky_direction_deg(sun.altitude_deg, sun.azimuth_deg);
    // Solid-angle means (patch_quadrature): each patch emits what the sky sends from it, so the error of a
    // uniform patch is of second order for a sensor of any orientation (a
    // cosine-weighted mean would be exact for horizontal ones only and 1.6 % high
    // on a vertical one under the overcast sky at MF 1).
    std::vector<double> means = patches.means(quadrature, luminance, sun_dir);
    // The relative luminances scaled so that the patches carry the hour's diffuse
    // horizontal illuminance exactly (Perez 1993's normalisation, done over the
    // patches, as gendaymtx does).
    double e_h = 0.0;
    for (std::size_t p = 0; p < means.size(); ++p) e_h += means[p] * patches.projected_solid_angle_sr(p);
    const double scale = e_h > 0.0 ? diffuse_horizontal_lx / e_h : 0.0;
    for (double& m : means) m *= scale;
    return means;
}

// 4 x 4 nodes per Tregenza patch, 2 x 2 per finer one: the luminance varies smoothly over a
// patch except at the sun, and the hour's total is exact (patch_luminances). Solid-angle
// means.
SkyPatches::Quadrature patch_quadrature(const SkyPatches& patches, int sky_mf) {
    return patches.quadrature(sky_mf == 1 ? 4 : 2, false);
}

}  // namespace

struct AnnualSky::RowSky {
    SkyModel model;
    SunPosition sun;
    double diffuse_horizontal_lx = 0.0, ground_lx = 0.0;  // ground: rho E_h,global
};

AnnualSky::AnnualSky(const weather::WeatherFile& weather, const SunSite& site, double utc_offset_h,
                     const AnnualOptions& options, const AnnualSkyShare& share)
    : patches_(options.sky_mf) {
    const bool leap = weather.hours.size() == 8784;
    const int year = options.year > 0 ? options.year : (leap ? 2016 : 2017);
    std::vector<RowSky> rows;
    for (std::size_t i = 0; i < weather.hours.size(); ++i) {
        const weather::WeatherHour& w = weather.hours[i];
        AnnualHour h = annual_hour(w, weather.format, options);
        const SunPosition sun = hour_sun(weather.path, i, h, year, utc_offset_h, site);
        h.sun_altitude_deg = sun.altitude_deg;
        h.sun_azimuth_deg = sun.azimuth_deg;
        if (sun.above_horizon() && !(w.diffuse_horizontal_w_m2 == 0.0 && w.direct_normal_w_m2 == 0.0)) {
            require_sky_inputs(weather.path, i, h, w);
            // No diffuse irradiance, no sky to model (a real file's dawn may say so): dark.
            if (w.diffuse_horizontal_w_m2 > 0.0) add_sky_row(h, i, w, sun, year, options, rows);
        }
        hours_.push_back(h);
    }
    sky_vectors(rows, options, share);
}

void AnnualSky::add_sky_row(AnnualHour& h, std::size_t index, const weather::WeatherHour& w, const SunPosition& sun,
                            int year, const AnnualOptions& options, std::vector<RowSky>& rows) {
    const PerezSkyInput in = perez_input(w, sun, year);
    const PerezSky perez(in, false);  // scaled over the patches (patch_luminances)
    if (perez.clamped()) ++clamped_;
    h.daylit = true;
    h.row = rows_++;
    h.diffuse_horizontal_lx = perez.diffuse_horizontal_illuminance_lx();
    h.direct_normal_lx = perez.direct_normal_illuminance_lx();
    const SkyModel model = options.sky == "cie" ? SkyModel::cie(options.cie_type, in.sun_zenith_rad, in.sun_azimuth_rad)
                                                : perez.model();
    rows.push_back({model, sun, h.diffuse_horizontal_lx, options.ground_reflectance * h.global_horizontal_lx()});
    if (h.direct_normal_lx > 0.0) {
        h.sun = static_cast<int>(suns_.size());
        suns_.push_back(index);
    }
}

void AnnualSky::sky_vectors(const std::vector<RowSky>& rows, const AnnualOptions& options,
                            const AnnualSkyShare& share) {
    const std::size_t entries = sky_entries();
    const std::size_t parts = share.gather ? static_cast<std::size_t>(std::max(1, share.parts)) : 1;
    const std::size_t part = parts > 1 ? static_cast<std::size_t>(share.part) : 0;
    std::vector<std::size_t> offsets;
    for (std::size_t p = 0; p <= parts; ++p) offsets.push_back(rows.size() * p / parts * entries);
    luminance_.assign(rows.size() * entries, 0.0);
    // This part's rows, on every core (each row its own: the same bits on any core count).
    const std::size_t first = offsets[part] / entries, last = offsets[part + 1] / entries;
    const SkyPatches::Quadrature quadrature = patch_quadrature(patches_, options.sky_mf);
    for_each_index(last - first, 16, [&](std::size_t i) {
        const std::size_t r = first + i;
        std::vector<double> means = patch_luminances(patches_, quadrature, rows[r].model, rows[r].sun,
                                                     rows[r].diffuse_horizontal_lx);
        // Radiance's ground glow: a uniform lower hemisphere of luminance rho E_h,global / pi.
        means.push_back(rows[r].ground_lx / kPi);
        std::copy(means.begin(), means.end(), luminance_.begin() + static_cast<std::ptrdiff_t>(r * entries));
    });
    if (parts > 1) share.gather(luminance_, offsets);
    yearly_.assign(entries, 0.0);
    for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t e = 0; e < entries; ++e) yearly_[e] += luminance_[r * entries + e];
    weights_.resize(luminance_.size());
    for (std::size_t i = 0; i < luminance_.size(); ++i) {
        const double year = yearly_[i % entries];
        weights_[i] = year > 0.0 ? luminance_[i] / year : 0.0;
    }
}

double AnnualSky::sum_direct_normal_lx_h() const {
    double s = 0.0;
    for (std::size_t i : suns_) s += hours_[i].direct_normal_lx;
    return s;
}

std::size_t AnnualSetup::sun_rows() const {
    if (shared_sun_row.empty()) return sky ? sky->suns().size() : 0;
    return *std::max_element(shared_sun_row.begin(), shared_sun_row.end()) + 1;
}

std::vector<std::size_t> sun_rows_of_days(const AnnualSky& sky, int days) {
    std::vector<std::size_t> rows;
    if (days <= 1) return rows;
    // Key (block of days, clock hour) -> row, in the order of the suns (by hour).
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> row_of;
    for (const std::size_t h : sky.suns()) {
        const auto key = std::make_pair(h / 24 / static_cast<std::size_t>(days), h % 24);
        const auto [it, added] = row_of.try_emplace(key, row_of.size());
        rows.push_back(it->second);
    }
    return rows;
}

}  // namespace luxtrace
