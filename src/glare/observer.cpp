#include "luxtrace/glare/observer.hpp"

#include "luxtrace/glare/ugr.hpp"
#include "luxtrace/light/light_set.hpp"

#include <cmath>
#include <sstream>

namespace luxtrace {

void Observer::finalize() {
    view_direction = glm::normalize(view_direction);
    up = glm::normalize(Vec3(0, 0, 1) - view_direction.z * view_direction);
    right = glm::cross(view_direction, up);
}

namespace {

constexpr double kDeg = 180.0 / kPi;
// CIE 117's table of Guth's position index covers H/R up to 1.9 and T/R up to 3.
constexpr double kMaxHOverR = 1.9;
constexpr double kMaxTOverR = 3.0;

std::string fmt(double v) {
    std::ostringstream os;
    os.precision(4);
    os << v;
    return os.str();
}

}  // namespace

std::vector<GlareSource> glare_sources(Observer& o, const LightSet& lights) {
    std::vector<GlareSource> out;
    const std::string who = "observer '" + o.name + "': ";
    for (std::size_t i = 0; i < lights.lights().size(); ++i) {
        const Light& l = lights.lights()[i];
        GlareSource s;
        s.light = i;
        s.label = l.label;
        const LuminaireView view = l.view_from(o.position);
        s.position = view.position;
        s.distance_m = view.distance_m;
        s.intensity_cd = view.intensity_cd;
        s.projected_area_m2 = view.projected_area_m2;
        s.luminance_cd_m2 = view.luminance_cd_m2;
        s.solid_angle_sr = view.solid_angle_sr;
        const bool luminous = view.luminous;
        const std::string& why = view.why_not;
        if (!luminous && !view.field_test_when_dark) {
            // Lights that cannot be placed in the field are left out of the sum; say so
            // only for those in front of the eye, the others could not count anyway.
            const bool behind = view.placed && glm::dot(view.position - o.position, o.view_direction) <= 0.0;
            if (behind) continue;
            o.notes.push_back(who + l.label + " is left out of UGR: " + why);
            continue;
        }
        // Field of view and Guth's angles, from the centre of the luminous area.
        const Vec3 v = s.position - o.position;
        const double R = glm::dot(v, o.view_direction), H = glm::dot(v, o.up), T = glm::dot(v, o.right);
        if (!(R > 0.0) || H < 0.0 || H > kMaxHOverR * R || std::abs(T) > kMaxTOverR * R) continue;
        if (!luminous) {
            o.notes.push_back(who + l.label + " is left out of UGR: " + why);
            continue;
        }
        s.beta_deg = std::atan2(std::hypot(H, T), R) * kDeg;
        s.alpha_deg = (H == 0.0 && T == 0.0) ? 0.0 : std::atan2(std::abs(T), H) * kDeg;
        s.position_index = guth_position_index(s.alpha_deg, s.beta_deg);
        if (s.solid_angle_sr < kUgrMinSolidAngleSr || s.solid_angle_sr > kUgrMaxSolidAngleSr)
            o.notes.push_back(who + l.label + " subtends " + fmt(s.solid_angle_sr) +
                              " sr, outside CIE 117's range for UGR (0.0003 to 0.1 sr)");
        out.push_back(s);
    }
    return out;
}

}  // namespace luxtrace
