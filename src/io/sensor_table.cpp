#include "luxtrace/io/sensor_table.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/text.hpp"
#include "luxtrace/estimate/result_estimates.hpp"
#include "luxtrace/io/atomic_file.hpp"
#include "luxtrace/scene/scene.hpp"

#include <cmath>
#include <cstdio>

namespace luxtrace {

namespace {

bool is_table_detector(const Detector& d) { return d.type == DetectorType::points && d.observer < 0; }

// 9 significant digits: far below any standard error, and "nan" for a sensor without photons.
std::string nine_digits(double x) {
    if (std::isnan(x)) return "nan";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", x);
    return buf;
}

}  // namespace

SensorTable sensor_table(const Scene& scene, std::size_t detector, const DetectorEstimate& e, std::uint64_t photons) {
    const Detector& d = scene.detectors[detector];
    SensorTable t;
    t.detector = d.name;
    t.points_file = d.points_file;
    t.radius_m = d.radius_m;
    t.bands = scene.bands;
    t.photons = photons;
    t.error_estimator = e.replicate_spread ? "replicate_spread" : "independent_photons_eq8";
    t.maintenance_factor = scene.lights.maintenance_factor();
    t.maintenance_factor_uniform = scene.lights.maintenance_factor_uniform();
    t.positions = d.sensors.positions();
    t.illuminance_lx = e.summed_value;
    t.sigma_lx = e.summed_sigma;
    return t;
}

std::string format_sensor_table(const SensorTable& t) {
    std::string s;
    s += "# luxtrace sensor table: points detector " + t.detector + ", " + std::to_string(t.positions.size()) +
         " sensors of " + t.points_file + " in its order, each a disc of radius " + shortest_decimal(t.radius_m) +
         " m\n";
    s += "# photons traced: " + std::to_string(t.photons) + "\n";
    s += "# values: initial, no maintenance factor applied; maintained = " + shortest_decimal(t.maintenance_factor) +
         (t.maintenance_factor_uniform ? " x E (the lights' maintenance factor)\n"
                                       : " x E about (the lights' flux-weighted maintenance factor; theirs differ)\n");
    s += "# columns: x y z E sigma_E\n";
    s += "#   x y z    m   the sensor's position as read\n";
    s += "#   E        lx  illuminance on the sensor's front side, summed over the bands (" + comma_list(t.bands) +
         ")\n";
    s += "#   sigma_E  lx  one-sigma standard error of E (" + t.error_estimator + "); nan where no photon arrived\n";
    for (std::size_t k = 0; k < t.positions.size(); ++k) {
        const Vec3& p = t.positions[k];
        s += shortest_decimal(p.x) + ' ' + shortest_decimal(p.y) + ' ' + shortest_decimal(p.z) + ' ' +
             nine_digits(t.illuminance_lx[k]) + ' ' + nine_digits(t.sigma_lx[k]) + '\n';
    }
    return s;
}

std::filesystem::path sensor_table_path(const std::filesystem::path& result, const std::string& detector) {
    return result.parent_path() / (result.stem().string() + "." + detector + ".txt");
}

std::vector<std::filesystem::path> sensor_table_paths(const Scene& scene, const std::filesystem::path& result) {
    std::vector<std::filesystem::path> paths;
    for (const Detector& d : scene.detectors)
        if (is_table_detector(d)) paths.push_back(sensor_table_path(result, d.name));
    return paths;
}

std::vector<std::filesystem::path> write_sensor_tables(const std::filesystem::path& result, const Scene& scene,
                                                       const ResultEstimates& estimates, std::uint64_t photons,
                                                       std::vector<std::string>& failures) {
    std::vector<std::filesystem::path> written;
    for (std::size_t di = 0; di < scene.detectors.size(); ++di) {
        const Detector& d = scene.detectors[di];
        if (!is_table_detector(d)) continue;
        const std::filesystem::path path = sensor_table_path(result, d.name);
        const std::string text = format_sensor_table(sensor_table(scene, di, estimates.detectors[di], photons));
        try {
            write_file_atomically(path, text);
            written.push_back(path);
        } catch (const IoError& e) {
            failures.push_back(e.what());
        }
    }
    return written;
}

}  // namespace luxtrace
