#pragma once
// Light sources and photon emission. A light turns four uniforms into a starting point
// and direction; which light and which band emits photon k is chosen by LightSet in
// proportion to flux (SPEC §3).
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/photometry.hpp"
#include "luxtrace/light/photometry_distribution.hpp"
#include "luxtrace/light/sky_directions.hpp"

#include <memory>
#include <string>
#include <vector>

namespace luxtrace {

struct Portal;
class PortalSky;

enum class LightType { point, spot, area, directional, sun, sky, sky_patch };

struct EmittedRay {
    Vec3 origin;
    Vec3 direction;
    int emitter_triangle = -1;                // area lights: the scene triangle the photon leaves from,
    double emitter_u = 0.0, emitter_v = 0.0;  // and the point's barycentrics on it (as Embree's)
    // Which side of the emitter triangle the photon leaves from: +1 its front, -1 its back.
    // A portal photon starts outside the opening and checks its way back to the sky.
    int emitter_side = 1;
    bool through_portal = false;
    // A sky patch's photon aimed past its portal (Light::emit_through_portal_disk): it
    // carries its share of the flux but never enters the scene.
    bool missed = false;
};

// A sky patch (annual daylight, light/sky_patches.hpp) in the sky frame: sin(altitude) in
// [mu_lo, mu_hi], azimuth (clockwise from north) from az_lo_rad over az_width_rad.
struct SkyPatchBounds {
    double mu_lo = 0.0, mu_hi = 1.0, az_lo_rad = 0.0, az_width_rad = 2.0 * kPi;
    double solid_angle_sr() const { return (mu_hi - mu_lo) * az_width_rad; }
};

// Triangles of an area emitter, with the cumulative area for uniform position sampling.
struct EmitterSurface {
    std::vector<Vec3> p0, e1, e2, normal;  // vertex, two edges, unit front normal
    std::vector<double> cdf;               // normalised cumulative area
    std::vector<int> scene_triangle;
    double area_m2 = 0.0;
};

struct Light {
    std::string label;  // e.g. "light 2 (spot)" for messages
    LightType type = LightType::point;
    // Its light group (`group = "NAME"`, issue 22): the index in Scene::light_groups. Every
    // tally keeps the groups apart, so light scenes recombine them after the run.
    std::size_t group = 0;
    double flux_lm = 0.0;
    std::vector<double> band_share;  // normalised colour share per band
    // point / spot
    Vec3 position{0.0};           // point with photometry: the photometric centre
    Vec3 aim{0.0, 0.0, -1.0};     // point with photometry: photometric axis; spot: axis
    double cos_half_angle = 1.0;  // spot
    // A point light with a luminaire's photometry: its direction sampler, and the
    // photometry as read (intensities for the renderer's direct light). Intensity toward
    // a direction = photometry->intensity_cd(local) * flux_lm / photometry->flux_lm().
    std::shared_ptr<const PhotometryDistribution> distribution;
    std::shared_ptr<const Photometry> photometry;
    // Where its photons start: the file's luminous opening, or a point (`emission = "point"`).
    LuminousOpening opening;
    Frame frame = Frame::around(Vec3(0, 0, -1));  // local +z = aim, +x = C0 (photometry.hpp)
    // The factors that made flux_lm from the file's flux (for reports): flux_lm =
    // photometry->flux_lm() x multiplier x lamp_factor x dimming x tilt_factor; maintained
    // values are maintenance_factor times the initial ones.
    double multiplier = 1.0, lamp_factor = 1.0, dimming = 1.0, tilt_factor = 1.0;
    double maintenance_factor = 1.0;
    // Daylight (sun and sky, issue 23): the illuminance this light alone gives an
    // unobstructed horizontal plane from above (ground glow excluded), from its model,
    // not from the run: the E_h,ext of daylight factors. 0 for electric light.
    double unobstructed_horizontal_lx = 0.0;
    // area
    EmitterSurface surface;
    // directional: a disk of radius `beam_radius` centred on the scene's bounding sphere,
    // set back along -direction, emits parallel rays. sun: the same disk, perpendicular
    // to `aim` (the direction of travel from the sun's centre), emits rays spread evenly
    // over the solar disc (cos_half_angle); illuminance_lx is the direct normal
    // illuminance. sky: `beam_center` is the sphere's centre and each photon starts on the
    // disk perpendicular to its own direction.
    double illuminance_lx = 0.0;
    Vec3 beam_center{0.0};
    double beam_radius = 0.0;
    // sun and sky (docs/DAYLIGHT.md): the sun's position they refer to (for the sky, the
    // one its luminance distribution is centred on; unused by types 16 and uniform).
    double sun_altitude_deg = 0.0, sun_azimuth_deg = 0.0;
    // sky: where its photons come from (sky frame), and the sky frame in the scene
    // (site.hpp: t = east, b = north, n = up).
    std::shared_ptr<const SkyDirections> sky;
    Frame horizon{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    std::string sky_description;  // e.g. "CIE type 16", "uniform", "ground glow of light 2 (sun)"
    // sun and sky through a [[portal]] (portal.hpp): photons start on the opening instead
    // of the beam disk; flux_lm is what the unobstructed sky or sun sends through it. A
    // light with several portals is one Light per portal, `portal_index` 0, 1, ...; only
    // the first keeps unobstructed_horizontal_lx, so the scene's sum stays that of the sky.
    std::shared_ptr<const Portal> portal;
    std::shared_ptr<const PortalSky> portal_sky;  // sky: its directions through the opening
    std::size_t portal_index = 0;
    // sky_patch (annual daylight, docs/ANNUAL.md): uniform luminance `patch_luminance_cd_m2`
    // over `patch`, directions uniform in solid angle. Without a portal its photons start on
    // the scene's beam disk like a sky's; through one, on a disk perpendicular to their
    // direction around the opening (beam_center, beam_radius: its centroid and the largest
    // distance to a corner), kept if they cross the opening: the flux through it is then
    // exactly L A cos(theta) per direction, with every photon's share equal.
    SkyPatchBounds patch;
    double patch_luminance_cd_m2 = 0.0;

    EmittedRay emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const;
    // A photon starting just outside the portal at (u_pos1, u_pos2), travelling along `direction`.
    EmittedRay emit_through_portal(const Vec3& direction, double u_pos1, double u_pos2) const;
    // sky_patch through a portal: from the disk around the opening along `direction`.
    EmittedRay emit_through_portal_disk(const Vec3& direction, double u_pos1, double u_pos2) const;
    // Whether its photons start on a beam disk (directional, sun, sky): they then draw
    // two uniforms for the position.
    bool beam() const {
        return type == LightType::directional || type == LightType::sun || type == LightType::sky ||
               type == LightType::sky_patch;
    }
    // Whether its photons' start points are drawn (area lights, beams, luminous openings):
    // two more uniforms, from the photon's block 1.
    bool draws_position() const {
        return type == LightType::area || beam() || opening.shape != LuminousOpening::Shape::point;
    }
};

// The solar disc seen from the Earth: 0.533 degrees across.
inline constexpr double kSunHalfAngleDeg = 0.2665;

// Choice of light and band for a photon, both by inversion of cumulative tables.
class LightSet {
public:
    LightSet() = default;
    explicit LightSet(std::vector<Light> lights);
    const std::vector<Light>& lights() const { return lights_; }
    double total_flux_lm() const { return total_flux_lm_; }
    // The lights' maintenance factors weighted by flux, and whether they are all the same
    // (then maintained values are exactly this times the initial ones).
    double maintenance_factor() const { return maintenance_factor_; }
    bool maintenance_factor_uniform() const { return maintenance_factor_uniform_; }
    std::size_t pick_light(double u) const;
    int pick_band(std::size_t light, double u) const;

private:
    std::vector<Light> lights_;
    std::vector<double> light_cdf_;
    std::vector<std::vector<double>> band_cdf_;
    double total_flux_lm_ = 0.0;
    double maintenance_factor_ = 1.0;
    bool maintenance_factor_uniform_ = true;
};

// Uniform direction on the unit sphere and inside a cone around +z (local frame).
Vec3 sample_uniform_sphere(double u1, double u2);
Vec3 sample_uniform_cone(double cos_max, double u1, double u2);
// Uniform point on the disk of `radius` around the origin in the z = 0 plane.
Vec3 disk_point(double radius, double u1, double u2);
// A uniform point on the surface (two uniforms): the surface's triangle, the point's
// barycentrics on it, the point.
struct SurfacePick {
    std::size_t triangle = 0;
    double a = 0.0, b = 0.0;
    Vec3 point{0.0};
};
SurfacePick surface_point(const EmitterSurface& surface, double u1, double u2);
// Index of the first cdf entry > u (cdf normalised, last entry 1).
std::size_t sample_cdf(const std::vector<double>& cdf, double u);

}  // namespace luxtrace
