#include "luxtrace/light/light.hpp"

#include "luxtrace/light/luminous_opening.hpp"
#include "luxtrace/light/portal.hpp"
#include "luxtrace/material/material.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

Vec3 sample_uniform_sphere(double u1, double u2) {
    const double z = 1.0 - 2.0 * u1;
    return unit_at_azimuth(std::sqrt(std::max(0.0, 1.0 - z * z)), z, u2);
}

Vec3 sample_uniform_cone(double cos_max, double u1, double u2) {
    // Uniform in solid angle: cos(theta) uniform in [cos_max, 1].
    const double z = 1.0 - u1 * (1.0 - cos_max);
    return unit_at_azimuth(std::sqrt(std::max(0.0, 1.0 - z * z)), z, u2);
}

Vec3 disk_point(double radius, double u1, double u2) {
    const double r = radius * std::sqrt(u1);
    const double phi = 2.0 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), 0.0};
}

namespace {
// disk_point with the angle's sine and cosine taken in float, as unit_at_azimuth does:
// positions good to 1e-7 of the radius (what Embree's float origins keep), at a fraction
// of the double calls' cost; for the sky's per-photon disks.
Vec3 disk_point_f(double radius, double u1, double u2) {
    const double r = radius * std::sqrt(u1);
    const float phi = static_cast<float>(2.0 * kPi * u2);
    return {r * static_cast<double>(std::cos(phi)), r * static_cast<double>(std::sin(phi)), 0.0};
}
}  // namespace

std::size_t sample_cdf(const std::vector<double>& cdf, double u) {
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return std::min<std::size_t>(static_cast<std::size_t>(it - cdf.begin()), cdf.size() - 1);
}

