#pragma once
// The detectors as filters on a photon's path: each kind says which of its cells an event
// of the path registers in, and appends them to the photon's registrations (the scorer,
// tally/photon_tally.hpp, counts them when the photon ends). Two events exist:
//   a flight, from a point along a direction up to the next surface (or to infinity):
//     illuminance planes it crosses, cylinders it enters, sensor discs (points detectors)
//     it crosses; planes of indirect light only
//     skip the flight from the light;
//   a departure, from a point (a luminaire's surface or a scattering point) along a
//     direction: luminance detectors that see it leave.
// A new detector kind adds a list and a loop here, and nothing in the tracer's step.
#include "luxtrace/core/math.hpp"
#include "luxtrace/detector/detector.hpp"
#include "luxtrace/tally/photon_tally.hpp"

#include <cstdint>
#include <vector>

namespace luxtrace {

class DetectorFilters {
public:
    explicit DetectorFilters(const std::vector<Detector>& detectors);
    // `direct`: the flight is on the straight line from the light (no event turned it);
    // `hit_normal`: the unit normal of the surface it ends on (zero if it escapes).
    // Inline: it runs for every flight of every photon.
    void flight(const Vec3& origin, const Vec3& direction, double t_max, const Vec3& hit_normal, bool direct,
                std::vector<Registration>& out) {
        cross(planes_, origin, direction, t_max, hit_normal, direct, out);
        if (!cylinders_.empty()) enter_cylinders(origin, direction, t_max, direct, out);
        if (!points_.empty()) cross_sensors(origin, direction, t_max, hit_normal, direct, out);
        // Indirect only: planes that skip direct light (an observer's eye detector).
        if (!direct) cross(indirect_planes_, origin, direction, t_max, hit_normal, false, out);
    }
    void departure(const Vec3& point, const Vec3& direction, std::vector<Registration>& out) const;
    bool sees_flights() const {
        return !planes_.empty() || !cylinders_.empty() || !points_.empty() || !indirect_planes_.empty();
    }
    bool sees_departures() const { return !luminance_.empty(); }

private:
    void cross(const std::vector<std::uint32_t>& planes, const Vec3& o, const Vec3& d, double t_max,
               const Vec3& hit_normal, bool direct, std::vector<Registration>& out) const {
        for (std::uint32_t di : planes) {
            const int cell = detectors_[di].crossing(o, d, t_max, hit_normal);
            if (cell >= 0) out.push_back({di, static_cast<std::uint32_t>(cell), direct});
        }
    }
    void enter_cylinders(const Vec3& o, const Vec3& d, double t_max, bool direct, std::vector<Registration>& out);
    void cross_sensors(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal, bool direct,
                       std::vector<Registration>& out);

    const std::vector<Detector>& detectors_;
    std::vector<std::uint32_t> planes_, indirect_planes_, cylinders_, points_, luminance_;
    std::vector<int> cells_;  // scratch for cylinder entries and sensor crossings
};

}  // namespace luxtrace
