#include "luxtrace/light/portal_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

namespace {

// Does any of the patch face the opening's outside? cos(theta) is linear in the
// direction, so between the points of a 5 x 5 grid it changes by less than the grid's
// angular step (< 0.1 rad for any patch): a patch is dropped only when it lies behind the
// opening by more than that everywhere.
bool faces_outside(const SkyPatchLight& light, const Vec3& outward) {
    bool faces = false;
    for (int im = 0; im <= 4; ++im)
        for (int ia = 0; ia <= 4; ++ia) {
            const double mu = light.patch.mu_lo + 0.25 * im * (light.patch.mu_hi - light.patch.mu_lo);
            const double az = light.patch.az_lo_rad + 0.25 * ia * light.patch.az_width_rad;
            const double c = std::sqrt(std::max(0.0, 1.0 - mu * mu));
            faces = faces ||
                    glm::dot(light.horizon.to_world(Vec3(c * std::sin(az), c * std::cos(az), mu)), outward) > -0.1;
        }
    return faces;
}

}  // namespace

PortalLight PortalLight::through(DaylightKind source, std::shared_ptr<const Portal> portal, std::size_t index,
                                 double& flux_lm) {
    PortalLight l;
    l.portal = std::move(portal);
    l.portal_index = index;
    const double area = l.portal->surface.area_m2;
    if (const auto* patch = std::get_if<SkyPatchLight>(&source)) {
        const Vec3 centroid = l.portal->surface.centroid();
        l.disk.center = centroid;
        l.disk.radius = l.portal->surface.radius_around(centroid) * (1.0 + 1e-9) + 1e-12;
        flux_lm = faces_outside(*patch, l.portal->outward)
                      ? patch->luminance_cd_m2 * patch->patch.solid_angle_sr() * kPi * l.disk.radius * l.disk.radius
                      : 0.0;
    } else if (const auto* sun = std::get_if<SunLight>(&source)) {
        // Directions from the disc as without the portal.
        flux_lm = sun->illuminance_lx * area * std::max(0.0, -glm::dot(sun->aim, l.portal->outward));
    } else {
        const SkyLight& sky = std::get<SkyLight>(source);
        l.portal_sky = std::make_shared<const PortalSky>(sky.sky->luminance(), sky.horizon, l.portal->frame);
        flux_lm = l.portal_sky->illuminance_lx() * area;
    }
    l.source = std::move(source);
    return l;
}

EmittedRay PortalLight::from_opening(const Vec3& direction, double up1, double up2) const {
    const SurfacePick s = surface_point(portal->surface, up1, up2);
    return {s.point, direction, portal->surface.scene_triangle[s.triangle], s.a, s.b, portal->side, true};
}

EmittedRay PortalLight::from_disk(const Vec3& d, double up1, double up2) const {
    EmittedRay missed;
    missed.direction = d;
    missed.missed = true;
    const double facing = glm::dot(d, portal->outward);  // < 0: travelling inward
    if (!(facing < 0.0)) return missed;
    // A point on the disk through the centroid perpendicular to d, slid along d onto the
    // opening's plane.
    const Vec3 q = disk.center + Frame::around(d).to_world(disk_point(disk.radius, up1, up2));
    const Vec3 x = q + (glm::dot(disk.center - q, portal->outward) / facing) * d;
    const auto at = locate_on_surface(portal->surface, x);
    if (!at) return missed;
    return {x, d, portal->surface.scene_triangle[at->triangle], at->a, at->b, portal->side, true};
}

IncidentSampling PortalLight::incident_sampling(int requested) const {
    if (std::holds_alternative<SkyLight>(source)) return {requested, true};
    if (std::holds_alternative<SunLight>(source) && portal_index == 0) return {1, false};
    return {};
}

bool PortalLight::incident(const Vec3& p, const Vec3& n, double flux_lm, double u1, double u2, int count,
                           IncidentLight& in) const {
    if (const auto* sun = std::get_if<SunLight>(&source)) return sun->incident(p, n, flux_lm, u1, u2, count, in);
    const auto* sky = std::get_if<SkyLight>(&source);
    if (sky == nullptr) return false;
    // E = integral over the opening of L(w) cos_s cos_p / r^2 dA, w from p to the opening's
    // point: points uniform in area, each seen through the opening (its pane's
    // transmittance on the way) and with its sky not blocked beyond (the tracer's ray back out).
    const SurfacePick s = surface_point(portal->surface, u1, u2);
    const Vec3 v = s.point - p;
    const double d2 = glm::dot(v, v);
    in.distance_m = std::sqrt(d2);
    in.direction = v / in.distance_m;
    const double cos_s = glm::dot(n, in.direction), cos_p = glm::dot(in.direction, portal->outward);
    if (!(d2 > 0.0) || cos_s <= 0.0 || cos_p <= 0.0) return false;
    const double lum = sky->luminance_seen_cd_m2(in.direction);
    if (!(lum > 0.0)) return false;
    in.distant = false;
    in.end = s.point;
    in.end_margin = -1.0;
    in.beyond_opening = true;
    in.opening_outward = portal->outward;
    in.illuminance_lx = lum * cos_s * cos_p / d2 * (portal->surface.area_m2 / count);
    return true;
}

double PortalLight::luminance_seen_cd_m2(const Vec3& direction) const {
    const auto* sky = std::get_if<SkyLight>(&source);
    return sky != nullptr && portal_index == 0 ? sky->luminance_seen_cd_m2(direction) : 0.0;
}

LuminaireView PortalLight::view_from(const Vec3&, double) const { return not_a_luminaire(kDaylightIsNotALuminaire); }

std::optional<DaylightReference> PortalLight::daylight() const {
    if (const auto* sun = std::get_if<SunLight>(&source)) return sun->daylight();
    if (const auto* sky = std::get_if<SkyLight>(&source)) return sky->daylight();
    return std::nullopt;
}

bool PortalLight::source_lit() const {
    if (const auto* sun = std::get_if<SunLight>(&source)) return sun->illuminance_lx > 0.0;
    return std::holds_alternative<SkyLight>(source);
}

std::string PortalLight::why_dark() const {
    return std::holds_alternative<SunLight>(source) ? "the sun is behind the opening"
                                                    : "no sky or ground is seen through the opening";
}

void PortalLight::describe(std::ostream& out, double unobstructed_horizontal_lx) const {
    if (const auto* sun = std::get_if<SunLight>(&source)) sun->describe(out, unobstructed_horizontal_lx);
    if (const auto* sky = std::get_if<SkyLight>(&source)) sky->describe(out, unobstructed_horizontal_lx);
}

}  // namespace luxtrace
