#include "luxtrace/tracer/detector_filters.hpp"

namespace luxtrace {

DetectorFilters::DetectorFilters(const std::vector<Detector>& detectors) : detectors_(detectors) {
    for (std::uint32_t i = 0; i < detectors.size(); ++i) {
        const Detector& d = detectors[i];
        if (d.type == DetectorType::luminance) luminance_.push_back(i);
        else if (d.cylinders()) cylinders_.push_back(i);
        else if (d.type == DetectorType::points) points_.push_back(i);
        else (d.indirect_only ? indirect_planes_ : planes_).push_back(i);
    }
}

void DetectorFilters::enter_cylinders(const Vec3& o, const Vec3& d, double t_max, bool direct,
                                      std::vector<Registration>& out) {
    for (std::uint32_t di : cylinders_) {
        cells_.clear();
        detectors_[di].cylinder_entries(o, d, t_max, cells_);
        for (int cell : cells_) out.push_back({di, static_cast<std::uint32_t>(cell), direct});
    }
}

void DetectorFilters::cross_sensors(const Vec3& o, const Vec3& d, double t_max, const Vec3& hit_normal, bool direct,
                                    std::vector<Registration>& out) {
    for (std::uint32_t di : points_) {
        cells_.clear();
        detectors_[di].sensor_crossings(o, d, t_max, hit_normal, cells_);
        for (int cell : cells_) out.push_back({di, static_cast<std::uint32_t>(cell), direct});
    }
}

void DetectorFilters::departure(const Vec3& point, const Vec3& direction, std::vector<Registration>& out) const {
    for (std::uint32_t di : luminance_) {
        const int cell = detectors_[di].leaving(point, direction);
        if (cell >= 0) out.push_back({di, static_cast<std::uint32_t>(cell)});
    }
}

}  // namespace luxtrace
