// The sensor tables beside a result (io/sensor_table.hpp, issue 25 §3): the file's name;
// its text read back gives every sensor's position exactly and E, sigma_E to their printed
// digits, in order, after '#' lines only; and end to end, a run with a points detector
// under a point light writes one line per sensor in the .pts order whose E and sigma_E are
// the result file's band-summed cell and its eq. (8) error and whose E matches the disc's
// analytic mean within sigma_E, a scene without points detectors writes no table, one that
// cannot be written warns and keeps the result, and a bad .pts file writes nothing.
#include "luxtrace/io/sensor_table.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "point_source.hpp"
#include "test_support.hpp"
#include "z_pool.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace luxtrace {
namespace {

using namespace test_support;
namespace fs = std::filesystem;

struct Row {
    double x, y, z, e, sigma;
};

// A table's rows as numpy.loadtxt reads them: '#' lines skipped, five numbers a line.
std::vector<Row> rows_of(const std::string& text, std::vector<std::string>* comments = nullptr) {
    std::vector<Row> rows;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind('#', 0) == 0) {
            if (comments != nullptr) comments->push_back(line);
            continue;
        }
        std::istringstream words(line);
        std::string w[5], extra;
        for (std::string& s : w) words >> s;
        EXPECT_FALSE(words >> extra) << "more than five columns: " << line;
        Row r{};
        double* out[5] = {&r.x, &r.y, &r.z, &r.e, &r.sigma};
        for (int k = 0; k < 5; ++k) {
            char* end = nullptr;
            *out[k] = std::strtod(w[k].c_str(), &end);
            EXPECT_TRUE(!w[k].empty() && *end == '\0') << "not a number: '" << w[k] << "' in " << line;
        }
        rows.push_back(r);
    }
    return rows;
}

std::string read_text(const fs::path& path) {
    std::stringstream ss;
    ss << std::ifstream(path).rdbuf();
    return ss.str();
}

TEST(SensorTable, PathIsTheResultsStemThenTheDetectorsName) {
    EXPECT_EQ(sensor_table_path("out/office.h5", "desk"), fs::path("out/office.desk.txt"));
    EXPECT_EQ(sensor_table_path("office", "desk"), fs::path("office.desk.txt"));
    EXPECT_EQ(sensor_table_path("/a/run.2.h5", "grid_1"), fs::path("/a/run.2.grid_1.txt"));
}

// Honeybee's float-rounded decimals come back exactly; a sensor no photon reached reads
// E 0 with sigma_E nan; the header names the detector, photons and maintenance.
TEST(SensorTable, TextReadsBackInOrderPositionsExactValuesToTheirDigits) {
    SensorTable t;
    t.detector = "grid";
    t.points_file = "room.pts";
    t.radius_m = 0.25;
    t.bands = {"R", "G", "B"};
    t.photons = 1234567;
    t.error_estimator = "independent_photons_eq8";
    t.maintenance_factor = 0.8;
    t.positions = {{0.800000011921, -1.5, 0.75}, {1e-3, 2.0 / 3.0, 1234.5}, {-7, 0, 1e9}};
    t.illuminance_lx = {512.123456789123, 1.0 / 3.0, 0.0};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    t.sigma_lx = {3.14159265358979, 2e-7 / 3.0, nan};
    std::vector<std::string> comments;
    const std::vector<Row> rows = rows_of(format_sensor_table(t), &comments);
    ASSERT_EQ(rows.size(), 3u);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        EXPECT_EQ(rows[k].x, t.positions[k].x) << k;
        EXPECT_EQ(rows[k].y, t.positions[k].y) << k;
        EXPECT_EQ(rows[k].z, t.positions[k].z) << k;
        EXPECT_NEAR(rows[k].e, t.illuminance_lx[k], 5e-9 * std::abs(t.illuminance_lx[k])) << k;
    }
    EXPECT_NEAR(rows[0].sigma, t.sigma_lx[0], 5e-9 * t.sigma_lx[0]);
    EXPECT_NEAR(rows[1].sigma, t.sigma_lx[1], 5e-9 * t.sigma_lx[1]);
    EXPECT_TRUE(std::isnan(rows[2].sigma));
    std::string header;
    for (const std::string& c : comments) header += c + "\n";
    for (const char* word : {"grid", "room.pts", "1234567", "initial", "0.8", "R, G, B", "x y z E sigma_E"})
        EXPECT_NE(header.find(word), std::string::npos) << word << " not in\n" << header;
}

// A 1000 lm point light 1.5 m above the origin, `detector` (a [[detector]] table), 10k photons.
std::string lamp_scene(const std::string& detector) {
    return std::string(kBlackSpeck) + "\n[[light]]\ntype = \"point\"\nposition = [0, 0, 1.5]\nflux_lm = 1000\n\n" +
           detector + "\n[run]\nphotons = 10000\n";
}

