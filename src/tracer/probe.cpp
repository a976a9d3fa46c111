#include "luxtrace/tracer/probe.hpp"

#include "luxtrace/sampler/philox_sampler.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/ray_offset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace luxtrace {

namespace {

// Whether a surface cuts the small cylinder at point (i, j) of a cylindrical detector:
// rays from its centre along the axis, across it at three heights, and to its rims.
// A flight scattered from a surface inside a cylinder starts inside and is not counted.
bool cylinder_cut(const Detector& d, int i, int j, const EmbreeScene& embree) {
    const Vec3 p = d.center + ((i + 0.5) / d.nx - 0.5) * d.size_u * d.u_axis +
                   ((j + 0.5) / d.ny - 0.5) * d.size_v * d.v_axis;
    const double half_h = 0.5 * d.height_m;
    auto cut = [&](const Vec3& from, const Vec3& to) {
        const Vec3 r = to - from;
        const double len = glm::length(r);
        return embree.occluded(from, r / len, static_cast<float>(len));
    };
    if (cut(p, p + half_h * d.normal) || cut(p, p - half_h * d.normal)) return true;
    for (int k = 0; k < 8; ++k) {
        const double a = k * kPi / 4.0;
        const Vec3 rim = d.radius_m * (std::cos(a) * d.u_axis + std::sin(a) * d.v_axis);
        for (const double z : {-half_h, 0.0, half_h})
            if (cut(p + z * d.normal, p + z * d.normal + rim)) return true;
        if (cut(p, p + rim + half_h * d.normal) || cut(p, p + rim - half_h * d.normal)) return true;
    }
    return false;
}

// Where a light's photon goes first, as the tracer would take it.
enum class FirstFlight { hit, black, escaped, blocked };

FirstFlight first_flight(const Scene& scene, const EmbreeScene& embree, const EmittedRay& r) {
    if (r.missed) return FirstFlight::escaped;  // a sky patch's photon past its portal, as the tracer counts it
    Vec3f o = embree.to_local(r.origin);
    if (r.emitter_triangle >= 0) {  // leave the emitter as the tracer does
        const auto t = static_cast<unsigned>(r.emitter_triangle);
        const glm::uvec3 v = scene.triangles[t];
        const float margin = embree.self_hit_margin(t);
        o = spawn_origin(point_on_triangle(embree.local_vertex(v.x), embree.local_vertex(v.y), embree.local_vertex(v.z),
                                           static_cast<float>(r.emitter_u), static_cast<float>(r.emitter_v), margin),
                         Vec3f(scene.triangle_normal[t]) * static_cast<float>(r.emitter_side), margin);
        // A portal photon's way back to the sky (tracer.cpp).
        if (r.through_portal && embree.occluded_local(o, -Vec3f(r.direction))) return FirstFlight::blocked;
    }
    const Hit h = embree.intersect_local(o, Vec3f(r.direction));
    if (!h.found) return FirstFlight::escaped;
    return scene.materials[scene.triangle_material[h.triangle]].type == MaterialType::black ? FirstFlight::black
                                                                                            : FirstFlight::hit;
}

struct ProbeCounts {
    int black = 0, escaped = 0, blocked = 0;
};

// `rays` photons of light `l`, the same ones for every light.
ProbeCounts probe_light(const Scene& scene, const EmbreeScene& embree, const Light& l, int rays,
                        PhiloxSampler& sampler) {
    ProbeCounts n;
    for (int k = 0; k < rays; ++k) {
        sampler.start_photon(static_cast<std::uint64_t>(k));
        const double a = sampler.next(), b = sampler.next(), c = sampler.next(), d = sampler.next();
        switch (first_flight(scene, embree, l.emit(a, b, c, d))) {
        case FirstFlight::black: ++n.black; break;
        case FirstFlight::escaped: ++n.escaped; break;
        case FirstFlight::blocked: ++n.blocked; break;
        case FirstFlight::hit: break;
        }
    }
    return n;
}

void warn_about_light(const Light& l, const ProbeCounts& n, int rays, std::vector<std::string>& warnings) {
    char buf[512];
    if (n.blocked > 0) {
        std::snprintf(buf, sizeof buf,
                      "%s: %.1f%% of probe rays back out through the opening hit exterior geometry: the sky "
                      "it hides is right, but the light it reflects into the opening is not simulated "
                      "(exact only if it is black; docs/DAYLIGHT.md, Portals)",
                      l.label.c_str(), 100.0 * n.blocked / rays);
        warnings.emplace_back(buf);
    }
    if (n.black == rays) {
        std::snprintf(buf, sizeof buf,
                      "%s: every probe ray hits a black surface first: its photons are all absorbed at the first "
                      "hit (is it inside a closed black box?)",
                      l.label.c_str());
        warnings.emplace_back(buf);
    } else if (n.escaped == rays && !l.distant()) {
        std::snprintf(buf, sizeof buf, "%s: no probe ray hits any surface: its light leaves the scene",
                      l.label.c_str());
        warnings.emplace_back(buf);
    } else if (n.escaped > rays / 2 && !l.distant()) {
        std::snprintf(buf, sizeof buf, "%s: %.0f%% of probe rays leave the scene without hitting a surface",
                      l.label.c_str(), 100.0 * n.escaped / rays);
        warnings.emplace_back(buf);
    }
}

void warn_about_detector(const Scene& scene, const EmbreeScene& embree, const Detector& d,
                         std::vector<std::string>& warnings) {
    const Vec3 lo = scene.bounds_min - Vec3(1e-3), hi = scene.bounds_max + Vec3(1e-3);
    if (glm::any(glm::lessThan(d.center, lo)) || glm::any(glm::greaterThan(d.center, hi)))
        warnings.push_back("detector '" + d.name + "': its centre lies outside the scene's bounding box");
    if (!d.cylinders()) return;
    // At most about 4096 points, evenly strided, on a large grid.
    const int stride = std::max(1, d.cells() / 4096);
    int probed = 0, cut = 0, first = -1;
    for (int c = 0; c < d.cells(); c += stride, ++probed)
        if (cylinder_cut(d, c % d.nx, c / d.nx, embree)) {
            if (cut++ == 0) first = c;
        }
    if (cut > 0)
        warnings.push_back("detector '" + d.name + "': a surface cuts " + std::to_string(cut) + " of " +
                           std::to_string(probed) + " probed cylinders (the first at point [" +
                           std::to_string(first % d.nx) + ", " + std::to_string(first / d.nx) +
                           "]): light scattered from a surface inside a cylinder is not counted");
}

// UGR counts every luminaire in an observer's field of view (glare/observer.hpp): say
// when a surface stands between the eye and a luminous centre. The ray stops 1 cm short
// of the centre, so a recessed opening flush with its ceiling is not hidden by it.
void warn_about_hidden_luminaires(const Scene& scene, const EmbreeScene& embree, std::vector<std::string>& warnings) {
    for (const Observer& o : scene.observers)
        for (const GlareSource& g : o.sources) {
            const Vec3 d = g.position - o.position;
            const double r = glm::length(d);
            if (r > 0.02 && embree.occluded(o.position, d / r, static_cast<float>(r - 0.01)))
                warnings.push_back("observer '" + o.name + "': " + g.label +
                                   " is hidden from the eye by a surface, but UGR counts it (luxtrace does not "
                                   "test what the eye sees)");
        }
}

void warn_about_unused_materials(const Scene& scene, std::vector<std::string>& warnings) {
    std::vector<bool> used(scene.materials.size(), false);
    for (std::uint32_t m : scene.triangle_material) used[m] = true;
    for (std::size_t m = 0; m < used.size(); ++m)
        if (!used[m]) warnings.push_back("material '" + scene.materials[m].name + "' is not used by any triangle");
}

}  // namespace

std::vector<std::string> probe_scene(const Scene& scene, const EmbreeScene& embree, int rays) {
    std::vector<std::string> warnings;
    PhiloxSampler sampler(0x9e3779b9u);
    for (const Light& l : scene.lights.lights()) {
        if (!(l.flux_lm > 0.0)) continue;  // a sun below the horizon or behind its portal
        warn_about_light(l, probe_light(scene, embree, l, rays, sampler), rays, warnings);
    }
    for (const Detector& d : scene.detectors) warn_about_detector(scene, embree, d, warnings);
    warn_about_hidden_luminaires(scene, embree, warnings);
    warn_about_unused_materials(scene, warnings);
    return warnings;
}

}  // namespace luxtrace
