#include "luxtrace/scene/radiance_materials.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/material/glazing.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {
namespace {

// Per band of the scene, from an RGB triple.
std::vector<double> to_bands(const double rgb[3], const std::vector<std::string>& bands) {
    if (bands.size() == 1)
        return {kRadianceLuminanceWeights[0] * rgb[0] + kRadianceLuminanceWeights[1] * rgb[1] +
                kRadianceLuminanceWeights[2] * rgb[2]};
    return {rgb[0], rgb[1], rgb[2]};
}

std::string list(const std::vector<double>& v) {
    std::string s;
    for (const double x : v) s += (s.empty() ? "" : " ") + detail::fmt_number(x);
    return s;
}

}  // namespace

std::string RadianceMapping::describe() const {
    std::string s = material.name + " -> ";
    switch (role) {
    case RadianceRole::ignored: s += "not a material (ignored)"; break;
    case RadianceRole::light: s += "light, luminance " + list(luminance_cd_m2) + " cd/m2"; break;
    case RadianceRole::portal: s += "daylight portal; "; [[fallthrough]];
    case RadianceRole::surface:
        switch (material.type) {
        case MaterialType::black: s += "black"; break;
        case MaterialType::glazing:
            s += "glazing, transmittance " + list(material.transmittance) + ", index " +
                 detail::fmt_number(material.ior);
            break;
        case MaterialType::glass: s += "glass, index " + detail::fmt_number(material.ior); break;
        case MaterialType::mirror: s += "mirror, specular reflectance " + list(material.specular_reflectance); break;
        default:
            s += "diffuse reflectance " + list(material.diffuse_reflectance) + ", specular " +
                 list(material.specular_reflectance) +
                 (material.roughness > 0.0 ? " (roughness " + detail::fmt_number(material.roughness) + ")" : "") +
                 ", diffuse transmittance " + list(material.diffuse_transmittance) + ", specular transmittance " +
                 list(material.specular_transmittance);
        }
    }
    for (const std::string& n : notes) s += "; " + n;
    return s;
}

