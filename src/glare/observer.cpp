#include "luxtrace/glare/observer.hpp"

#include "luxtrace/glare/ugr.hpp"
#include "luxtrace/light/light.hpp"
#include "luxtrace/light/luminous_opening.hpp"

#include <cmath>
#include <sstream>

namespace luxtrace {

void Observer::finalize() {
    view_direction = glm::normalize(view_direction);
    up = glm::normalize(Vec3(0, 0, 1) - view_direction.z * view_direction);
    right = glm::cross(view_direction, up);
}

namespace {

constexpr double kDeg = 180.0 / kPi;
// CIE 117's table of Guth's position index covers H/R up to 1.9 and T/R up to 3.
constexpr double kMaxHOverR = 1.9;
constexpr double kMaxTOverR = 3.0;

std::string fmt(double v) {
    std::ostringstream os;
    os.precision(4);
    os << v;
    return os.str();
}

// The luminous area and intensity of one light toward the eye; false when it has none.
bool luminous_terms(const Light& l, const Vec3& eye, GlareSource& s, std::string& why) {
    if (l.type == LightType::area) {
        // Lambertian from the front side: L = flux / (pi A) wherever it is seen; the
        // triangles turned toward the eye add their projected areas and solid angles.
        const EmitterSurface& e = l.surface;
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
        s.position = centre / area;
        s.distance_m = glm::length(eye - s.position);
        if (!(projected > 0.0)) {
            why = "its emitting side faces away from the eye";
            return false;
        }
        s.luminance_cd_m2 = l.flux_lm / (kPi * e.area_m2);
        s.projected_area_m2 = projected;
        s.intensity_cd = s.luminance_cd_m2 * projected;
        s.solid_angle_sr = omega;
        return true;
    }
    if (l.beam()) {
        why = l.type == LightType::directional ? "a directional beam is not a luminaire (CIE 117 rates luminaires)"
                                               : "daylight is not a luminaire (CIE 117 rates luminaires)";
        return false;
    }
    if (l.type == LightType::spot || !l.photometry) {
        why = "it has no luminous area (only a point light with a photometric file's luminous opening has one)";
        return false;
    }
    // A photometric file's luminous opening; also when photons start from the point
    // (emission = "point"): the file still says how large the luminaire looks.
    const LuminousOpening& opening = l.opening.shape != LuminousOpening::Shape::point ? l.opening
                                                                                      : l.photometry->opening;
    if (opening.shape == LuminousOpening::Shape::point) {
        why = "its photometric file gives no luminous opening";
        return false;
    }
    s.position = l.position;
    const Vec3 to_eye = eye - l.position;
    s.distance_m = glm::length(to_eye);
    if (!(s.distance_m > 0.0)) {
        why = "the eye is at its photometric centre";
        return false;
    }
    const Vec3 local = l.frame.to_local(to_eye / s.distance_m);
    s.intensity_cd = l.photometry->intensity_cd(local) * (l.flux_lm / l.photometry->flux_lm());
    s.projected_area_m2 = projected_area_m2(opening, local);
    if (!(s.projected_area_m2 > 0.0)) {
        why = "its luminous opening is seen edge-on";
        return false;
    }
    // The intensity divided by the area seen is the opening's mean luminance toward the
    // eye (uniform luminance, luminous_opening.hpp); omega is the small-source solid angle.
    s.luminance_cd_m2 = s.intensity_cd / s.projected_area_m2;
    s.solid_angle_sr = s.projected_area_m2 / (s.distance_m * s.distance_m);
    return true;
}

}  // namespace

std::vector<GlareSource> glare_sources(Observer& o, const LightSet& lights) {
    std::vector<GlareSource> out;
    const std::string who = "observer '" + o.name + "': ";
    for (std::size_t i = 0; i < lights.lights().size(); ++i) {
        const Light& l = lights.lights()[i];
        GlareSource s;
        s.light = i;
        s.label = l.label;
        std::string why;
        const bool luminous = luminous_terms(l, o.position, s, why);
        if (!luminous && l.type != LightType::area) {
            // Lights that cannot be placed in the field are left out of the sum; say so
            // only for those in front of the eye, the others could not count anyway.
            const bool behind = glm::dot(l.position - o.position, o.view_direction) <= 0.0;
            if (!l.beam() && behind) continue;
            o.notes.push_back(who + l.label + " is left out of UGR: " + why);
            continue;
        }
        // Field of view and Guth's angles, from the centre of the luminous area.
        const Vec3 v = s.position - o.position;
        const double R = glm::dot(v, o.view_direction), H = glm::dot(v, o.up), T = glm::dot(v, o.right);
        if (!(R > 0.0) || H < 0.0 || H > kMaxHOverR * R || std::abs(T) > kMaxTOverR * R) continue;
        if (!luminous) {
            o.notes.push_back(who + l.label + " is left out of UGR: " + why);
            continue;
        }
        s.beta_deg = std::atan2(std::hypot(H, T), R) * kDeg;
        s.alpha_deg = (H == 0.0 && T == 0.0) ? 0.0 : std::atan2(std::abs(T), H) * kDeg;
        s.position_index = guth_position_index(s.alpha_deg, s.beta_deg);
        if (s.solid_angle_sr < kUgrMinSolidAngleSr || s.solid_angle_sr > kUgrMaxSolidAngleSr)
            o.notes.push_back(who + l.label + " subtends " + fmt(s.solid_angle_sr) +
                              " sr, outside CIE 117's range for UGR (0.0003 to 0.1 sr)");
        out.push_back(s);
    }
    return out;
}

}  // namespace luxtrace
