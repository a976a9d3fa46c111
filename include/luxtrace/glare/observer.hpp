#pragma once
// An observer of the scene ([[observer]]): an eye position and a line of sight, for the
// discomfort glare of the luminaires it sees (UGR, CIE 117:1995; ugr.hpp, docs/GLARE.md).
// The loader places a small vertical illuminance detector at the eye that counts only
// indirect light; the luminaires' own terms (luminance, solid angle, Guth position index)
// are geometry and photometry, fixed when the scene is loaded.
#include "luxtrace/core/math.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace luxtrace {

class LightSet;

// One luminaire in the observer's field of view, with its terms of the UGR sum.
struct GlareSource {
    std::size_t light = 0;           // index in LightSet::lights()
    std::string label;               // the light's label, for reports
    Vec3 position{0.0};              // centre of its luminous area
    double distance_m = 0.0;         // eye to that centre
    double intensity_cd = 0.0;       // toward the eye
    double projected_area_m2 = 0.0;  // luminous area seen from the eye
    double luminance_cd_m2 = 0.0;    // L = I / A_projected
    double solid_angle_sr = 0.0;     // omega = A_projected / r^2 (small source)
    double alpha_deg = 0.0;       // Guth: angle from the vertical of the plane through the line of sight and the source
    double beta_deg = 0.0;        // Guth: angle between the line of sight and the direction of the source
    double position_index = 1.0;  // p (ugr.hpp)
    // L^2 omega / p^2, the luminaire's share of the UGR sum (cd^2 m^-4 sr).
    double term() const {
        return luminance_cd_m2 * luminance_cd_m2 * solid_angle_sr / (position_index * position_index);
    }
};

struct Observer {
    std::string name;
    Vec3 position{0.0};                // the eye
    Vec3 view_direction{1, 0, 0};      // unit line of sight
    Vec3 up{0, 0, 1};                  // unit, the vertical turned perpendicular to the line of sight
    Vec3 right{0, -1, 0};              // view_direction x up
    double eye_detector_size_m = 0.2;  // side of the square vertical detector at the eye
    std::size_t eye_detector = 0;      // its index in Scene::detectors
    std::vector<GlareSource> sources;  // the luminaires in the field of view (field_of_view rule below)
    // Lights that could not enter the sum (no luminous area, not a luminaire) and sources
    // outside CIE 117's range of solid angles: shown as warnings and stored with the result.
    std::vector<std::string> notes;

    // Set up and right from view_direction (which must not be vertical).
    void finalize();
};

// The luminaires of `lights` that `o` sees, with their UGR terms, in the order of the
// lights; appends to o.notes what was left out and why. The field of view is CIE 117's
// Guth table: a source counts when it lies in front of the eye (R > 0), at or above the
// line of sight (H >= 0), with H/R <= 1.9 and |T|/R <= 3 (R along the line of sight, H up,
// T sideways). Luminaires are taken as visible: nothing between them and the eye is tested.
std::vector<GlareSource> glare_sources(Observer& o, const LightSet& lights);

}  // namespace luxtrace
