#include "luxtrace/material/material.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

namespace luxtrace {

double fresnel_dielectric(double cos_i, double eta) {
    cos_i = std::clamp(cos_i, 0.0, 1.0);
    const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0) return 1.0;  // total internal reflection
    const double cos_t = std::sqrt(1.0 - sin2_t);
    const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

Vec3 sample_cosine_hemisphere(const Vec3& n, double u1, double u2) {
    // Uniform point on the unit disk, lifted to the hemisphere: pdf = cos(theta) / pi.
    return Frame::around(n).to_world(unit_at_azimuth(std::sqrt(u1), std::sqrt(std::max(0.0, 1.0 - u1)), u2));
}

namespace {

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - 2.0 * glm::dot(d, n) * n; }

double at(const std::vector<double>& v, int band) { return v.empty() ? 0.0 : v[static_cast<size_t>(band)]; }

// The specular reflection chosen by u in [lo, hi): the mirror direction, or with a lobe a
// direction from it with probability a(cos_i), (u - lo) / (hi - lo) deciding (ward_lobe.hpp).
Scattered specular(const WardLobe* lobe, const Vec3& dir, const Vec3& n, double u, double lo, double hi, double u1,
                   double u2) {
    if (lobe == nullptr) return {ScatterEvent::specular_reflection, reflect(dir, n), 1};
    const std::optional<Vec3> d = lobe->reflect(dir, n, (u - lo) / (hi - lo), u1, u2);
    if (!d) return {};
    return {ScatterEvent::specular_reflection, *d, 1};
}

}  // namespace

void Material::set_roughness(double alpha) {
    roughness = alpha;
    lobe = alpha > 0.0 ? std::make_shared<const WardLobe>(alpha) : nullptr;
}

ScatterModel scatter_model(const Material& m, int band) {
    ScatterModel s;
    s.type = m.type;
    switch (m.type) {
    case MaterialType::black: break;
    case MaterialType::diffuse: s.diffuse_reflection = at(m.diffuse_reflectance, band); break;
    case MaterialType::mirror:
        s.specular_reflection = at(m.specular_reflectance, band);
        s.lobe = m.lobe.get();
        break;
    case MaterialType::general:
        s.lobe = m.lobe.get();
        s.diffuse_reflection = at(m.diffuse_reflectance, band);
        s.specular_reflection = s.diffuse_reflection + at(m.specular_reflectance, band);
        s.diffuse_transmission = s.specular_reflection + at(m.diffuse_transmittance, band);
        s.specular_transmission = s.diffuse_transmission + at(m.specular_transmittance, band);
        break;
    case MaterialType::glass:
        s.ior = m.ior;
        s.transmittance = m.transmittance.empty() ? 1.0 : at(m.transmittance, band);
        break;
    case MaterialType::glazing:
        if (m.glazing) s.glazing = &(*m.glazing)[static_cast<size_t>(band)];
        break;
    }
    return s;
}

Scattered scatter(const ScatterModel& m, const Vec3& dir, const Vec3& ng, double u, double u1, double u2) {
    // Normal on the side the photon arrives from.
    const bool from_front = glm::dot(dir, ng) < 0.0;
    const Vec3 n = from_front ? ng : -ng;
    Scattered s;
    switch (m.type) {
    case MaterialType::black: return s;
    case MaterialType::diffuse:
        if (u < m.diffuse_reflection) s = {ScatterEvent::diffuse_reflection, sample_cosine_hemisphere(n, u1, u2), 1};
        return s;
    case MaterialType::mirror:
        if (u < m.specular_reflection) s = specular(m.lobe, dir, n, u, 0.0, m.specular_reflection, u1, u2);
        return s;
    case MaterialType::general:
        if (u < m.diffuse_reflection) return {ScatterEvent::diffuse_reflection, sample_cosine_hemisphere(n, u1, u2), 1};
        if (u < m.specular_reflection)
            return specular(m.lobe, dir, n, u, m.diffuse_reflection, m.specular_reflection, u1, u2);
        if (u < m.diffuse_transmission)
            return {ScatterEvent::diffuse_transmission, sample_cosine_hemisphere(-n, u1, u2), -1};
        if (u < m.specular_transmission) return {ScatterEvent::specular_transmission, dir, -1};
        return s;
    case MaterialType::glass: {
        // Entering through the front side goes from air (1) into glass (ior).
        // Index 1 is no interface: an opening's surface that blocks nothing (a portal's
        // hole, docs/DAYLIGHT.md), crossed straight, so its light stays direct.
        if (m.ior == 1.0) {
            if (u < m.transmittance) return {ScatterEvent::specular_transmission, dir, -1};
            return s;
        }
        const double eta = from_front ? 1.0 / m.ior : m.ior;
        const double cos_i = -glm::dot(dir, n);
        const double r = fresnel_dielectric(cos_i, eta);
        if (u < r) return {ScatterEvent::specular_reflection, reflect(dir, n), 1};
        if (u >= r + (1.0 - r) * m.transmittance) return s;  // absorbed in the crossing
        const double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
        const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin2_t));
        const Vec3 refracted = glm::normalize(eta * dir + (eta * cos_i - cos_t) * n);
        return {ScatterEvent::refraction, refracted, -1};
    }
    case MaterialType::glazing: {
        // A thin pane, alike from both sides: mirror reflection or straight through.
        if (m.glazing == nullptr) return s;
        const PaneOptics o = m.glazing->at(-glm::dot(dir, n));
        if (u < o.reflectance) return {ScatterEvent::specular_reflection, reflect(dir, n), 1};
        if (u < o.reflectance + o.transmittance) return {ScatterEvent::specular_transmission, dir, -1};
        return s;
    }
    }
    return s;
}

double albedo(const Material& m, int band) {
    switch (m.type) {
    case MaterialType::black: return 0.0;
    case MaterialType::diffuse: return at(m.diffuse_reflectance, band);
    case MaterialType::mirror: return at(m.specular_reflectance, band) * (m.lobe ? m.lobe->albedo(1.0) : 1.0);
    case MaterialType::general:
        return at(m.diffuse_reflectance, band) +
               at(m.specular_reflectance, band) * (m.lobe ? m.lobe->albedo(1.0) : 1.0) +
               at(m.diffuse_transmittance, band) + at(m.specular_transmittance, band);
    case MaterialType::glass:
        return m.transmittance.empty() ? 1.0
                                       : std::max(fresnel_dielectric(1.0, 1.0 / m.ior), 0.0) +
                                             (1.0 - fresnel_dielectric(1.0, 1.0 / m.ior)) * at(m.transmittance, band);
    case MaterialType::glazing: {
        if (!m.glazing) return 0.0;
        const PaneOptics o = (*m.glazing)[static_cast<size_t>(band)].at(1.0);
        return o.reflectance + o.transmittance;
    }
    }
    return 0.0;
}

}  // namespace luxtrace