SurfacePick surface_point(const EmitterSurface& surface, double u1, double u2) {
    // Pick a triangle by area, then a uniform point in it (folded square sampling).
    const std::size_t i = sample_cdf(surface.cdf, u1);
    const double lo = i == 0 ? 0.0 : surface.cdf[i - 1];
    const double width = surface.cdf[i] - lo;
    double a = width > 0.0 ? std::clamp((u1 - lo) / width, 0.0, 1.0) : 0.5;
    double b = u2;
    if (a + b > 1.0) {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    const Vec3 p = surface.p0[i] + a * surface.e1[i] + b * surface.e2[i];
    return {i, a, b, p};
}

EmittedRay Light::emit_through_portal(const Vec3& direction, double up1, double up2) const {
    const SurfacePick s = surface_point(portal->surface, up1, up2);
    return {s.point, direction, portal->surface.scene_triangle[s.triangle], s.a, s.b, portal->side, true};
}

EmittedRay Light::emit_through_portal_disk(const Vec3& d, double up1, double up2) const {
    EmittedRay missed;
    missed.direction = d;
    missed.missed = true;
    const double facing = glm::dot(d, portal->outward);  // < 0: travelling inward
    if (!(facing < 0.0)) return missed;
    // A point on the disk through the centroid perpendicular to d, slid along d onto the
    // opening's plane.
    const Vec3 q = beam_center + Frame::around(d).to_world(disk_point(beam_radius, up1, up2));
    const Vec3 x = q + (glm::dot(beam_center - q, portal->outward) / facing) * d;
    const EmitterSurface& s = portal->surface;
    for (std::size_t i = 0; i < s.p0.size(); ++i) {
        // x = p0 + a e1 + b e2 in the triangle's plane.
        const Vec3 w = x - s.p0[i];
        const double d11 = glm::dot(s.e1[i], s.e1[i]), d12 = glm::dot(s.e1[i], s.e2[i]);
        const double d22 = glm::dot(s.e2[i], s.e2[i]);
        const double w1 = glm::dot(w, s.e1[i]), w2 = glm::dot(w, s.e2[i]);
        const double det = d11 * d22 - d12 * d12;
        if (!(det > 0.0)) continue;
        const double a = (w1 * d22 - w2 * d12) / det, b = (w2 * d11 - w1 * d12) / det;
        if (a >= 0.0 && b >= 0.0 && a + b <= 1.0) return {x, d, s.scene_triangle[i], a, b, portal->side, true};
    }
    return missed;
}

EmittedRay Light::emit(double up1, double up2, double ud1, double ud2) const {
    switch (type) {
    case LightType::point:
        if (distribution) {
            const Vec3 d = distribution->sample(ud1, ud2);
            Vec3 origin = position;  // where on the opening depends on d (luminous_opening.hpp)
            if (opening.shape != LuminousOpening::Shape::point)
                origin += frame.to_world(sample_opening_point(opening, d, up1, up2));
            return {origin, frame.to_world(d)};
        }
        return {position, sample_uniform_sphere(ud1, ud2)};
    case LightType::spot: return {position, frame.to_world(sample_uniform_cone(cos_half_angle, ud1, ud2))};
    case LightType::area: {
        // A Lambertian direction from the point's front side.
        const SurfacePick s = surface_point(surface, up1, up2);
        return {s.point, sample_cosine_hemisphere(surface.normal[s.triangle], ud1, ud2),
                surface.scene_triangle[s.triangle], s.a, s.b};
    }
    case LightType::directional: return {beam_center + frame.to_world(disk_point(beam_radius, up1, up2)), aim};
    case LightType::sun:
        if (portal) return emit_through_portal(frame.to_world(sample_uniform_cone(cos_half_angle, ud1, ud2)), up1, up2);
        return {beam_center + frame.to_world(disk_point(beam_radius, up1, up2)),
                frame.to_world(sample_uniform_cone(cos_half_angle, ud1, ud2))};
    case LightType::sky: {
        if (portal) return emit_through_portal(-portal_sky->sample(ud1, ud2), up1, up2);
        // Travel away from the sky element, starting on the disk that covers the scene's
        // sphere as seen from that direction.
        const Vec3 d = -horizon.to_world(sky->sample(ud1, ud2));
        return {beam_center - 1.01 * beam_radius * d + Frame::around(d).to_world(disk_point_f(beam_radius, up1, up2)),
                d};
    }
    case LightType::sky_patch: {
        // Uniform in solid angle: sin(altitude) and azimuth uniform over the patch.
        const double mu = patch.mu_lo + ud1 * (patch.mu_hi - patch.mu_lo);
        const double az = patch.az_lo_rad + ud2 * patch.az_width_rad;
        const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
        const Vec3 d = -horizon.to_world(Vec3(s * std::sin(az), s * std::cos(az), mu));
        if (portal) return emit_through_portal_disk(d, up1, up2);
        return {beam_center - 1.01 * beam_radius * d + Frame::around(d).to_world(disk_point_f(beam_radius, up1, up2)),
                d};
    }
    }
    return {};
}

LightSet::LightSet(std::vector<Light> lights) : lights_(std::move(lights)) {
    double sum = 0.0;
    for (const Light& l : lights_) {
        sum += l.flux_lm;
        light_cdf_.push_back(sum);
        std::vector<double> bands;
        double s = 0.0;
        for (double share : l.band_share) bands.push_back(s += share);
        for (double& v : bands) v /= s;
        band_cdf_.push_back(std::move(bands));
    }
    total_flux_lm_ = sum;
    double mf = 0.0;
    for (const Light& l : lights_) {
        mf += l.maintenance_factor * l.flux_lm;
        maintenance_factor_uniform_ = maintenance_factor_uniform_ &&
                                      std::abs(l.maintenance_factor - lights_.front().maintenance_factor) <= 1e-12;
    }
    if (sum > 0.0) maintenance_factor_ = mf / sum;
    for (double& v : light_cdf_) v /= sum;
}

namespace {
// sample_cdf for the few entries of a light or band table: a scan, same answer.
std::size_t scan_cdf(const std::vector<double>& cdf, double u) {
    std::size_t i = 0;
    while (i + 1 < cdf.size() && cdf[i] <= u) ++i;
    return i;
}
}  // namespace

std::size_t LightSet::pick_light(double u) const {
    return light_cdf_.size() <= 16 ? scan_cdf(light_cdf_, u) : sample_cdf(light_cdf_, u);
}

int LightSet::pick_band(std::size_t light, double u) const {
    return static_cast<int>(scan_cdf(band_cdf_[light], u));  // at most a few bands
}

}  // namespace luxtrace
