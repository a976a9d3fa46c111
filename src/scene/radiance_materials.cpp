#include "luxtrace/scene/radiance_materials.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/material/glazing.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>

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

// One modifier being mapped: what the mapping of each type needs, and the result with its
// notes.
struct Mapper {
    const RadianceModifier& m;
    const std::string where;  // "file:line: modifier 'NAME' (TYPE)", for errors
    const std::vector<std::string>& bands;
    RadianceMapping out;

    std::size_t nb() const { return bands.size(); }

    // Reals first..first+2 as a colour per band; components above 1 are taken as 1.
    std::vector<double> colour(std::size_t first) {
        double c[3] = {m.reals.at(first), m.reals.at(first + 1), m.reals.at(first + 2)};
        for (double& x : c) {
            if (x < 0.0) throw InputError(where + ": a negative colour component (" + detail::fmt_number(x) + ")");
            if (x > 1.0) {
                out.notes.push_back("colour component " + detail::fmt_number(x) + " above 1 taken as 1");
                x = 1.0;
            }
        }
        return to_bands(c, bands);
    }

    double unit_fraction(double x, const char* what) {
        if (x < 0.0 || x > 1.0) {
            out.notes.push_back(std::string(what) + " " + detail::fmt_number(x) + " clamped to [0, 1]");
            return std::clamp(x, 0.0, 1.0);
        }
        return x;
    }

    // The specular lobe's roughness, when there is a specular part.
    void roughness(double rough, double spec) {
        if (!(spec > 0.0)) return;
        if (rough > WardLobe::kMaxRoughness) {
            out.notes.push_back("roughness " + detail::fmt_number(rough) + " above " +
                                detail::fmt_number(WardLobe::kMaxRoughness) + " taken as " +
                                detail::fmt_number(WardLobe::kMaxRoughness));
            rough = WardLobe::kMaxRoughness;
        }
        out.material.set_roughness(std::max(0.0, rough));
    }
};

std::vector<double> scaled(std::vector<double> v, double f) {
    for (double& x : v) x *= f;
    return v;
}

// Radiance: diffuse (1 - spec) colour; specular spec, white for plastic, coloured for
// metal; the specular part a Ward lobe of the roughness.
void map_plastic_or_metal(Mapper& c) {
    const RadianceModifier& m = c.m;
    const bool plastic = m.type == "plastic";
    const std::vector<double> colour = c.colour(0);
    const double spec = c.unit_fraction(m.reals[3], "specularity");
    Material& mat = c.out.material;
    mat.type = MaterialType::general;
    mat.diffuse_reflectance = scaled(colour, 1.0 - spec);
    mat.specular_reflectance = plastic ? std::vector<double>(c.nb(), spec) : scaled(colour, spec);
    mat.diffuse_transmittance.assign(c.nb(), 0.0);
    mat.specular_transmittance.assign(c.nb(), 0.0);
    c.roughness(m.reals[4], spec);
    if (plastic && spec > 0.0)
        c.out.notes.push_back("specular reflectance constant over incidence (Radiance adds a Fresnel rise at "
                              "grazing angles)");
}

// Radiance's trans: Rd = c (1 - s)(1 - t), Rs = s, Td = c (1 - s) t (1 - ts),
// Ts = c (1 - s) t ts; the specular transmission goes straight through.
void map_trans(Mapper& c) {
    const RadianceModifier& m = c.m;
    const std::vector<double> colour = c.colour(0);
    const double s = c.unit_fraction(m.reals[3], "specularity");
    const double tr = c.unit_fraction(m.reals[5], "transmissivity");
    const double ts = c.unit_fraction(m.reals[6], "transmitted specularity");
    Material& mat = c.out.material;
    mat.type = MaterialType::general;
    mat.diffuse_reflectance = scaled(colour, (1.0 - s) * (1.0 - tr));
    mat.specular_reflectance.assign(c.nb(), s);
    mat.diffuse_transmittance = scaled(colour, (1.0 - s) * tr * (1.0 - ts));
    mat.specular_transmittance = scaled(colour, (1.0 - s) * tr * ts);
    c.roughness(m.reals[4], s);
    if (m.reals[4] > 0.0 && ts > 0.0)
        c.out.notes.push_back("specular transmission straight through (Radiance spreads it by the roughness)");
}

void map_mirror(Mapper& c) {
    c.out.material.type = MaterialType::mirror;
    c.out.material.specular_reflectance = c.colour(0);
    if (!c.m.strings.empty() && c.m.strings[0] != "void")
        c.out.notes.push_back("the alternate material '" + c.m.strings[0] + "' for rays not from sources ignored");
}

