#pragma once
// A points detector's result as the plain text table a Radiance user reads (issue 25 §3):
// one line "x y z E sigma_E" per sensor in the .pts file's order, after a few '#' lines
// that say what the columns are, the detector, the photons and whether the values are
// initial or maintained; numpy.loadtxt reads it. The numbers are the result file's own
// (the band-summed cells of the points detector's DetectorEstimate, the estimates the
// writer stores), so the table and /detectors/NAME never disagree. docs/REFERENCE.md §4,
// "Sensor tables".
#include "luxtrace/core/math.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

struct Scene;
struct DetectorEstimate;
struct ResultEstimates;

struct SensorTable {
    std::string detector;     // the detector's name
    std::string points_file;  // the .pts file as the scene names it
    double radius_m = 0.0;    // every sensor disc's radius
    std::vector<std::string> bands;
    std::uint64_t photons = 0;
    std::string error_estimator;  // as /detectors/NAME's error_estimator attribute
    double maintenance_factor = 1.0;
    bool maintenance_factor_uniform = true;
    std::vector<Vec3> positions;                   // m, as read from the .pts file
    std::vector<double> illuminance_lx, sigma_lx;  // band-summed; sigma NaN where no photon arrived
};

// Table of points detector `detector` (an index into scene.detectors) from its estimate.
SensorTable sensor_table(const Scene& scene, std::size_t detector, const DetectorEstimate& estimate,
                         std::uint64_t photons);

// The file's text: header lines starting with '#', then one line per sensor; positions in
// their shortest exact decimal form, E and sigma_E with 9 significant digits.
std::string format_sensor_table(const SensorTable& table);

// RESULT's directory / (RESULT's stem + "." + detector + ".txt"): out/office.h5 and
// detector "desk" give out/office.desk.txt. Detector names hold no '.', so the name is
// the part between the last two dots.
std::filesystem::path sensor_table_path(const std::filesystem::path& result, const std::string& detector);

// The paths the tables of `scene`'s points detectors go to, beside `result`, in detector order.
std::vector<std::filesystem::path> sensor_table_paths(const Scene& scene, const std::filesystem::path& result);

// Writes each points detector's table atomically beside `result` (estimates and photons as
// the result was written with); returns the paths written. A table that cannot be written
// is left out, its IoError's message appended to `failures`: the result holds its numbers.
std::vector<std::filesystem::path> write_sensor_tables(const std::filesystem::path& result, const Scene& scene,
                                                       const ResultEstimates& estimates, std::uint64_t photons,
                                                       std::vector<std::string>& failures);

}  // namespace luxtrace
