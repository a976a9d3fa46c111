#include "scene_summary.hpp"

#include "luxtrace/scene/scene.hpp"

#include <iomanip>
#include <ostream>
#include <span>
#include <string>

namespace luxtrace {

namespace {
const char* type_name(MaterialType t) {
    switch (t) {
    case MaterialType::diffuse: return "diffuse";
    case MaterialType::mirror: return "mirror";
    case MaterialType::glass: return "glass";
    case MaterialType::general: return "general";
    case MaterialType::black: return "black";
    case MaterialType::glazing: return "glazing";
    }
    return "?";
}

// Only when the scene has more than the one default group, or light scenes; an annual
// scene's groups are its sky patches and suns, summarised with the lights.
void print_light_groups(const Scene& s, std::ostream& out) {
    const bool only_default = s.light_groups.size() == 1 && s.light_groups[0] == Scene::kDefaultLightGroup;
    if ((only_default && s.light_scenes.empty()) || s.annual) return;
    std::vector<std::size_t> lights(s.light_groups.size(), 0);
    std::vector<double> flux_lm(s.light_groups.size(), 0.0);
    for (const Light& l : s.lights.lights()) {
        ++lights[l.group];
        flux_lm[l.group] += l.flux_lm;
    }
    out << "groups     " << s.light_groups.size() << " light group(s)\n";
    for (std::size_t g = 0; g < s.light_groups.size(); ++g)
        out << "  " << std::left << std::setw(16) << s.light_groups[g] << std::right << "  " << lights[g]
            << " light(s), " << std::setprecision(6) << flux_lm[g] << " lm\n";
    out << "scenes     " << s.light_scenes.size() << " light scene(s)\n";
    for (const LightScene& ls : s.light_scenes) {
        out << "  " << std::left << std::setw(16) << ls.name << std::right << " ";
        for (std::size_t g = 0; g < s.light_groups.size(); ++g) {
            out << (g == 0 ? " " : ", ") << s.light_groups[g] << ' ';
            if (ls.weights[g] == 0.0) out << "off";
            else out << std::setprecision(6) << ls.weights[g];
        }
        out << '\n';
    }
}
// An annual scene's lights in a few lines instead of one per patch and sun.
void print_annual_lights(const Scene& s, std::ostream& out) {
    const AnnualSky& sky = *s.annual->sky;
    out << "lights     " << describe_lights(s) << " (" << s.light_groups.size() << " light groups), total "
        << std::setprecision(6) << s.lights.total_flux_lm() << " lm: the year's sky and sun from "
        << s.annual->options.weather.string() << '\n'
        << "  " << sky.daylit_hours() << " daylit hours of " << sky.hours().size() << ", " << sky.suns().size()
        << " with a sun; "
        << (s.annual->options.sky == "cie" ? "CIE type " + std::to_string(s.annual->options.cie_type)
                                           : std::string("Perez"))
        << " skies, ground reflectance " << s.annual->options.ground_reflectance << '\n';
    const AnnualOptions& o = s.annual->options;
    if (!o.shadow_rays()) {
        out << "  the grids' light: the photons over each sensor's disc\n";
        return;
    }
    out << "  the grids' direct light by shadow rays from each sensor, the light after a diffuse reflection ";
    if (o.gathers())
        out << "gathered from the photons' arrivals (" << o.gather_rays << " rays a sensor, patches up to "
            << o.gather_patch_m << " m)\n";
    else out << "by the photons over each sensor's disc\n";
    if (o.sun_group_days > 1)
        out << "  the suns' photons in " << s.annual->sun_rows() << " light groups, a clock hour's suns of "
            << o.sun_group_days << " days each (sun_group_days)\n";
}

}  // namespace

std::string describe_lights(const Scene& s) {
    if (!s.annual) return std::to_string(s.lights.lights().size()) + " lights";
    return std::to_string(s.annual->sky->patches().count()) + " sky patches, ground, " +
           std::to_string(s.annual->sky->suns().size()) + " suns";
}

void print_scene_summary(const Scene& s, const std::vector<std::string>& warnings, std::ostream& out) {
    out << "scene      " << s.name << " (" << s.file.string() << ")\n";
    out << "bands      ";
    for (const std::string& b : s.bands) out << b << ' ';
    out << "\ngeometry   " << s.triangle_count() << " triangles, " << s.vertices.size() << " vertices, "
        << std::setprecision(6) << s.total_area_m2() << " m^2; bounds [" << s.bounds_min.x << ", " << s.bounds_min.y
        << ", " << s.bounds_min.z << "] - [" << s.bounds_max.x << ", " << s.bounds_max.y << ", " << s.bounds_max.z
        << "]\n";
    std::vector<std::size_t> count(s.materials.size(), 0);
    std::vector<double> area(s.materials.size(), 0.0);
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        ++count[s.triangle_material[t]];
        area[s.triangle_material[t]] += s.triangle_area_m2[t];
    }
    out << "materials  " << s.materials.size() << '\n';
    for (std::size_t m = 0; m < s.materials.size(); ++m)
        out << "  " << std::left << std::setw(16) << s.materials[m].name << std::right << std::setw(8)
            << type_name(s.materials[m].type) << "  albedo " << std::setprecision(3) << albedo(s.materials[m], 0)
            << "  " << count[m] << " triangles, " << area[m] << " m^2\n";
    // What each Radiance modifier became, with the approximations made (docs/RADIANCE.md).
    if (!s.radiance_modifiers.empty()) {
        out << "radiance   " << s.radiance_modifiers.size() << " modifiers\n";
        for (const std::string& m : s.radiance_modifiers) out << "  " << m << '\n';
    }
    if (s.annual) print_annual_lights(s, out);
    else
        out << "lights     " << s.lights.lights().size() << ", total " << std::setprecision(6)
            << s.lights.total_flux_lm() << " lm\n";
    // An annual scene's thousands of patches and suns are summarised above, not listed.
    const std::span<const Light> listed = s.annual ? std::span<const Light>{}
                                                   : std::span<const Light>(s.lights.lights());
    for (const Light& l : listed) {
        out << "  " << std::left << std::setw(24) << l.label << std::right << "  " << l.flux_lm << " lm";
        l.describe(out);
        out << '\n';
    }
    print_light_groups(s, out);
    out << "detectors  " << s.detectors.size() - s.observers.size() << '\n';
    for (const Detector& d : s.detectors) {
        if (d.observer >= 0) continue;  // an observer's eye detector: listed with the observer
        out << "  " << std::left << std::setw(16) << d.name << std::right << " " << detector_type_name(d.type) << "  "
            << d.nx << " x " << d.ny;
        if (d.cylinders()) {
            out << " points, cylinders r " << d.radius_m << " m h " << d.height_m << " m";
            if (d.type == DetectorType::semicylindrical)
                out << " facing [" << d.facing.x << ", " << d.facing.y << ", " << d.facing.z << "]";
            if (d.horizontal_index >= 0) out << ", modelling ratio over '" << d.horizontal << "'";
        } else if (d.type == DetectorType::points) {
            out << " sensors from " << d.points_file << " (" << d.sensors.planes() << " plane(s)), discs r "
                << d.radius_m << " m";
        } else {
            out << " cells of " << d.cell_area_m2() << " m^2";
        }
        out << ", units " << d.units() << '\n';
        for (const TaskArea& a : d.task_areas)
            out << "    task area " << a.name << ": cells [" << a.i0 << ":" << a.i1 << "," << a.j0 << ":" << a.j1
                << "], " << (a.i1 - a.i0) * (a.j1 - a.j0) << " cells, "
                << (a.i1 - a.i0) * (a.j1 - a.j0) * d.cell_area_m2() << " m^2\n";
    }
    if (!s.observers.empty()) out << "observers  " << s.observers.size() << " (UGR, CIE 117)\n";
    for (const Observer& o : s.observers) {
        out << "  " << std::left << std::setw(16) << o.name << std::right << " eye (" << o.position.x << ", "
            << o.position.y << ", " << o.position.z << "), looking (" << o.view_direction.x << ", "
            << o.view_direction.y << ", " << o.view_direction.z << "), " << o.sources.size()
            << " luminaire(s) in view, eye detector " << o.eye_detector_size_m << " m\n";
        for (const GlareSource& g : o.sources)
            out << "    " << g.label << ": L " << g.luminance_cd_m2 << " cd/m^2, omega " << g.solid_angle_sr
                << " sr, p " << g.position_index << ", L^2 omega / p^2 " << g.term() << '\n';
    }
    out << "run        " << s.run.photons << " photons, seed " << s.run.seed << ", output " << s.run.output << ", "
        << s.run.targets.size() << " target(s)\n";
    out << "warnings   " << warnings.size() << '\n';
    for (const std::string& w : warnings) out << "  warning: " << w << '\n';
}

}  // namespace luxtrace