// Radiance gives the transmissivity tn (one pass through the glass); luxtrace's glazing
// takes the pane's normal transmittance, that of a pane of transmissivity tn
// (glazing.hpp: T = (1 - r0)^2 tn / (1 - r0^2 tn^2)).
void map_glass(Mapper& c) {
    const std::vector<double> tn = c.colour(0);
    double ior = c.m.reals.size() > 3 ? c.m.reals[3] : 1.52;
    if (!(ior > 0.0))
        throw InputError(c.where + ": the refractive index must be positive, not " + detail::fmt_number(ior));
    // The pane's curve is exact for indices in [1.2, 3] (glazing.hpp), as a TOML
    // glazing's refractive_index; at 1 and below it has no value at grazing incidence.
    if (ior < 1.2 || ior > 3.0) {
        const double taken = std::clamp(ior, 1.2, 3.0);
        c.out.notes.push_back("refractive index " + detail::fmt_number(ior) + " outside [1.2, 3] taken as " +
                              detail::fmt_number(taken));
        ior = taken;
    }
    Material& mat = c.out.material;
    mat.type = MaterialType::glazing;
    mat.ior = ior;
    auto curves = std::make_shared<std::vector<GlazingCurve>>();
    for (const double tau : tn) {
        const double tt = pane_optics(1.0, ior, tau).transmittance;
        mat.transmittance.push_back(tt);
        curves->push_back(pane_curve(std::clamp(tt, 1e-9, max_pane_transmittance(ior)), ior));
    }
    mat.glazing = std::move(curves);
}

void map_dielectric(Mapper& c) {
    const RadianceModifier& m = c.m;
    if (!(m.reals[3] > 0.0))
        throw InputError(c.where + ": the refractive index must be positive, not " + detail::fmt_number(m.reals[3]));
    c.out.material.type = MaterialType::glass;
    c.out.material.ior = m.reals[3];
    c.out.material.transmittance.assign(c.nb(), 1.0);
    const std::vector<double> tn = c.colour(0);
    if (std::any_of(tn.begin(), tn.end(), [](double x) { return x < 1.0; }))
        c.out.notes.push_back("absorption per metre (" + list(tn) + ") ignored: clear glass");
    if (m.reals[4] != 0.0) c.out.notes.push_back("Hartmann constant ignored (no dispersion)");
}

// light, glow and spotlight: a Lambertian emitter of the radiance times 179 lm/W.
void map_emitter(Mapper& c) {
    const RadianceModifier& m = c.m;
    c.out.role = RadianceRole::light;
    c.out.material.type = MaterialType::black;
    double rgb[3] = {m.reals[0], m.reals[1], m.reals[2]};
    for (const double x : rgb)
        if (x < 0.0) throw InputError(c.where + ": a negative radiance (" + detail::fmt_number(x) + ")");
    // Bands sum to the photometric total (as a [[light]]'s colour shares do): R, G, B
    // carry each channel's part of the luminance, w_c c_c.
    if (c.bands.size() == 3)
        for (int k = 0; k < 3; ++k) rgb[k] *= kRadianceLuminanceWeights[k];
    c.out.luminance_cd_m2 = scaled(to_bands(rgb, c.bands), kRadianceEfficacy_lm_per_W);
    if (m.type == "glow") c.out.notes.push_back("glow's radius of influence ignored: a light everywhere");
    if (m.type == "spotlight") c.out.notes.push_back("spotlight cone ignored: a Lambertian emitter");
}

// illum: a daylight portal, open to every photon.
void map_illum(Mapper& c) {
    c.out.role = RadianceRole::portal;
    c.out.material.type = MaterialType::glass;
    c.out.material.ior = 1.0;  // an opening: every photon passes
    c.out.material.transmittance.assign(c.nb(), 1.0);
    if (!c.m.strings.empty() && c.m.strings[0] != "void")
        c.out.notes.push_back("the material '" + c.m.strings[0] + "' behind the illum is not used: an open portal");
}

// The material types mapped, each to its function; any other modifier (texfunc,
// brightdata, skyfunc) is not a material. A new type goes here, with its function above.
struct TypeMapping {
    std::string_view type;
    void (*map)(Mapper&);
};
constexpr TypeMapping kTypeMappings[] = {
    {"plastic", map_plastic_or_metal},
    {"metal", map_plastic_or_metal},
    {"trans", map_trans},
    {"mirror", map_mirror},
    {"glass", map_glass},
    {"dielectric", map_dielectric},
    {"light", map_emitter},
    {"glow", map_emitter},
    {"spotlight", map_emitter},
    {"illum", map_illum},
};

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
    Mapper c{m, model.where(m.at) + ": modifier '" + m.name + "' (" + m.type + ")", bands, {}};
    const bool y = bands.size() == 1 && bands[0] == "Y";
    const bool rgb = bands == std::vector<std::string>{"R", "G", "B"};
    if (!y && !rgb) throw InputError(c.where + ": a Radiance model needs bands [\"Y\"] or [\"R\", \"G\", \"B\"]");
    c.out.material.name = m.name;
    if (!m.read_as.empty()) c.out.notes.push_back("read as " + m.type + " from " + m.read_as + " (isotropic)");
    const auto rule = std::find_if(std::begin(kTypeMappings), std::end(kTypeMappings),
                                   [&](const TypeMapping& r) { return r.type == m.type; });
    if (rule != std::end(kTypeMappings)) rule->map(c);
    else c.out.role = RadianceRole::ignored;
    return std::move(c.out);
}

}  // namespace luxtrace
