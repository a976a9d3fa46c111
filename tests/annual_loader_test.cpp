// [annual] in the scene loader (src/scene/annual_loader.cpp, src/annual/annual_sky.cpp;
// docs/ANNUAL.md): the weather file's year becomes one light group per sky patch, the
// ground and every hour's sun, each emitting the year's sum of its hourly values; the
// hourly skies carry exactly the hour's diffuse illuminance; bad input is an InputError
// naming the file, line and key.
#include "luxtrace/annual/annual_sky.hpp"
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/weather/weather_file.hpp"
#include "scene_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

namespace luxtrace {
namespace {

using namespace test_support;

const std::string kEpw = data("weather/chicago.epw").string();
const std::string kAnnual = "[annual]\nweather = \"" + kEpw + "\"\n";
const std::string kGrid = "[[detector]]\nname = \"desk\"\ncenter = [0, 0, 0.8]\nsize = [2, 2]\ncells = [2, 2]\n";

TEST_F(Loader, AnnualScenesLightsAreThePatchesTheGroundAndEverySunHour) {
    const Scene s = load(kAnnual + kMat + kFloor + kGrid);
    ASSERT_TRUE(s.annual);
    const AnnualSetup& a = *s.annual;
    const AnnualSky& sky = *a.sky;
    EXPECT_EQ(sky.hours().size(), 8760u);
    EXPECT_EQ(sky.patches().count(), 145u);
    // Groups: the patches in Radiance's order, the ground, then one per sun hour.
    ASSERT_EQ(s.light_groups.size(), 145u + 1u + sky.suns().size());
    EXPECT_EQ(s.light_groups.front(), "sky_001");
    EXPECT_EQ(s.light_groups[a.ground_group], "ground");
    EXPECT_EQ(s.light_groups[a.sun_group(0)], "sun_" + std::string(4 - std::to_string(sky.suns()[0] + 1).size(), '0') +
                                                  std::to_string(sky.suns()[0] + 1));
    EXPECT_GT(sky.suns().size(), 3000u);
    EXPECT_LE(sky.suns().size(), sky.daylit_hours());
    // The site is the weather file's (no [site]).
    EXPECT_NEAR(s.site.sun_site.latitude_deg, 41.98, 1e-9);
    EXPECT_NEAR(s.site.sun_site.longitude_deg, -87.92, 1e-9);
    EXPECT_EQ(s.site.utc_offset_h, -6.0);
    // The tallies keep direct counts and one surface map.
    const TallyLayout layout = tally_layout(s);
    EXPECT_TRUE(layout.direct_scores());
    EXPECT_EQ(layout.map_groups(), 1u);
    EXPECT_FALSE(s.run.group_maps);
    // Each light emits the year's sum: a patch's flux is Y_p Omega_p pi R^2 on the beam disk.
    double sun_lx_h = 0.0;
    for (const Light& l : s.lights.lights()) {
        if (const SkyPatchLight* k = l.as<SkyPatchLight>()) {
            const std::size_t p = l.group - a.first_patch_group;
            EXPECT_DOUBLE_EQ(k->luminance_cd_m2, sky.yearly_luminance()[p]);
            EXPECT_NEAR(k->patch.solid_angle_sr(), sky.patches().solid_angle_sr(p), 1e-12);
            EXPECT_NEAR(l.flux_lm,
                        k->luminance_cd_m2 * k->patch.solid_angle_sr() * kPi * k->beam.radius * k->beam.radius,
                        1e-9 * l.flux_lm);
        } else if (const SunLight* sun = l.as<SunLight>()) {
            const std::size_t i = l.group - a.first_sun_group;
            EXPECT_EQ(sun->illuminance_lx, sky.hours()[sky.suns()[i]].direct_normal_lx);
            sun_lx_h += sun->illuminance_lx;
        }
    }
    EXPECT_NEAR(sun_lx_h, sky.sum_direct_normal_lx_h(), 1e-9 * sun_lx_h);
}

TEST_F(Loader, AnnualHoursSkyCarriesTheDiffuseIlluminanceAndTheSunSitsMidHour) {
    const Scene s = load(kAnnual + kMat + kFloor + kGrid);
    const AnnualSky& sky = *s.annual->sky;
    const SkyPatches& p = sky.patches();
    const weather::WeatherFile w = weather::read_epw(kEpw);
    std::size_t checked = 0;
    for (std::size_t h = 0; h < sky.hours().size(); ++h) {
        const AnnualHour& a = sky.hours()[h];
        // EPW hour k is (k - 1):00 to k:00; its sun is computed at the middle.
        EXPECT_DOUBLE_EQ(a.hour_mid, w.hours[h].hour - 0.5);
        EXPECT_EQ(a.occupied, a.hour_mid >= 8.0 && a.hour_mid < 18.0);
        if (!a.daylit) continue;
        EXPECT_GT(a.sun_altitude_deg, 0.0);
        const double* v = sky.sky_vector(a.row);
        double e = 0.0;
        for (std::size_t i = 0; i < p.count(); ++i) e += v[i] * p.projected_solid_angle_sr(i);
        EXPECT_NEAR(e, a.diffuse_horizontal_lx, 1e-9 * a.diffuse_horizontal_lx);
        EXPECT_NEAR(v[sky.ground_entry()], 0.2 * a.global_horizontal_lx() / kPi, 1e-9 * a.global_horizontal_lx());
        ++checked;
    }
    EXPECT_EQ(checked, sky.daylit_hours());
    EXPECT_GT(checked, 4000u);
}

// The ranks share building the year's skies (AnnualSkyShare): each computes its run of
// the hours, the gather gives everyone every row. Built in three parts, their rows put
// together, the skies are the one-part build's to the bit; and a part leaves the others'
// rows to the gather.
TEST_F(Loader, AnnualSkiesBuiltInPartsAreTheSameBits) {
    const weather::WeatherFile w = weather::read_epw(kEpw);
    const Scene s = load(kAnnual + kMat + kFloor + kGrid);
    const SunSite site = s.site.sun_site;
    const double utc = s.site.utc_offset_h;
    const AnnualOptions options = s.annual->options;
    const AnnualSky whole(w, site, utc, options);
    const std::size_t values = whole.daylit_hours() * whole.sky_entries();
    constexpr int kParts = 3;
    std::vector<std::vector<double>> parts(kParts);
    std::vector<std::size_t> offsets;
    for (int p = 0; p < kParts; ++p) {
        AnnualSkyShare share;
        share.part = p;
        share.parts = kParts;
        share.gather = [&](std::vector<double>& luminance, const std::vector<std::size_t>& o) {
            parts[static_cast<std::size_t>(p)] = luminance;  // only its own rows are filled
            offsets = o;
        };
        const AnnualSky part(w, site, utc, options, share);
    }
    ASSERT_EQ(offsets.size(), static_cast<std::size_t>(kParts) + 1);
    EXPECT_EQ(offsets.back(), values);
    // Each part's rows are the whole build's; outside them it computed nothing.
    for (int p = 0; p < kParts; ++p)
        for (std::size_t i = 0; i < values; ++i) {
            const double got = parts[static_cast<std::size_t>(p)][i];
            const std::size_t row = i / whole.sky_entries(), e = i % whole.sky_entries();
            const bool own = i >= offsets[static_cast<std::size_t>(p)] && i < offsets[static_cast<std::size_t>(p) + 1];
            ASSERT_EQ(got, own ? whole.sky_vector(row)[e] : 0.0) << "part " << p << ", value " << i;
        }
    // Put together by the gather, the sky is the whole one's, weights and sums included.
    AnnualSkyShare share;
    share.part = 1;
    share.parts = kParts;
    share.gather = [&](std::vector<double>& luminance, const std::vector<std::size_t>& o) {
        for (int p = 0; p < kParts; ++p)
            for (std::size_t i = o[static_cast<std::size_t>(p)]; i < o[static_cast<std::size_t>(p) + 1]; ++i)
                luminance[i] = parts[static_cast<std::size_t>(p)][i];
    };
    const AnnualSky shared(w, site, utc, options, share);
    EXPECT_EQ(shared.yearly_luminance(), whole.yearly_luminance());
    for (std::size_t r = 0; r < whole.daylit_hours(); ++r)
        for (std::size_t e = 0; e < whole.sky_entries(); ++e) {
            ASSERT_EQ(shared.sky_vector(r)[e], whole.sky_vector(r)[e]);
            ASSERT_EQ(shared.sky_weights(r)[e], whole.sky_weights(r)[e]);
        }
    EXPECT_EQ(shared.suns(), whole.suns());
}

TEST_F(Loader, AnnualPortalDropsPatchesBehindTheOpening) {
    // A window facing south (y = 0 plane, outward -y): no patch of the northern sky enters.
    const std::string window =
        "[[shape]]\nname = \"window\"\ntype = \"rectangle\"\ncenter = [0, 0, 1]\nnormal = [0, 1, 0]\nsize = [1, 1]\n"
        "material = \"m\"\n[[portal]]\nshape = \"window\"\n";
    const Scene s = load(kAnnual + kMat + kFloor + window + kGrid);
    std::size_t patches = 0;
    for (const Light& l : s.lights.lights()) {
        const PortalLight* through = l.as<PortalLight>();
        ASSERT_TRUE(through != nullptr) << l.label;
        const SkyPatchLight* k = std::get_if<SkyPatchLight>(&through->source);
        if (k == nullptr) continue;
        ++patches;
        // Some of the patch faces the opening's outside (within the check's 0.1 margin).
        const double mid_az = k->patch.az_lo_rad + 0.5 * k->patch.az_width_rad;
        EXPECT_FALSE(std::cos(mid_az) > 0.5 && k->patch.mu_hi < 0.5) << l.label << " looks north";
    }
    EXPECT_GT(patches, 50u);
    EXPECT_LT(patches, 120u);
}

TEST_F(Loader, AnnualBadInputNamesItsKey) {
    expect_bad("[annual]\nweather = \"nowhere.epw\"\n" + kMat + kFloor, "", {"nowhere.epw"});
    expect_bad("[annual]\n" + kMat + kFloor, "", {"[annual]", "weather"});
    expect_bad(kAnnual + "sky_mf = 9\n" + kMat + kFloor, "sky_mf", {"sky_mf", "1"});
    expect_bad(kAnnual + "sky = \"blue\"\n" + kMat + kFloor, "sky =", {"perez", "cie"});
    expect_bad(kAnnual + "cie_type = 3\n" + kMat + kFloor, "cie_type", {"cie_type"});
    expect_bad(kAnnual + "occupied_hours = [18, 8]\n" + kMat + kFloor, "occupied_hours", {"occupied_hours"});
    expect_bad(kAnnual + "ground_reflectance = 2\n" + kMat + kFloor, "ground_reflectance", {"[0, 1]"});
    expect_bad(kAnnual + "direct = \"rays\"\n" + kMat + kFloor, "direct =", {"photons", "shadow_rays"});
    expect_bad(kAnnual + "direct = \"shadow_rays\"\ndirect_sky_rays = 9\n" + kMat + kFloor, "direct_sky_rays",
               {"square of an even number", "9"});
    expect_bad(kAnnual + "direct = \"shadow_rays\"\ndirect_sun_rays = 0\n" + kMat + kFloor, "direct_sun_rays",
               {"square of an even number"});
    expect_bad(kAnnual + "direct_sun_rays = 16\n" + kMat + kFloor, "direct_sun_rays", {"shadow_rays"});
    const std::string shadow = "direct = \"shadow_rays\"\n";
    expect_bad(kAnnual + shadow + "indirect = \"map\"\n" + kMat + kFloor, "indirect", {"photons", "gather"});
    expect_bad(kAnnual + "indirect = \"gather\"\n" + kMat + kFloor, "indirect", {"shadow_rays"});
    expect_bad(kAnnual + shadow + "gather_rays = 64\n" + kMat + kFloor, "gather_rays", {"gather"});
    expect_bad(kAnnual + shadow + "indirect = \"gather\"\ngather_rays = 50\n" + kMat + kFloor, "gather_rays",
               {"square of an even number", "50"});
    expect_bad(kAnnual + shadow + "indirect = \"gather\"\ngather_patch_m = 0\n" + kMat + kFloor, "gather_patch_m",
               {"(0, 1000]"});
    expect_bad(kAnnual + shadow + "gather_patch_m = 0.3\n" + kMat + kFloor, "gather_patch_m", {"gather"});
    expect_bad(kAnnual + "sun_group_days = 7\n" + kMat + kFloor, "sun_group_days", {"shadow_rays"});
    expect_bad(kAnnual + shadow + "sun_group_days = 0\n" + kMat + kFloor, "sun_group_days", {"1 to 366"});
    // A [site] that contradicts the weather file.
    expect_bad("[site]\nlatitude_deg = 52.5\nlongitude_deg = 13.4\nutc_offset_h = 1\n" + kAnnual + kMat + kFloor,
               "weather", {"latitude_deg", "41.98"});
    // Lights come from [annual].
    expect_bad(kAnnual + kMat + kFloor + kLamp, "", {"[annual]", "[[light]]"});
    expect_bad(kAnnual + kMat + kFloor + "[run]\ngroup_maps = true\n", "group_maps", {"annual"});
    expect_bad(kAnnual + "[scene]\nbands = [\"R\", \"G\", \"B\"]\n" + kMat + kFloor, "", {"one band"});
}

TEST_F(Loader, AnnualDirectByShadowRaysKeepsTheGridsDirectApart) {
    const Scene photons = load(kAnnual + kMat + kFloor + kGrid);
    EXPECT_FALSE(photons.annual->options.shadow_rays());
    EXPECT_FALSE(tally_layout(photons).direct_apart(0));
    const Scene shadow = load(kAnnual + "direct = \"shadow_rays\"\ndirect_sky_rays = 16\ndirect_sun_rays = 36\n" +
                              kMat + kFloor + kGrid);
    EXPECT_TRUE(shadow.annual->options.shadow_rays());
    EXPECT_EQ(shadow.annual->options.direct_sky_rays, 16);
    EXPECT_EQ(shadow.annual->options.direct_sun_rays, 36);
    EXPECT_TRUE(tally_layout(shadow).direct_apart(0));
    EXPECT_FALSE(tally_layout(shadow).gathered(0));
    const Scene gather = load(kAnnual +
                              "direct = \"shadow_rays\"\nindirect = \"gather\"\ngather_rays = 256\n"
                              "gather_patch_m = 0.25\n" +
                              kMat + kFloor + kGrid);
    EXPECT_TRUE(gather.annual->options.gathers());
    EXPECT_EQ(gather.annual->options.gather_rays, 256);
    EXPECT_EQ(gather.annual->options.gather_patch_m, 0.25);
    EXPECT_TRUE(tally_layout(gather).gathered(0));
    EXPECT_GT(tally_layout(gather).size(), tally_layout(shadow).size());
}

// sun_group_days (7 by default with shadow rays): the suns of one clock hour on a block of
// days share a light group (in the order of their first sun), each sun light keeping its own
// index; the tallies shrink.
TEST_F(Loader, AnnualSunsOfAWeeksClockHourShareALightGroup) {
    const std::string shadow = "direct = \"shadow_rays\"\n";
    const Scene own = load(kAnnual + shadow + "sun_group_days = 1\n" + kMat + kFloor + kGrid);
    const Scene week = load(kAnnual + shadow + kMat + kFloor + kGrid);  // 7 days: the default with shadow rays
    EXPECT_EQ(week.annual->options.sun_group_days, 7);
    EXPECT_EQ(load(kAnnual + kMat + kFloor + kGrid).annual->options.sun_group_days, 1);
    const AnnualSetup& a = *week.annual;
    const AnnualSky& sky = *a.sky;
    EXPECT_EQ(own.annual->sun_rows(), sky.suns().size());
    const std::size_t rows = a.sun_rows();
    EXPECT_EQ(week.light_groups.size(), 146u + rows);
    // About a seventh of the suns' groups: a clock hour's suns of a week, fewer at dawn and dusk.
    EXPECT_LT(rows, sky.suns().size() / 5);
    EXPECT_GT(rows, sky.suns().size() / 8);
    std::vector<std::size_t> suns_seen(sky.suns().size(), 0);
    for (const Light& l : week.lights.lights()) {
        if (!l.is<SunLight>()) continue;
        ASSERT_GE(l.annual_sun, 0);
        const std::size_t s = static_cast<std::size_t>(l.annual_sun), h = sky.suns()[s];
        ++suns_seen[s];
        EXPECT_EQ(l.group, a.first_sun_group + a.sun_row(s));
        // Its group's name: the first day of its block and its clock hour.
        char name[32];
        std::snprintf(name, sizeof name, "suns_%03zu_%02zu", h / 24 / 7 * 7 + 1, h % 24);
        const std::string& group = week.light_groups[l.group];
        EXPECT_EQ(group.substr(group.size() - 2), std::string(name).substr(std::strlen(name) - 2)) << group;
        // Every sun of a group shares its clock hour and its week.
        const std::size_t first = sky.suns()[std::find(a.shared_sun_row.begin(), a.shared_sun_row.end(), a.sun_row(s)) -
                                             a.shared_sun_row.begin()];
        EXPECT_EQ(first % 24, h % 24);
        EXPECT_EQ(first / 24 / 7, h / 24 / 7);
    }
    for (const std::size_t n : suns_seen) EXPECT_EQ(n, 1u);
    EXPECT_LT(tally_layout(week).size(), tally_layout(own).size() / 3);
}

TEST_F(Loader, AnnualTruncatedWeatherFileNamesItsLine) {
    std::ifstream in(kEpw);
    std::ofstream out(dir_ / "short.epw");
    std::string line;
    for (int i = 0; i < 8 + 100 && std::getline(in, line); ++i) out << line << '\n';
    out.close();
    expect_bad("[annual]\nweather = \"short.epw\"\n" + kMat + kFloor, "", {"short.epw"});
}

}  // namespace
}  // namespace luxtrace