// 16 sensors 0.5 m apart in a scrambled order (k -> 7 k mod 16), three bands, under a
// 1000 lm point light 1.5 m above: the table beside the result has one line per sensor in
// the file's order; E is the sum of the result's band values and sigma_E eq. (8) on the
// band-summed n and q, to the printed digits; E is the disc's analytic mean within sigma_E.
TEST(SensorTableRun, OneLinePerSensorInPtsOrderHoldingTheResultsNumbers) {
    ScratchDir dir("sensor_table");
    std::vector<std::pair<double, double>> xy;
    std::ofstream pts(dir.path() / "grid.pts");
    pts << "# a scrambled 4 x 4 grid\n";
    for (int k = 0; k < 16; ++k) {
        const int m = (7 * k) % 16;
        xy.emplace_back(0.5 * (m % 4) - 0.75, 0.5 * (m / 4) - 0.75);
        pts << xy.back().first << ' ' << xy.back().second << " 0 0 0 1\n";
    }
    pts.close();
    const std::string text = std::string(kBlackSpeck) +
                             "\n[scene]\nbands = [\"R\", \"G\", \"B\"]\n"
                             "\n[[light]]\ntype = \"point\"\nposition = [0, 0, 1.5]\nflux_lm = 1000\n"
                             "\n[[detector]]\nname = \"sensors\"\ntype = \"points\"\npoints = \"grid.pts\"\n"
                             "\n[run]\nseed = 3\nphotons = 1000000\n";
    CommandOutcome o;
    const fs::path result = run_scene_text(dir, "s", text, &o);
    ASSERT_EQ(o.code, 0) << o.out;
    const fs::path table = dir.path() / "s.sensors.txt";
    ASSERT_TRUE(fs::exists(table)) << o.out;
    EXPECT_NE(o.out.find("sensor table: " + fs::absolute(table).string() + "\n"), std::string::npos) << o.out;

    const ResultReader r(result);
    const std::string g = "/detectors/sensors";
    const std::vector<double> value = r.f64(g + "/value");
    const std::vector<std::uint64_t> count = r.u64(g + "/count"), sumsq = r.u64(g + "/sumsq");
    const double photons = static_cast<double>(r.attr_u64("/", "photons"));
    std::vector<std::string> comments;
    const std::vector<Row> rows = rows_of(read_text(table), &comments);
    ASSERT_EQ(rows.size(), 16u);
    ASSERT_EQ(value.size(), 16u * 3u);
    ZPool pool("sensor_table");
    const double intensity = 1000.0 / (4.0 * kPi);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        EXPECT_EQ(rows[k].x, xy[k].first) << k;
        EXPECT_EQ(rows[k].y, xy[k].second) << k;
        EXPECT_EQ(rows[k].z, 0.0) << k;
        double e = 0.0, n = 0.0, q = 0.0;
        for (std::size_t b = 0; b < 3; ++b) {
            e += value[3 * k + b];
            n += static_cast<double>(count[3 * k + b]);
            q += static_cast<double>(sumsq[3 * k + b]);
        }
        ASSERT_GT(n, 0.0) << k;
        const double sigma = e * std::sqrt(q / (n * n) - 1.0 / photons);
        EXPECT_NEAR(rows[k].e, e, 1e-8 * e) << k;
        EXPECT_NEAR(rows[k].sigma, sigma, 1e-8 * sigma) << k;
        pool.add("sensor " + std::to_string(k), rows[k].e, rows[k].sigma,
                 disc_average(intensity, 1.5, xy[k].first, xy[k].second, 0.25));
    }
    pool.check("point light, table against the disc means");
    std::string header;
    for (const std::string& c : comments) header += c + "\n";
    EXPECT_NE(header.find("photons traced: " + std::to_string(r.attr_u64("/", "photons"))), std::string::npos)
        << header;
}

TEST(SensorTableRun, NoTableWithoutAPointsDetector) {
    ScratchDir dir("sensor_table_none");
    const std::string text = lamp_scene(
        "[[detector]]\nname = \"cells\"\ncenter = [0, 0, 0]\nsize = [1, 1]\ncells = [2, 2]\n");
    CommandOutcome o;
    run_scene_text(dir, "s", text, &o);
    ASSERT_EQ(o.code, 0) << o.out;
    EXPECT_TRUE(fs::exists(dir.path() / "s.h5"));
    for (const fs::directory_entry& f : fs::directory_iterator(dir.path()))
        EXPECT_NE(f.path().extension(), ".txt") << f.path();
    EXPECT_EQ(o.out.find("sensor table"), std::string::npos) << o.out;
}

// A table that cannot be written (a folder in its place) warns; the result is kept, exit 0.
TEST(SensorTableRun, ATableThatCannotBeWrittenWarnsAndTheResultStays) {
    ScratchDir dir("sensor_table_blocked");
    std::ofstream(dir.path() / "grid.pts") << "0 0 0 0 0 1\n0 0.5 0 0 0 1\n";
    fs::create_directories(dir.path() / "s.sensors.txt" / "inside");
    const std::string text = lamp_scene("[[detector]]\nname = \"sensors\"\ntype = \"points\"\npoints = \"grid.pts\"\n");
    CommandOutcome o;
    run_scene_text(dir, "s", text, &o);
    EXPECT_EQ(o.code, 0) << o.out;
    EXPECT_TRUE(fs::exists(dir.path() / "s.h5"));
    EXPECT_NE(o.out.find("warning: sensor table not written: "), std::string::npos) << o.out;
    EXPECT_EQ(o.out.find("sensor table: "), std::string::npos) << o.out;
}

// A malformed .pts line: exit 2 naming the file and line, and neither result nor table.
TEST(SensorTableRun, BadPtsFileWritesNothing) {
    ScratchDir dir("sensor_table_bad");
    std::ofstream(dir.path() / "grid.pts") << "0 0 0 0 0 1\n0 0.5 0 0 0\n";
    const std::string text = lamp_scene(
        "[[detector]]\nname = \"sensors\"\ntype = \"points\"\npoints = \"grid.pts\"\nradius_m = 0.1\n");
    CommandOutcome o;
    run_scene_text(dir, "s", text, &o);
    EXPECT_EQ(o.code, 2) << o.out;
    EXPECT_NE(o.out.find("grid.pts:2:"), std::string::npos) << o.out;
    EXPECT_FALSE(fs::exists(dir.path() / "s.h5"));
    EXPECT_FALSE(fs::exists(dir.path() / "s.sensors.txt"));
}

}  // namespace
}  // namespace luxtrace
