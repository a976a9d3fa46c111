#include "luxtrace/light/light.hpp"

namespace luxtrace {

EmittedRay Light::emit(double u_pos1, double u_pos2, double u_dir1, double u_dir2) const {
    return std::visit([&](const auto& k) { return k.emit(u_pos1, u_pos2, u_dir1, u_dir2); }, kind);
}

void Light::place(const Vec3& lo, const Vec3& hi) {
    const SceneSphere sphere = SceneSphere::around(lo, hi);
    std::visit(
        [&](auto& k) {
            if constexpr (requires { k.place(sphere); }) flux_lm = k.place(sphere);
        },
        kind);
}

IncidentSampling Light::incident_sampling(int requested) const {
    return std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.incident_sampling(requested); }) return k.incident_sampling(requested);
            else return IncidentSampling{};
        },
        kind);
}

bool Light::incident(const Vec3& p, const Vec3& n, double u1, double u2, int count, IncidentLight& in) const {
    return std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.incident(p, n, flux_lm, u1, u2, count, in); })
                return k.incident(p, n, flux_lm, u1, u2, count, in);
            else return false;
        },
        kind);
}

double Light::luminance_seen_cd_m2(const Vec3& direction) const {
    return std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.luminance_seen_cd_m2(direction); }) return k.luminance_seen_cd_m2(direction);
            else return 0.0;
        },
        kind);
}

std::optional<DaylightReference> Light::daylight() const {
    return std::visit(
        [](const auto& k) -> std::optional<DaylightReference> {
            if constexpr (requires { k.daylight(); }) return k.daylight();
            else return std::nullopt;
        },
        kind);
}

bool Light::may_be_dark() const {
    return std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.may_be_dark(flux_lm); }) return k.may_be_dark(flux_lm);
            else return false;
        },
        kind);
}

void Light::describe(std::ostream& out) const {
    std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.describe_photometry(out); }) k.describe_photometry(out);
        },
        kind);
    if (dimming != 1.0) out << ", dimmed to " << dimming;
    if (maintenance_factor != 1.0) out << ", MF " << maintenance_factor;
    std::visit(
        [&](const auto& k) {
            if constexpr (requires { k.describe(out, unobstructed_horizontal_lx); })
                k.describe(out, unobstructed_horizontal_lx);
        },
        kind);
}

std::optional<Light> Light::through_portal(const std::shared_ptr<const Portal>& portal, std::size_t index) const {
    std::optional<DaylightKind> source;
    if (const auto* sun = as<SunLight>()) source = *sun;
    else if (const auto* sky = as<SkyLight>()) source = *sky;
    else if (const auto* patch = as<SkyPatchLight>()) source = *patch;
    if (!source) return std::nullopt;
    Light l = *this;
    l.label = label + " through portal '" + portal->name + "'";
    l.kind = PortalLight::through(std::move(*source), portal, index, l.flux_lm);
    if (index > 0) l.unobstructed_horizontal_lx = 0.0;  // the sky's E_h,ext, counted once
    return l;
}

}  // namespace luxtrace
