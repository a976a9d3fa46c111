#pragma once
// A year of skies for annual daylight (issue 24, docs/ANNUAL.md): from a weather file, each
// hour's sun position (at the middle of the hour), its sky as luminances of the sky
// patches and the ground, and its sun's direct normal illuminance. A run traces every patch
// and every hour's sun as a light group once; an hour's illuminance is then the groups'
// tallies weighted by that hour's values (weights()).
//
// Normalisation: group g emits the luminance Y_g = the year's sum over hours of its hourly
// luminance (a patch, the ground) or direct normal illuminance (the hour's own sun), so a
// plain run is the year's cumulative sky (lx h) and the photons go where the year's light
// comes from. Hour h's weight of group g is L_hg / Y_g.
#include "luxtrace/light/sky_patches.hpp"
#include "luxtrace/light/sun_position.hpp"
#include "luxtrace/weather/weather_file.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace luxtrace {

// [annual] in the scene file (docs/REFERENCE.md §2).
struct AnnualOptions {
    std::filesystem::path weather;  // .epw or .wea
    int sky_mf = 1;                 // sky patches: 1 Tregenza (145), 2 and 4 Reinhart (577, 2305)
    // "perez": each hour's Perez all-weather sky; "cie": CIE type `cie_type` scaled to the
    // hour's diffuse horizontal illuminance (from the Perez efficacy).
    std::string sky = "perez";
    int cie_type = 16;
    double ground_reflectance = 0.2;
    // LM-83's occupied hours: the hours whose middle lies in [from, to) local standard time.
    double occupied_from_h = 8.0, occupied_to_h = 18.0;
    int year = 0;  // the calendar year of the sun positions; 0: 2017 (2016 for a leap-year file)
    // The Ladybug Tools results folder (io/annual_ladybug.hpp): empty = beside the result;
    // write_ladybug false: none.
    std::filesystem::path ladybug_folder;
    bool write_ladybug = true;
    // How the sensor grids get their direct light (issue 37): "photons" (every arrival
    // counts), or "shadow_rays" (the direct part by shadow rays from each sensor,
    // tracer/direct_daylight.hpp; the photons count only what arrives after an event).
    std::string direct = "photons";
    int direct_sky_rays = 0;   // per patch and sensor, the square of an even number; 0: about 9,216 per sensor
    int direct_sun_rays = 16;  // per sun and sensor where its disc is cut (points), or always (cells)
    bool shadow_rays() const { return direct == "shadow_rays"; }
    // How they get the light after a diffuse reflection (issue 37): "photons" (the photons
    // registering over the sensors' discs), or "gather" (shadow rays only): each photon's
    // arrival on a surface patch gathered to the sensors that see the patch, as its
    // Lambertian luminance seen through their share of the hemisphere
    // (tracer/gather_table.hpp); the discs then count only what comes off glossy, mirror
    // and glass surfaces.
    std::string indirect = "photons";
    int gather_rays = 4096;       // per sensor, the square of an even number
    double gather_patch_m = 0.5;  // the surfaces' patches' longest edge at most this
    bool gathers() const { return indirect == "gather"; }
    // The photons' light groups of the suns (issue 37, docs/ANNUAL.md "Suns' groups"): the
    // suns of one clock hour on this many consecutive days (from 1 January) share one, whose
    // interreflected and gathered light each sun then reads in its share of their direct
    // normal illuminance; 1: every sun its own group. Above 1 only with shadow rays (the
    // direct sun stays every hour's own), where it is kShadowRaySunGroupDays by default.
    int sun_group_days = 1;
    static constexpr int kShadowRaySunGroupDays = 7;
    // The rays' rule (but direct_sky_rays' 0): n x n strata, n even, 4 to 4096 rays.
    static bool valid_direct_rays(std::int64_t rays);
};

// How the ranks of a run share building the year's skies (each hour's patch luminances, most
// of the load's time): this one computes part `part` of `parts` (contiguous runs of the
// daylit hours), then `gather` fills in the others' rows: `luminance` holds every row
// (hours x entries) with this part's at its place, part p's values start at offsets[p]
// (offsets[parts] = luminance.size()). The rows come out the same, to the bit, however the
// work is shared. The default: one builds all.
struct AnnualSkyShare {
    int part = 0, parts = 1;
    std::function<void(std::vector<double>& luminance, const std::vector<std::size_t>& offsets)> gather;
};

