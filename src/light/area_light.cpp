#include "luxtrace/light/area_light.hpp"

#include "luxtrace/material/material.hpp"

namespace luxtrace {

bool AreaLight::incident(const Vec3& p, const Vec3& n, double flux_lm, double u1, double u2, int count,
                         IncidentLight& in) const {
    // Points uniform in area: E = sum (M/pi) cos_s cos_e / d^2 * A / N over unshadowed points.
    const SurfacePick s = surface_point(surface, u1, u2);
    const Vec3 v = s.point - p;
    const double d2 = glm::dot(v, v);
    in.distance_m = std::sqrt(d2);
    in.direction = v / in.distance_m;
    const double cos_s = glm::dot(n, in.direction), cos_e = -glm::dot(surface.normal[s.triangle], in.direction);
    if (!(d2 > 0.0) || cos_s <= 0.0 || cos_e <= 0.0) return false;
    in.distant = false;
    in.end = s.point;
    in.end_margin = 2.0;
    in.illuminance_lx = flux_lm / kPi / count * (cos_s * cos_e / d2);
    return true;
}

LuminaireView AreaLight::view_from(const Vec3& eye, double flux_lm) const {
    // Lambertian from the front side: L = flux / (pi A) wherever it is seen; the triangles
    // turned toward the eye add their projected areas and solid angles.
    const EmitterSurface& e = surface;
    Vec3 centre(0.0);
    double area = 0.0, projected = 0.0, omega = 0.0;
    for (std::size_t t = 0; t < e.p0.size(); ++t) {
        const double a = 0.5 * glm::length(glm::cross(e.e1[t], e.e2[t]));
        const Vec3 c = e.p0[t] + (e.e1[t] + e.e2[t]) / 3.0;
        centre += a * c;
        area += a;
        const Vec3 to_eye = eye - c;
        const double r = glm::length(to_eye);
        const double cosine = r > 0.0 ? glm::dot(e.normal[t], to_eye) / r : 0.0;
        if (cosine <= 0.0) continue;
        projected += a * cosine;
        omega += a * cosine / (r * r);
    }
    LuminaireView v;
    v.placed = true;
    v.field_test_when_dark = true;
    v.position = centre / area;
    v.distance_m = glm::length(eye - v.position);
    if (!(projected > 0.0)) {
        v.why_not = "its emitting side faces away from the eye";
        return v;
    }
    v.luminance_cd_m2 = luminance_cd_m2(flux_lm);
    v.projected_area_m2 = projected;
    v.intensity_cd = v.luminance_cd_m2 * projected;
    v.solid_angle_sr = omega;
    v.luminous = true;
    return v;
}

}  // namespace luxtrace
