#pragma once
// Radiance's materials mapped onto luxtrace's (issue 25 §2; docs/RADIANCE.md "Materials"):
// what a photon does at a surface of each Radiance modifier, with every approximation the
// mapping makes said in words, for `luxtrace check` to print. Colours become the scene's
// bands: "Y" weighs Radiance's RGB as Radiance's own luminance does, "R", "G", "B" keep the
// channels. Radiance radiance (W sr^-1 m^-2) becomes luminance with Radiance's luminous
// efficacy, 179 lm/W.
#include "luxtrace/material/material.hpp"
#include "luxtrace/scene/radiance_reader.hpp"

#include <string>
#include <vector>

namespace luxtrace {

// Radiance's luminous efficacy of its white (lm/W) and its luminance weights of R, G, B.
inline constexpr double kRadianceEfficacy_lm_per_W = 179.0;
inline constexpr double kRadianceLuminanceWeights[3] = {0.265074126, 0.670114631, 0.064811243};

enum class RadianceRole {
    surface,  // photons scatter by `material`
    light,    // an emitter of `luminance_cd_m2` (light, glow, spotlight)
    portal,   // illum: a daylight opening (docs/DAYLIGHT.md "Portals"), `material` what it is
    ignored   // not a material (texfunc, brightdata, skyfunc)
};

struct RadianceMapping {
    RadianceRole role = RadianceRole::surface;
    Material material;                    // named as the modifier
    std::vector<double> luminance_cd_m2;  // light: per band
    std::vector<std::string> notes;       // each approximation the mapping made
    // One line: "NAME (TYPE) -> luxtrace ...; notes".
    std::string describe() const;
};

// Maps modifier `index` of `model` for a scene of `bands` ({"Y"} or {"R", "G", "B"}).
// Throws InputError naming the modifier's file:line for bands it cannot fill or a value no
// material can hold (a negative colour).
RadianceMapping map_radiance_modifier(const RadianceModel& model, std::size_t index,
                                      const std::vector<std::string>& bands);

}  // namespace luxtrace
