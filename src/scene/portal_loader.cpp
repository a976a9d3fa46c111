// [[portal]] -> every sun and sky light split into one light per opening (docs/REFERENCE.md
// §2, docs/DAYLIGHT.md "Portals"; the physics in light/portal.hpp).
#include "luxtrace/core/error.hpp"
#include "luxtrace/light/portal.hpp"
#include "scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

namespace luxtrace::detail {

namespace {

// Surfaces beyond the opening's plane, on its outside, that are not black: the sky they
// hide is blocked exactly (the tracer's ray back out), the light they reflect into the
// opening is not simulated.
void warn_of_exterior_geometry(SceneLoad& load, const Portal& portal, double extent) {
    const Scene& scene = load.scene;
    const double tolerance = 1e-6 * (1.0 + extent + glm::length(portal.surface.p0[0]));
    std::size_t outside = 0;
    for (std::size_t tri = 0; tri < scene.triangles.size(); ++tri) {
        if (scene.materials[scene.triangle_material[tri]].type == MaterialType::black) continue;
        const glm::uvec3 v = scene.triangles[tri];
        for (const unsigned k : {v.x, v.y, v.z})
            if (glm::dot(Vec3(scene.vertices[k]) - portal.surface.p0[0], portal.outward) > tolerance) {
                ++outside;
                break;
            }
    }
    if (outside > 0)
        load.scene.warnings.push_back("portal '" + portal.name + "': " + std::to_string(outside) +
                                      " triangle(s) that are not black lie outside its opening: the sky they hide is "
                                      "blocked exactly, but the light they reflect into the opening is not simulated "
                                      "(docs/DAYLIGHT.md, Portals)");
}

// The opening `surface` named `name`: its triangles must lie in one plane with one
// orientation (`fail`, which throws, says otherwise). Its front normal points into the room;
// `flip` turns that round.
std::shared_ptr<const Portal> make_portal(SceneLoad& load, const std::string& name, EmitterSurface surface, bool flip,
                                          const std::function<void(const std::string&)>& fail) {
    const Scene& scene = load.scene;
    auto portal = std::make_shared<Portal>();
    portal->name = name;
    portal->surface = std::move(surface);
    const EmitterSurface& s = portal->surface;
    // Planar: one normal (the first triangle's with area), every vertex on its plane.
    Vec3 normal(0.0);
    for (std::size_t i = 0; i < s.p0.size() && normal == Vec3(0.0); ++i)
        if (scene.triangle_area_m2[static_cast<std::size_t>(s.scene_triangle[i])] > 0.0) normal = s.normal[i];
    double extent = 0.0;
    for (std::size_t i = 0; i < s.p0.size(); ++i)
        extent = std::max({extent, glm::length(s.p0[i] - s.p0[0]), glm::length(s.e1[i]), glm::length(s.e2[i])});
    for (std::size_t i = 0; i < s.p0.size(); ++i) {
        const double off = std::max({std::abs(glm::dot(s.p0[i] - s.p0[0], normal)),
                                     std::abs(glm::dot(s.p0[i] + s.e1[i] - s.p0[0], normal)),
                                     std::abs(glm::dot(s.p0[i] + s.e2[i] - s.p0[0], normal))});
        const bool has_area = scene.triangle_area_m2[static_cast<std::size_t>(s.scene_triangle[i])] > 0.0;
        if ((has_area && glm::dot(s.normal[i], normal) < 1.0 - 1e-9) || off > 1e-6 * (1.0 + extent))
            fail("'" + name +
                 "' is not planar (a portal is one flat opening; its triangles must lie in one plane and face one "
                 "way)");
    }
    portal->side = flip ? 1 : -1;  // photons start outside: opposite the inward normal
    portal->outward = flip ? normal : -normal;
    portal->frame = Portal::frame_for(portal->outward, scene.site.horizon());
    warn_of_exterior_geometry(load, *portal, extent);
    return portal;
}

// The opening on [[shape]] `name`.
std::shared_ptr<const Portal> read_portal(SceneLoad& load, TableReader& r, std::vector<std::string>& used) {
    const auto shape = r.string("shape");
    if (!shape) r.fail_entry("needs 'shape' (the name of a planar [[shape]], the opening)");
    if (std::find(used.begin(), used.end(), *shape) != used.end())
        r.fail("shape", "shape '" + *shape + "' is already a portal");
    used.push_back(*shape);
    const bool flip = r.boolean("flip").value_or(false);
    r.finish();
    return make_portal(load, *shape, shape_surface(load, r, "shape", *shape), flip,
                       [&](const std::string& what) { r.fail("shape", "shape " + what); });
}

}  // namespace

void read_portals(SceneLoad& load, TableReader& root) {
    const auto tables = tables_of(root, "portal");
    if (tables.empty() && load.radiance_portals.empty()) return;
    std::vector<std::shared_ptr<const Portal>> portals;
    std::vector<std::string> used;
    for (std::size_t i = 0; i < tables.size(); ++i) {
        TableReader r(*tables[i], load.fname, entry_name("portal", i, *tables[i]), "portal");
        portals.push_back(read_portal(load, r, used));
    }
    // A Radiance model's illum surfaces face into the room, as a light source's front does.
    for (const SceneLoad::RadiancePortal& p : load.radiance_portals)
        portals.push_back(
            make_portal(load, p.name, triangles_surface(load.scene, p.triangles), false,
                        [&](const std::string& what) { throw InputError(p.where + ": illum surface " + what); }));
    Scene& scene = load.scene;
    const auto& old = scene.lights.lights();
    if (std::none_of(old.begin(), old.end(), [](const Light& l) { return l.enters_portals(); })) {
        if (tables.empty())
            throw InputError(load.radiance_portals[0].where + ": illum surface '" + load.radiance_portals[0].name +
                             "' is a daylight portal, and the scene has no sky or sun (no !gensky or !gendaylit, "
                             "no [[light]] of type 'sun' or 'sky')");
        TableReader r(*tables[0], load.fname, entry_name("portal", 0, *tables[0]), "portal");
        r.fail_entry("a portal lets sun and sky light in, and the scene has no [[light]] of type 'sun' or 'sky'");
    }
    std::vector<Light> lights;
    for (const Light& l : old) {
        if (!l.enters_portals()) {  // electric light
            lights.push_back(l);
            continue;
        }
        for (std::size_t p = 0; p < portals.size(); ++p) {
            Light through = *l.through_portal(portals[p], p);
            // An annual scene's patches and hourly suns behind an opening are many and
            // expected: they are left out without a word.
            if (scene.annual && !(through.flux_lm > 0.0)) continue;
            const PortalLight& opening = *through.as<PortalLight>();
            if (opening.source_lit() && !(through.flux_lm > 0.0))
                scene.warnings.push_back(through.label + ": " + opening.why_dark() + ": no light enters through it");
            lights.push_back(std::move(through));
        }
    }
    scene.lights = LightSet(std::move(lights));
}

}  // namespace luxtrace::detail
