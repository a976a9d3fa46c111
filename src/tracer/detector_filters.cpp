#include "luxtrace/tracer/detector_filters.hpp"

#include "luxtrace/detector/detector.hpp"

namespace luxtrace {

DetectorFilters::DetectorFilters(const std::vector<Detector>& detectors) : detectors_(detectors) {
    for (std::uint32_t i = 0; i < detectors.size(); ++i) {
        const Detector& d = detectors[i];
        if (d.type == DetectorType::luminance) luminance_.push_back(i);
        else if (d.cylinders()) cylinders_.push_back(i);
        else (d.indirect_only ? indirect_planes_ : planes_).push_back(i);
    }
}

void DetectorFilters::flight(const Vec3& o, const Vec3& d, double t_max, int bounce, std::vector<Registration>& out) {
    auto cross = [&](const std::vector<std::uint32_t>& planes) {
        for (std::uint32_t di : planes) {
            const int cell = detectors_[di].crossing(o, d, t_max);
            if (cell >= 0) out.push_back({di, static_cast<std::uint32_t>(cell)});
        }
    };
    cross(planes_);
    for (std::uint32_t di : cylinders_) {
        cells_.clear();
        detectors_[di].cylinder_entries(o, d, t_max, cells_);
        for (int cell : cells_) out.push_back({di, static_cast<std::uint32_t>(cell)});
    }
    // Indirect only: the flight from the light (bounce 0) is the direct one.
    if (bounce > 0) cross(indirect_planes_);
}

void DetectorFilters::departure(const Vec3& point, const Vec3& direction, std::vector<Registration>& out) const {
    for (std::uint32_t di : luminance_) {
        const int cell = detectors_[di].leaving(point, direction);
        if (cell >= 0) out.push_back({di, static_cast<std::uint32_t>(cell)});
    }
}

}  // namespace luxtrace
