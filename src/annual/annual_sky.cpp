#include "luxtrace/annual/annual_sky.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/light/perez_sky.hpp"
#include "luxtrace/light/site.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

namespace luxtrace {

double AnnualHour::global_horizontal_lx() const {
    return diffuse_horizontal_lx + direct_normal_lx * std::sin(sun_altitude_deg * kPi / 180.0);
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

}  // namespace

AnnualSky::AnnualSky(const weather::WeatherFile& weather, const SunSite& site, double utc_offset_h,
                     const AnnualOptions& options)
    : patches_(options.sky_mf) {
    const bool leap = weather.hours.size() == 8784;
    const int year = options.year > 0 ? options.year : (leap ? 2016 : 2017);
    const std::size_t entries = sky_entries();
    yearly_.assign(entries, 0.0);
    std::vector<double> means;
    for (std::size_t i = 0; i < weather.hours.size(); ++i) {
        const weather::WeatherHour& w = weather.hours[i];
        AnnualHour h;
        h.month = w.month;
        h.day = w.day;
        h.hour_mid = hour_middle(w, weather.format);
        h.diffuse_horizontal_w_m2 = w.diffuse_horizontal_w_m2;
        h.direct_normal_w_m2 = w.direct_normal_w_m2;
        h.dew_point_c = w.dew_point_c;
        h.occupied = h.hour_mid >= options.occupied_from_h && h.hour_mid < options.occupied_to_h;
        SunPosition sun;
        try {
            sun = sun_position(at(year, w.month, w.day, h.hour_mid, utc_offset_h), site);
        } catch (const std::invalid_argument& e) {
            throw InputError(hour_name(weather.path, i, h) + ": no sun position: " + e.what());
        }
        h.sun_altitude_deg = sun.altitude_deg;
        h.sun_azimuth_deg = sun.azimuth_deg;
        const double diffuse = w.diffuse_horizontal_w_m2, direct = w.direct_normal_w_m2;
        if (sun.above_horizon() && !(diffuse == 0.0 && direct == 0.0)) {
            auto need = [&](double v, const char* what) {
                if (!std::isfinite(v))
                    throw InputError(hour_name(weather.path, i, h) + ": the sun is up and its " + what + " is missing");
            };
            need(diffuse, "diffuse horizontal irradiance");
            need(direct, "direct normal irradiance");
            need(w.dew_point_c, "dew point");
            if (!(diffuse > 0.0)) {  // no sky to model (a real file's dawn may say so): dark
                ++no_diffuse_;
                hours_.push_back(h);
                continue;
            }
            PerezSkyInput in;
            in.sun_zenith_rad = (90.0 - sun.altitude_deg) * kPi / 180.0;
            in.sun_azimuth_rad = sun.azimuth_deg * kPi / 180.0;
            in.diffuse_horizontal_w_m2 = diffuse;
            in.direct_normal_w_m2 = direct;
            in.dew_point_c = w.dew_point_c;
            in.day_of_year = day_of_year(year, w.month, w.day);
            const PerezSky perez(in, false);  // scaled below, over the patches
            if (perez.clamped()) ++clamped_;
            h.daylit = true;
            h.row = rows_++;
            h.diffuse_horizontal_lx = perez.diffuse_horizontal_illuminance_lx();
            h.direct_normal_lx = perez.direct_normal_illuminance_lx();
            const SkyModel model = options.sky == "cie"
                                       ? SkyModel::cie(options.cie_type, in.sun_zenith_rad, in.sun_azimuth_rad)
                                       : perez.model();
            const auto luminance = [&](const Vec3& d) { return model.relative_luminance(d); };
            // 4 x 4 nodes per Tregenza patch, 2 x 2 per finer one: the luminance varies
            // smoothly over a patch except at the sun, and the hour's total is exact below.
            const int nodes = options.sky_mf == 1 ? 4 : 2;
            // The sun's patch is cut at the sun, where the luminance has its kink.
            const Vec3 sun_dir = sky_direction_deg(sun.altitude_deg, sun.azimuth_deg);
            // Solid-angle means: each patch emits what the sky sends from it, so the error of a
            // uniform patch is of second order for a sensor of any orientation (a
            // cosine-weighted mean would be exact for horizontal ones only and 1.6 % high
            // on a vertical one under the overcast sky at MF 1).
            means = patches_.solid_angle_means(luminance, nodes, sun_dir);
            // The relative luminances scaled so that the patches carry the hour's diffuse
            // horizontal illuminance exactly (Perez 1993's normalisation, done over the
            // patches, as gendaymtx does).
            double e_h = 0.0;
            for (std::size_t p = 0; p < means.size(); ++p) e_h += means[p] * patches_.projected_solid_angle_sr(p);
            const double scale = e_h > 0.0 ? h.diffuse_horizontal_lx / e_h : 0.0;
            for (double& m : means) m *= scale;
            // Radiance's ground glow: a uniform lower hemisphere of luminance rho E_h,global / pi.
            means.push_back(options.ground_reflectance * h.global_horizontal_lx() / kPi);
            luminance_.insert(luminance_.end(), means.begin(), means.end());
            for (std::size_t e = 0; e < entries; ++e) yearly_[e] += means[e];
            if (h.direct_normal_lx > 0.0) {
                h.sun = static_cast<int>(suns_.size());
                suns_.push_back(i);
            }
        }
        hours_.push_back(h);
    }
}

double AnnualSky::sum_direct_normal_lx_h() const {
    double s = 0.0;
    for (std::size_t i : suns_) s += hours_[i].direct_normal_lx;
    return s;
}

}  // namespace luxtrace