// One hour of the weather file.
struct AnnualHour {
    int month = 0, day = 0;
    double hour_mid = 0.0;  // local standard time of the hour's middle (h), e.g. 12.5
    bool occupied = false;
    // The sun above the horizon at the middle of the hour and a diffuse irradiance > 0: the
    // hour has a sky (a row of sky vectors), otherwise it is dark.
    bool daylit = false;
    std::size_t row = 0;  // daylit: its row of sky vectors
    double sun_altitude_deg = 0.0, sun_azimuth_deg = 0.0;
    // As the sky model rebuilds them (Perez 1990 efficacies), lx.
    double diffuse_horizontal_lx = 0.0, direct_normal_lx = 0.0;
    // As the weather file gives them (NaN where it marks them missing).
    double diffuse_horizontal_w_m2 = 0.0, direct_normal_w_m2 = 0.0, dew_point_c = 0.0;
    int sun = -1;  // its sun (index in AnnualSky::suns), -1 when no direct sun
    double global_horizontal_lx() const;
};

class AnnualSky {
public:
    // Throws InputError naming the weather file and the hour for a value a daylit hour needs
    // that is missing or out of range.
    AnnualSky(const weather::WeatherFile& weather, const SunSite& site, double utc_offset_h,
              const AnnualOptions& options, const AnnualSkyShare& share = {});

    const SkyPatches& patches() const { return patches_; }
    const std::vector<AnnualHour>& hours() const { return hours_; }
    std::size_t daylit_hours() const { return rows_; }
    // Sky vector entries per row: every patch, then the ground.
    std::size_t sky_entries() const { return patches_.count() + 1; }
    std::size_t ground_entry() const { return patches_.count(); }
    // Row r's luminance of sky patch i (its mean over the patch's solid angle, scaled so
    // that the patches give the hour's diffuse horizontal illuminance) and of the
    // ground (entry ground_entry()), cd/m2.
    const double* sky_vector(std::size_t row) const { return &luminance_[row * sky_entries()]; }
    // The year's sum of each entry (cd/m2 h): what the patches' and the ground's groups emit.
    const std::vector<double>& yearly_luminance() const { return yearly_; }
    // Row r's weight of each entry's coefficient: its luminance over the year's sum (0 where
    // that is 0). Each entry's weights sum to 1 over the rows.
    const double* sky_weights(std::size_t row) const { return &weights_[row * sky_entries()]; }
    // The hours with a direct sun, in order: their hour index (in hours()).
    const std::vector<std::size_t>& suns() const { return suns_; }
    double sum_direct_normal_lx_h() const;
    // Hours whose Perez clearness or brightness lay outside the model's fitted range.
    std::size_t clamped_hours() const { return clamped_; }
    // Hours with the sun up and a direct but no diffuse irradiance (no sky to model): left dark.

private:
    // What a row's sky vector is made of: the hour's sky model and sun.
    struct RowSky;
    // Hour `index` has a sky: it gets the next row, its illuminances and its sun, and the
    // row's sky is noted in `rows` (its vector is made by sky_vectors).
    void add_sky_row(AnnualHour& h, std::size_t index, const weather::WeatherHour& w, const SunPosition& sun, int year,
                     const AnnualOptions& options, std::vector<RowSky>& rows);
    // The rows' sky vectors (the patches and the ground): this part's computed, the others'
    // gathered; then the entries' yearly sums and the weights.
    void sky_vectors(const std::vector<RowSky>& rows, const AnnualOptions& options, const AnnualSkyShare& share);

    SkyPatches patches_;
    std::vector<AnnualHour> hours_;
    std::size_t rows_ = 0, clamped_ = 0;
    std::vector<double> luminance_, yearly_, weights_;
    std::vector<std::size_t> suns_;
};

// An annual scene's sky ([annual], docs/ANNUAL.md) and where its light groups are: the
// sky patches are groups first_patch_group + i, the ground ground_group, the suns' groups
// ("sun rows") first_sun_group + r, sun s of sky->suns() in row sun_row(s): its own
// (r = s) unless options.sun_group_days > 1.
struct AnnualSetup {
    AnnualOptions options;
    std::shared_ptr<const AnnualSky> sky;
    std::size_t first_patch_group = 0, ground_group = 0, first_sun_group = 0;
    // Per sun its row, when the suns share rows (empty: each its own).
    std::vector<std::size_t> shared_sun_row;
    std::size_t sun_row(std::size_t sun) const { return shared_sun_row.empty() ? sun : shared_sun_row[sun]; }
    std::size_t sun_rows() const;
    std::size_t sun_group(int sun) const { return first_sun_group + sun_row(static_cast<std::size_t>(sun)); }
};

// Sun rows for suns of `days` consecutive days: per sun (sky.suns() order) its row, rows
// numbered in the order of their first sun; empty for days <= 1.
std::vector<std::size_t> sun_rows_of_days(const AnnualSky& sky, int days);

// The hour's middle in local standard time: an EPW hour is the hour ENDING then (hour 1 is
// 00:00-01:00, its middle 0.5); a .wea's decimal hour is already the middle as written.
double hour_middle(const weather::WeatherHour& h, weather::WeatherFormat format);

}  // namespace luxtrace
