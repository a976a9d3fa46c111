#include "luxtrace/light/point_light.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <stdexcept>

namespace luxtrace {

double PointLight::intensity_cd(const Vec3& out, double flux_lm) const {
    if (!distribution) return flux_lm / (4.0 * kPi);
    if (!photometry) throw std::logic_error("a point light's distribution without its photometry");
    // A luminous opening is seen as its centre here, in the pictures only.
    return photometry->intensity_cd(frame.to_local(out)) * (flux_lm / photometry->flux_lm());
}

bool PointLight::incident(const Vec3& p, const Vec3& n, double flux_lm, double, double, int, IncidentLight& in) const {
    return incident_from_point(
        position, p, n, [&](const Vec3& out) { return intensity_cd(out, flux_lm); }, in);
}

LuminaireView PointLight::view_from(const Vec3& eye, double flux_lm) const {
    LuminaireView v;
    v.placed = true;
    v.position = position;
    if (!photometry) {
        v.why_not = "it has no luminous area (only a point light with a photometric file's luminous opening has one)";
        return v;
    }
    // A photometric file's luminous opening; also when photons start from the point
    // (emission = "point"): the file still says how large the luminaire looks.
    const LuminousOpening& seen = opening.shape != LuminousOpening::Shape::point ? opening : photometry->opening;
    if (seen.shape == LuminousOpening::Shape::point) {
        v.why_not = "its photometric file gives no luminous opening";
        return v;
    }
    const Vec3 to_eye = eye - position;
    v.distance_m = glm::length(to_eye);
    if (!(v.distance_m > 0.0)) {
        v.why_not = "the eye is at its photometric centre";
        return v;
    }
    const Vec3 local = frame.to_local(to_eye / v.distance_m);
    v.intensity_cd = photometry->intensity_cd(local) * (flux_lm / photometry->flux_lm());
    v.projected_area_m2 = projected_area_m2(seen, local);
    if (!(v.projected_area_m2 > 0.0)) {
        v.why_not = "its luminous opening is seen edge-on";
        return v;
    }
    // The intensity divided by the area seen is the opening's mean luminance toward the
    // eye (uniform luminance, luminous_opening.hpp); omega is the small-source solid angle.
    v.luminance_cd_m2 = v.intensity_cd / v.projected_area_m2;
    v.solid_angle_sr = v.projected_area_m2 / (v.distance_m * v.distance_m);
    v.luminous = true;
    return v;
}

void PointLight::describe_photometry(std::ostream& out) const {
    if (!photometry) return;
    const Photometry& p = *photometry;
    out << " (" << p.format << ", " << shape_name(opening.shape) << "): table " << p.flux_lm() << " lm";
    if (p.stated_flux_lm > 0.0) out << ", file states " << p.stated_flux_lm << " lm (lamps x LORL)";
    else if (p.lamp_flux_lm > 0.0) out << ", lamps rated " << p.lamp_flux_lm << " lm";
    else out << ", absolute photometry";
    if (multiplier != 1.0) out << ", x multiplier " << multiplier;
    if (lamp_factor != 1.0) out << ", x lamp factor " << lamp_factor;
    if (tilt_factor != 1.0) out << ", x tilt " << tilt_factor;
}

}  // namespace luxtrace