RadianceMapping map_radiance_modifier(const RadianceModel& model, std::size_t index,
                                      const std::vector<std::string>& bands) {
    const RadianceModifier& m = model.modifiers.at(index);
    const std::string where = model.where(m.at) + ": modifier '" + m.name + "' (" + m.type + ")";
    const bool y = bands.size() == 1 && bands[0] == "Y";
    const bool rgb = bands == std::vector<std::string>{"R", "G", "B"};
    if (!y && !rgb) throw InputError(where + ": a Radiance model needs bands [\"Y\"] or [\"R\", \"G\", \"B\"]");
    RadianceMapping out;
    out.material.name = m.name;
    const std::size_t nb = bands.size();
    auto colour = [&](std::size_t first) {
        double c[3] = {m.reals.at(first), m.reals.at(first + 1), m.reals.at(first + 2)};
        for (double& x : c) {
            if (x < 0.0) throw InputError(where + ": a negative colour component (" + detail::fmt_number(x) + ")");
            if (x > 1.0) {
                out.notes.push_back("colour component " + detail::fmt_number(x) + " above 1 taken as 1");
                x = 1.0;
            }
        }
        return to_bands(c, bands);
    };
    auto scaled = [](std::vector<double> v, double f) {
        for (double& x : v) x *= f;
        return v;
    };
    auto unit_fraction = [&](double x, const char* what) {
        if (x < 0.0 || x > 1.0) {
            out.notes.push_back(std::string(what) + " " + detail::fmt_number(x) + " clamped to [0, 1]");
            return std::clamp(x, 0.0, 1.0);
        }
        return x;
    };
    auto roughness = [&](double rough, double spec) {
        if (!(spec > 0.0)) return;
        if (rough > WardLobe::kMaxRoughness) {
            out.notes.push_back("roughness " + detail::fmt_number(rough) + " above " +
                                detail::fmt_number(WardLobe::kMaxRoughness) + " taken as " +
                                detail::fmt_number(WardLobe::kMaxRoughness));
            rough = WardLobe::kMaxRoughness;
        }
        out.material.set_roughness(std::max(0.0, rough));
    };
    if (!m.read_as.empty()) out.notes.push_back("read as " + m.type + " from " + m.read_as + " (isotropic)");
    const std::string& t = m.type;
    if (t == "plastic" || t == "metal") {
        // Radiance: diffuse (1 - spec) colour; specular spec, white for plastic, coloured for
        // metal; the specular part a Ward lobe of the roughness.
        const std::vector<double> c = colour(0);
        const double spec = unit_fraction(m.reals[3], "specularity");
        out.material.type = MaterialType::general;
        out.material.diffuse_reflectance = scaled(c, 1.0 - spec);
        out.material.specular_reflectance = t == "plastic" ? std::vector<double>(nb, spec) : scaled(c, spec);
        out.material.diffuse_transmittance.assign(nb, 0.0);
        out.material.specular_transmittance.assign(nb, 0.0);
        roughness(m.reals[4], spec);
        if (t == "plastic" && spec > 0.0)
            out.notes.push_back("specular reflectance constant over incidence (Radiance adds a Fresnel rise at "
                                "grazing angles)");
    } else if (t == "trans") {
        // Radiance's trans: Rd = c (1 - s)(1 - t), Rs = s, Td = c (1 - s) t (1 - ts),
        // Ts = c (1 - s) t ts; the specular transmission goes straight through.
        const std::vector<double> c = colour(0);
        const double s = unit_fraction(m.reals[3], "specularity");
        const double tr = unit_fraction(m.reals[5], "transmissivity");
        const double ts = unit_fraction(m.reals[6], "transmitted specularity");
        out.material.type = MaterialType::general;
        out.material.diffuse_reflectance = scaled(c, (1.0 - s) * (1.0 - tr));
        out.material.specular_reflectance.assign(nb, s);
        out.material.diffuse_transmittance = scaled(c, (1.0 - s) * tr * (1.0 - ts));
        out.material.specular_transmittance = scaled(c, (1.0 - s) * tr * ts);
        roughness(m.reals[4], s);
        if (m.reals[4] > 0.0 && ts > 0.0)
            out.notes.push_back("specular transmission straight through (Radiance spreads it by the roughness)");
    } else if (t == "mirror") {
        out.material.type = MaterialType::mirror;
        out.material.specular_reflectance = colour(0);
        if (!m.strings.empty() && m.strings[0] != "void")
            out.notes.push_back("the alternate material '" + m.strings[0] + "' for rays not from sources ignored");
    } else if (t == "glass") {
        // Radiance gives the transmissivity tn (one pass through the glass); luxtrace's
        // glazing takes the pane's normal transmittance, that of a pane of transmissivity tn
        // (glazing.hpp: T = (1 - r0)^2 tn / (1 - r0^2 tn^2)).
        const std::vector<double> tn = colour(0);
        double ior = m.reals.size() > 3 ? m.reals[3] : 1.52;
        if (!(ior > 0.0))
            throw InputError(where + ": the refractive index must be positive, not " + detail::fmt_number(ior));
        // The pane's curve is exact for indices in [1.2, 3] (glazing.hpp), as a TOML
        // glazing's refractive_index; at 1 and below it has no value at grazing incidence.
        if (ior < 1.2 || ior > 3.0) {
            const double taken = std::clamp(ior, 1.2, 3.0);
            out.notes.push_back("refractive index " + detail::fmt_number(ior) + " outside [1.2, 3] taken as " +
                                detail::fmt_number(taken));
            ior = taken;
        }
        out.material.type = MaterialType::glazing;
        out.material.ior = ior;
        auto curves = std::make_shared<std::vector<GlazingCurve>>();
        for (const double tau : tn) {
            const double tt = pane_optics(1.0, ior, tau).transmittance;
            out.material.transmittance.push_back(tt);
            curves->push_back(pane_curve(std::clamp(tt, 1e-9, max_pane_transmittance(ior)), ior));
        }
        out.material.glazing = std::move(curves);
    } else if (t == "dielectric") {
        if (!(m.reals[3] > 0.0))
            throw InputError(where + ": the refractive index must be positive, not " + detail::fmt_number(m.reals[3]));
        out.material.type = MaterialType::glass;
        out.material.ior = m.reals[3];
        out.material.transmittance.assign(nb, 1.0);
        const std::vector<double> tn = colour(0);
        if (std::any_of(tn.begin(), tn.end(), [](double x) { return x < 1.0; }))
            out.notes.push_back("absorption per metre (" + list(tn) + ") ignored: clear glass");
        if (m.reals[4] != 0.0) out.notes.push_back("Hartmann constant ignored (no dispersion)");
    } else if (t == "light" || t == "glow" || t == "spotlight") {
        out.role = RadianceRole::light;
        out.material.type = MaterialType::black;
        double c[3] = {m.reals[0], m.reals[1], m.reals[2]};
        for (const double x : c)
            if (x < 0.0) throw InputError(where + ": a negative radiance (" + detail::fmt_number(x) + ")");
        // Bands sum to the photometric total (as a [[light]]'s colour shares do): R, G, B
        // carry each channel's part of the luminance, w_c c_c.
        if (bands.size() == 3)
            for (int k = 0; k < 3; ++k) c[k] *= kRadianceLuminanceWeights[k];
        out.luminance_cd_m2 = scaled(to_bands(c, bands), kRadianceEfficacy_lm_per_W);
        if (t == "glow") out.notes.push_back("glow's radius of influence ignored: a light everywhere");
        if (t == "spotlight") out.notes.push_back("spotlight cone ignored: a Lambertian emitter");
    } else if (t == "illum") {
        out.role = RadianceRole::portal;
        out.material.type = MaterialType::glass;
        out.material.ior = 1.0;  // an opening: every photon passes
        out.material.transmittance.assign(nb, 1.0);
        if (!m.strings.empty() && m.strings[0] != "void")
            out.notes.push_back("the material '" + m.strings[0] + "' behind the illum is not used: an open portal");
    } else {
        out.role = RadianceRole::ignored;
    }
    return out;
}

}  // namespace luxtrace
