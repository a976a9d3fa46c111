#pragma once
// What a straight path through the scene lets through, per band: a shadow ray. Light that
// keeps its direction through a surface (glazing's straight-through part, an open hole, a
// general material's specular transmittance) is what the photon tracer counts as direct
// (tracer.hpp, Photon::direct), so a shadow ray passes such surfaces times their
// transmittance at its incidence and stops at any other. Used for the renderer's direct
// light and for the direct daylight at sensor points (direct_daylight.hpp).
#include "luxtrace/core/math.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace luxtrace {

class EmbreeScene;
struct Scene;

class ShadowRay {
public:
    // `step_m`: how far past a pane the ray goes on (a few ray epsilons). `openings`, per
    // scene triangle (PortalOpenings::triangles), or null: a path that leaves the scene
    // passes only if it crossed one of them (daylight through portals). All must outlive
    // this.
    ShadowRay(const Scene& scene, const EmbreeScene& embree, double step_m,
              const std::vector<std::uint8_t>* openings = nullptr);

    // The share of each band (share[0 .. bands()-1]) that the path o + t d,
    // t_near <= t < t_far, lets through; false, with every share 0, if a surface stops it.
    bool passes(const Vec3& o, const Vec3& d, double t_far, double* share, double t_near = 0.0) const;

private:
    const Scene& scene_;
    const EmbreeScene& embree_;
    int bands_ = 1;
    double step_m_ = 0.0;
    bool see_through_ = false;  // some material lets a straight path through
    const std::vector<std::uint8_t>* openings_ = nullptr;
};

}  // namespace luxtrace
