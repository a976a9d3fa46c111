#pragma once
// A sun, sky or sky patch shining through a portal (portal.hpp): its photons start on the
// opening, or for a sky patch on a disk around it, instead of on the disk covering the
// whole scene, and its flux is what the unobstructed sun or sky sends through the opening.
// A light with several portals is one light per portal, `portal_index` 0, 1, ...
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/light_queries.hpp"
#include "luxtrace/light/portal.hpp"
#include "luxtrace/light/sky_light.hpp"
#include "luxtrace/light/sky_patch_light.hpp"
#include "luxtrace/light/sun_light.hpp"
#include "luxtrace/light/uniform_sampling.hpp"

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <variant>

namespace luxtrace {

// The kinds of light a portal lets in.
using DaylightKind = std::variant<SunLight, SkyLight, SkyPatchLight>;

struct PortalLight {
    DaylightKind source;
    std::shared_ptr<const Portal> portal;
    std::shared_ptr<const PortalSky> portal_sky;  // a sky's directions through the opening
    std::size_t portal_index = 0;
    // A sky patch's photons start on the disk perpendicular to their direction around the
    // opening (its centroid, the largest distance to a corner), kept if they cross the
    // opening: the flux through it is then exactly L A cos(theta) per direction, with
    // every photon's share equal.
    Beam disk;

    // `source` through `portal`, and the flux that enters (lm): E_n A cos(theta_sun) for
    // the sun, A x the integral of L cos over the opening's outward hemisphere for a sky,
    // L x solid angle x the disk's area for a patch facing the opening's outside.
    static PortalLight through(DaylightKind source, std::shared_ptr<const Portal> portal, std::size_t index,
                               double& flux_lm);
    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    static constexpr bool draws_position() { return true; }
    static constexpr bool distant() { return true; }
    // A sky through portals is sampled over each opening; a sun split over portals is one
    // light per opening, which a picture takes once (its shadow rays find the openings).
    IncidentSampling incident_sampling(int requested) const;
    bool incident(const Vec3& p, const Vec3& n, double flux_lm, double u1, double u2, int count,
                  IncidentLight& in) const;
    double luminance_seen_cd_m2(const Vec3& direction) const;
    LuminaireView view_from(const Vec3& eye, double flux_lm) const;
    std::optional<DaylightReference> daylight() const;
    bool may_be_dark(double flux_lm) const { return flux_lm == 0.0; }
    // Whether the source itself shines (a sky, or a sun above the horizon), and if nothing
    // enters, why.
    bool source_lit() const;
    std::string why_dark() const;
    void describe(std::ostream& out, double unobstructed_horizontal_lx) const;

private:
    // A photon starting just outside the opening at (u_pos1, u_pos2), travelling along `direction`.
    EmittedRay from_opening(const Vec3& direction, double u_pos1, double u_pos2) const;
    // A sky patch's: from the disk around the opening along `direction`.
    EmittedRay from_disk(const Vec3& direction, double u_pos1, double u_pos2) const;
};

// Inline: the tracer emits every photon through here (Light::emit).
inline EmittedRay PortalLight::emit(double up1, double up2, double ud1, double ud2) const {
    if (const auto* patch = std::get_if<SkyPatchLight>(&source))
        return from_disk(patch->travel_direction(ud1, ud2), up1, up2);
    if (const auto* sun = std::get_if<SunLight>(&source))
        return from_opening(sun->travel_direction(ud1, ud2), up1, up2);
    return from_opening(-portal_sky->sample(ud1, ud2), up1, up2);
}

}  // namespace luxtrace
