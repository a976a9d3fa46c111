#pragma once
// A light source: what every light shares (label, group, flux, band shares, dimming,
// maintenance, its daylight reference's horizontal illuminance) and its kind, one type per
// kind in a std::variant visited once per photon.
//
// Where a new kind goes (a linear luminaire, an HDR sky, a glow with a radius):
//   1. its own pair, include/luxtrace/light/NAME_light.hpp and src/light/NAME_light.cpp:
//      a struct with the kind's data and what every kind answers (point_light.hpp is the
//      fullest example):
//        EmittedRay emit(u_pos1, u_pos2, u_dir1, u_dir2) const   a photon, from four uniforms
//        draws_position() const   whether emit uses u_pos1 and u_pos2 (the photon's block 1)
//        distant() const          light from outside the scene (beams, daylight)
//        view_from(eye, flux_lm) const -> LuminaireView   how an eye sees it (UGR, glare/)
//      and, where the kind has them (left out, the answer is "none"):
//        place(SceneSphere) -> flux_lm      a distant light's disk over the scene
//        incident_sampling(requested), incident(p, n, flux_lm, u1, u2, count, IncidentLight&)
//                                 the light it sends to a point, for a shadow ray
//        luminance_seen_cd_m2(direction)    what a ray leaving the scene sees of it
//        daylight() -> DaylightReference    sun and sky: the daylight factors' reference
//        may_be_dark(flux_lm)      whether emitting nothing is allowed (a sun below the horizon)
//        describe_photometry(out), describe(out, unobstructed_horizontal_lx)   `check`, `info`
//   2. its alternative in LightKind below;
//   3. its loader: a function in scene/light_loader.cpp's table of [[light]] type names.
// Nothing in the tracer changes: it asks Light::emit and Light::draws_position only.
#include "luxtrace/light/area_light.hpp"
#include "luxtrace/light/directional_light.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/point_light.hpp"
#include "luxtrace/light/portal_light.hpp"
#include "luxtrace/light/sky_light.hpp"
#include "luxtrace/light/sky_patch_light.hpp"
#include "luxtrace/light/spot_light.hpp"
#include "luxtrace/light/sun_light.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

namespace luxtrace {

using LightKind =
    std::variant<PointLight, SpotLight, AreaLight, DirectionalLight, SunLight, SkyLight, SkyPatchLight, PortalLight>;

struct Light {
    std::string label;  // e.g. "light 2 (spot)" for messages
    // Its light group (`group = "NAME"`, issue 22): the index in Scene::light_groups. Every
    // tally keeps the groups apart, so light scenes recombine them after the run.
    std::size_t group = 0;
    double flux_lm = 0.0;
    std::vector<double> band_share;  // normalised colour share per band
    // `dimming` is already in flux_lm; maintained values are maintenance_factor times the
    // initial ones.
    double dimming = 1.0, maintenance_factor = 1.0;
    // Daylight (sun and sky, issue 23): the illuminance this light alone gives an
    // unobstructed horizontal plane from above (ground glow excluded), from its model,
    // not from the run: the E_h,ext of daylight factors. 0 for electric light. A light
    // split over several portals keeps it on the first only, so the scene's sum stays
    // that of the sky.
    double unobstructed_horizontal_lx = 0.0;
    // An annual run's sun (issue 24): its index in AnnualSky::suns() (its flux apart from
    // the others of its light group, AnnualSetup::sun_row); -1 for any other light.
    std::int64_t annual_sun = -1;
    LightKind kind;

    template <class K>
    const K* as() const {
        return std::get_if<K>(&kind);
    }
    template <class K>
    K* as() {
        return std::get_if<K>(&kind);
    }
    template <class K>
    bool is() const {
        return std::holds_alternative<K>(kind);
    }

    // One call per photon: the kinds' emit functions are inline in their headers and
    // meet in this one function (light.cpp), as one switch.
    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    // Whether its photons' start points are drawn (area lights, beams, luminous openings):
    // two more uniforms, from the photon's block 1.
    bool draws_position() const {
        return std::visit([](const auto& k) { return k.draws_position(); }, kind);
    }
    bool distant() const {
        return std::visit([](const auto& k) { return k.distant(); }, kind);
    }
    // A distant light's disk over the sphere around [lo, hi], and the flux it then emits.
    void place(const Vec3& lo, const Vec3& hi);
    IncidentSampling incident_sampling(int requested) const;
    // A sample of its light at p on a surface of normal n (IncidentLight); false if none.
    bool incident(const Vec3& p, const Vec3& n, double u1, double u2, int count, IncidentLight& in) const;
    double luminance_seen_cd_m2(const Vec3& direction) const;
    LuminaireView view_from(const Vec3& eye) const {
        return std::visit([&](const auto& k) { return k.view_from(eye, flux_lm); }, kind);
    }
    std::optional<DaylightReference> daylight() const;
    bool may_be_dark() const;
    // Its line's details in `check` and `info` after the label and flux.
    void describe(std::ostream& out) const;
    // Whether a portal lets it in (a sun, sky or sky patch), and the light it lets in.
    bool enters_portals() const { return is<SunLight>() || is<SkyLight>() || is<SkyPatchLight>(); }
    std::optional<Light> through_portal(const std::shared_ptr<const Portal>& portal, std::size_t index) const;
};

}  // namespace luxtrace
