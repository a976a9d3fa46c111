#include "cie171_cases.hpp"

#include <cmath>

namespace luxtrace::cie171 {
namespace {

using daylight_reference::Polygon;
using daylight_reference::rectangle;

constexpr double kDeg = kPi / 180.0;

// 5.9 / 5.10: A-F on the north wall (facing south) at x = 2, z = 2.75 ... 0.25; G-N on the
// floor at x = 2 from y = 3.75 (beside that wall) to y = 0.25.
std::vector<Point> roof_points() {
    std::vector<Point> p;
    const char* wall = "ABCDEF";
    for (int i = 0; i < 6; ++i) p.push_back({std::string(1, wall[i]), Vec3(2.0, 4.0, 2.75 - 0.5 * i), Vec3(0, -1, 0)});
    const char* floor = "GHIJKLMN";
    for (int i = 0; i < 8; ++i) p.push_back({std::string(1, floor[i]), Vec3(2.0, 3.75 - 0.5 * i, 0.0), Vec3(0, 0, 1)});
    return p;
}

// 5.11-5.14: the floor points at x = 2 from y = 3.75 (back wall) to y = 0.25 (facade),
// labelled G-N in §5.11/5.12 and A-H in §5.13/5.14.
std::vector<Point> facade_floor_points(const char* labels) {
    std::vector<Point> p;
    for (int i = 0; i < 8; ++i) p.push_back({std::string(1, labels[i]), Vec3(2.0, 3.75 - 0.5 * i, 0.0), Vec3(0, 0, 1)});
    return p;
}

Polygon roof_opening(double size) { return rectangle(Vec3(2, 2, 3), Vec3(0.5 * size, 0, 0), Vec3(0, 0.5 * size, 0)); }
Polygon window_2x1() { return rectangle(Vec3(2, 0, 1.5), Vec3(1, 0, 0), Vec3(0, 0, 0.5)); }
Polygon window_4x3() { return rectangle(Vec3(2, 0, 1.5), Vec3(2, 0, 0), Vec3(0, 0, 1.5)); }

// The report's overhang is wider than the room: its point H (and G under the 2 m mask) reads
// the same for every sky, i.e. sees no sky at all. 400 m hides every ray of these points.
Polygon overhang(double depth_m) {
    return rectangle(Vec3(2, -0.5 * depth_m, 3), Vec3(200, 0, 0), Vec3(0, 0.5 * depth_m, 0));
}
// The obstructing wall 6 m in front of the facade, parallel to it, taken as 1 km long.
Polygon front_wall(double height_m) {
    return rectangle(Vec3(2, -6, 0.5 * height_m), Vec3(500, 0, 0), Vec3(0, 0, 0.5 * height_m));
}

}  // namespace

SkyModel report_sky(int cie_type) {
    if (cie_type == 0) return SkyModel::uniform();
    return SkyModel::cie(cie_type, (90.0 - kSunAltitudeDeg) * kDeg, kSunAzimuthDeg * kDeg);
}

double exact_sc_percent(const Case& c, const Point& p, int cie_type) {
    const daylight_reference::SkyComponentQuery q{p.position, p.normal, c.opening, c.obstructions,
                                                  c.glazed ? daylight_reference::clear_glass_6mm()
                                                           : daylight_reference::Transmittance{}};
    return 100.0 * daylight_reference::sky_component(report_sky(cie_type), q, 1e-9);
}

// Published values: CIE 171:2006 Appendix B (decimal commas read as points), rows for sky
// types 1, 5, 12 and 16.
std::vector<Case> report_cases() {
    std::vector<Case> cases;
    const std::string roof = "4 m x 4 m x 3 m room, black inside, ";
    cases.push_back({"5.9 1x1",
                     roof + "unglazed 1 m x 1 m opening in the middle of the roof",
                     "B.1, B.2",
                     roof_opening(1.0),
                     {},
                     false,
                     false,
                     roof_points(),
                     {{0.46, 1.64, 2.34, 2.26, 1.88, 1.47, 2.33, 3.11, 3.84, 4.29, 4.29, 3.84, 3.11, 2.33},
                      {1.04, 2.39, 2.59, 2.20, 1.70, 1.27, 1.95, 2.52, 3.04, 3.37, 3.37, 3.04, 2.52, 1.95},
                      {1.74, 3.76, 4.55, 4.61, 4.24, 3.63, 5.72, 6.01, 5.12, 3.97, 2.90, 2.03, 1.40, 0.96},
                      {0.56, 1.78, 2.32, 2.20, 1.82, 1.43, 2.29, 3.07, 3.82, 4.29, 4.29, 3.82, 3.07, 2.29}}});
    cases.push_back(
        {"5.9 4x4",
         roof + "the whole roof (4 m x 4 m) open, unglazed",
         "B.3, B.4",
         roof_opening(4.0),
         {},
         false,
         false,
         roof_points(),
         {{37.84, 31.72, 26.85, 22.10, 17.89, 14.38, 31.87, 37.30, 41.27, 43.35, 43.35, 41.27, 37.30, 31.87},
          {46.74, 36.05, 28.05, 21.67, 16.73, 12.98, 26.80, 30.95, 33.99, 35.58, 35.58, 33.99, 30.95, 26.80},
          {66.34, 54.33, 44.25, 36.10, 29.48, 24.25, 42.33, 43.82, 43.54, 40.85, 35.92, 29.17, 22.62, 16.79},
          {39.28, 32.32, 26.79, 21.78, 17.53, 14.05, 31.36, 36.76, 40.71, 42.76, 42.76, 40.71, 36.76, 31.36}}});
    cases.push_back({"5.10 1x1",
                     roof + "1 m x 1 m roof opening glazed with 6 mm clear glass",
                     "B.5, B.6",
                     roof_opening(1.0),
                     {},
                     true,
                     false,
                     roof_points(),
                     {{0.15, 1.17, 1.91, 1.92, 1.62, 1.28, 2.04, 2.73, 3.38, 3.78, 3.78, 3.38, 2.73, 2.04},
                      {0.35, 1.69, 2.12, 1.87, 1.47, 1.11, 1.71, 2.22, 2.68, 2.96, 2.96, 2.68, 2.22, 1.71},
                      {0.58, 2.65, 3.72, 3.92, 3.66, 3.16, 5.01, 5.28, 4.51, 3.49, 2.55, 1.79, 1.23, 0.84},
                      {0.19, 1.26, 1.90, 1.87, 1.57, 1.24, 2.00, 2.70, 3.36, 3.78, 3.78, 3.36, 2.70, 2.00}}});
    cases.push_back(
        {"5.10 4x4",
         roof + "the whole roof glazed with 6 mm clear glass",
         "B.7, B.8",
         roof_opening(4.0),
         {},
         true,
         false,
         roof_points(),
         {{28.64, 25.36, 22.25, 18.71, 15.34, 12.43, 27.88, 32.69, 36.22, 38.07, 38.07, 36.22, 32.69, 27.88},
          {32.66, 27.87, 22.92, 18.23, 14.31, 11.20, 23.43, 27.12, 29.83, 31.25, 31.25, 29.83, 27.12, 23.43},
          {46.30, 42.34, 36.37, 30.47, 25.25, 20.95, 36.96, 38.34, 38.16, 35.86, 31.56, 25.63, 19.85, 14.71},
          {29.21, 25.63, 22.14, 18.43, 15.03, 12.15, 27.44, 32.23, 35.73, 37.56, 37.56, 35.73, 32.23, 27.44}}});
    const std::string facade = "4 m x 4 m x 3 m room, black inside, south facade with ";
    const char* gn = "GHIJKLMN";
    cases.push_back({"5.11 2x1",
                     facade + "an unglazed 2 m x 1 m opening, sill 1 m (floor points)",
                     "B.10",
                     window_2x1(),
                     {},
                     false,
                     false,
                     facade_floor_points(gn),
                     {{0.87, 1.31, 2.02, 3.20, 5.07, 7.64, 9.33, 5.09},
                      {1.27, 1.75, 2.49, 3.59, 5.19, 7.11, 7.99, 4.13},
                      {2.00, 2.80, 4.06, 6.13, 9.54, 14.57, 16.35, 5.03},
                      {0.95, 1.38, 2.07, 3.19, 4.97, 7.42, 9.11, 5.04}}});
    cases.push_back({"5.11 4x3",
                     facade + "the whole facade (4 m x 3 m) open (floor points)",
                     "B.13",
                     window_4x3(),
                     {},
                     false,
                     false,
                     facade_floor_points(gn),
                     {{4.27, 5.92, 8.33, 11.82, 16.84, 23.83, 33.05, 44.06},
                      {5.79, 7.63, 10.20, 13.78, 18.76, 25.50, 34.24, 45.29},
                      {9.26, 12.35, 16.79, 23.17, 32.10, 43.03, 54.44, 65.07},
                      {4.50, 6.15, 8.53, 12.00, 16.97, 23.91, 33.08, 44.43}}});
    cases.push_back({"5.12 2x1",
                     facade + "the 2 m x 1 m opening glazed with 6 mm clear glass (floor points)",
                     "B.16",
                     window_2x1(),
                     {},
                     true,
                     false,
                     facade_floor_points(gn),
                     {{0.77, 1.15, 1.77, 2.79, 4.38, 6.44, 7.19, 2.16},
                      {1.11, 1.54, 2.18, 3.13, 4.47, 6.00, 6.17, 1.75},
                      {1.75, 2.45, 3.55, 5.34, 8.23, 12.28, 12.69, 2.16},
                      {0.83, 1.21, 1.81, 2.78, 4.28, 6.26, 7.02, 2.13}}});
    cases.push_back({"5.12 4x3",
                     facade + "the whole facade glazed with 6 mm clear glass (floor points)",
                     "B.19",
                     window_4x3(),
                     {},
                     true,
                     false,
                     facade_floor_points(gn),
                     {{3.74, 5.17, 7.23, 10.18, 14.30, 19.66, 25.63, 30.02},
                      {5.07, 6.67, 8.87, 11.91, 16.00, 21.21, 26.96, 31.84},
                      {8.11, 10.79, 14.60, 20.00, 27.33, 35.75, 43.26, 47.73},
                      {3.94, 5.36, 7.41, 10.34, 14.42, 19.74, 25.70, 30.40}}});
    const char* ah = "ABCDEFGH";
    const std::string mask = facade + "the unglazed 2 m x 1 m opening and ";
    cases.push_back({"5.13 0.5 m",
                     mask + "a 0.5 m deep overhang at the top of the facade (z = 3 m)",
                     "B.21",
                     window_2x1(),
                     {overhang(0.5)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.87, 1.31, 2.02, 3.20, 5.07, 7.64, 8.27, 0.21},
                      {1.27, 1.75, 2.49, 3.59, 5.19, 7.11, 7.13, 0.21},
                      {2.00, 2.80, 4.06, 6.13, 9.54, 14.57, 14.68, 0.21},
                      {0.95, 1.38, 2.07, 3.19, 4.97, 7.42, 8.07, 0.21}}});
    cases.push_back({"5.13 1.0 m",
                     mask + "a 1 m deep overhang",
                     "B.22",
                     window_2x1(),
                     {overhang(1.0)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.87, 1.31, 2.02, 3.20, 5.07, 7.64, 5.69, 0.21},
                      {1.27, 1.75, 2.49, 3.59, 4.82, 5.42, 3.63, 0.21},
                      {2.00, 2.80, 4.06, 6.13, 8.73, 10.46, 7.25, 0.21},
                      {2.22, 3.12, 4.57, 6.99, 10.13, 12.33, 8.73, 0.41}}});
    cases.push_back({"5.13 2.0 m",
                     mask + "a 2 m deep overhang",
                     "B.23",
                     window_2x1(),
                     {overhang(2.0)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.83, 1.09, 1.44, 1.88, 2.22, 1.72, 0.40, 0.21},
                      {1.21, 1.50, 1.86, 2.24, 2.44, 1.73, 0.40, 0.21},
                      {1.90, 2.36, 2.94, 3.58, 3.97, 2.82, 0.40, 0.21},
                      {0.90, 1.16, 1.50, 1.90, 2.20, 1.68, 0.40, 0.21}}});
    cases.push_back({"5.14 3 m",
                     mask + "a 3 m high wall 6 m in front of the facade, parallel to it",
                     "B.24",
                     window_2x1(),
                     {front_wall(3.0)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.82, 1.28, 2.02, 3.20, 5.07, 7.64, 9.33, 5.09},
                      {1.15, 1.70, 2.49, 3.59, 5.19, 7.11, 7.99, 4.13},
                      {1.78, 2.69, 4.06, 6.13, 9.54, 14.57, 16.35, 5.03},
                      {0.88, 1.34, 2.07, 3.19, 4.97, 7.42, 9.11, 5.04}}});
    cases.push_back({"5.14 6 m",
                     mask + "a 6 m high wall 6 m in front",
                     "B.25",
                     window_2x1(),
                     {front_wall(6.0)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.41, 0.47, 0.79, 1.79, 3.725, 7.40, 9.33, 5.09},
                      {0.51, 0.59, 0.95, 1.96, 3.751, 6.89, 7.99, 4.13},
                      {0.38, 0.44, 0.99, 2.84, 6.611, 14.07, 16.35, 5.03},
                      {0.42, 0.48, 0.81, 1.78, 3.650, 7.19, 9.11, 5.04}}});
    cases.push_back({"5.14 9 m",
                     mask + "a 9 m high wall 6 m in front",
                     "B.26",
                     window_2x1(),
                     {front_wall(9.0)},
                     false,
                     true,
                     facade_floor_points(ah),
                     {{0.77, 0.90, 1.04, 1.19, 1.27, 3.97, 9.33, 5.09},
                      {0.97, 1.12, 1.30, 1.48, 1.59, 3.90, 7.99, 4.13},
                      {0.72, 0.84, 0.97, 1.10, 1.19, 1.02, 16.35, 5.03},
                      {0.80, 0.93, 1.08, 1.23, 1.32, 3.93, 9.11, 5.04}}});
    return cases;
}

std::vector<RunCase> run_cases() {
    // 3 m wide cells (x 0.5 ... 3.5 m), clear of the side walls.
    const Strip floor{"floor", Vec3(2, 0.25, 0.001), Vec3(0, 0.5, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), 3.0, 8};
    const Strip wall{"wall", Vec3(2, 3.999, 0.25), Vec3(0, 0, 0.5), Vec3(0, -1, 0), Vec3(1, 0, 0), 3.0, 6};
    const Polygon overhang_4m = rectangle(Vec3(2, -0.5, 3), Vec3(2, 0, 0), Vec3(0, 0.5, 0));
    const Polygon wall_12m = rectangle(Vec3(2, -6, 3), Vec3(6, 0, 0), Vec3(0, 0, 3));
    return {{"roof_4x4_cie12", "5.9", 12, false, roof_opening(4.0), {}, {floor, wall}, 8'000'000, 171},
            {"roof_4x4_cie16_glazed", "5.10", 16, true, roof_opening(4.0), {}, {floor, wall}, 8'000'000, 172},
            {"facade_4x3_cie5", "5.11", 5, false, window_4x3(), {}, {floor}, 16'000'000, 173},
            {"facade_4x3_cie1_glazed", "5.12", 1, true, window_4x3(), {}, {floor}, 16'000'000, 174},
            {"facade_2x1_overhang_cie12", "5.13", 12, false, window_2x1(), {overhang_4m}, {floor}, 32'000'000, 175},
            {"facade_2x1_wall_cie16", "5.14", 16, false, window_2x1(), {wall_12m}, {floor}, 128'000'000, 176}};
}

// A 4 x 4 Gauss-Legendre rule on each 1 m x 0.5 m part of a cell agrees with one on parts
// eight times smaller to 2e-4 relative in every cell of run_cases() (the masks' edges put
// kinks in the integrand), a tenth of the runs' 1-2 % errors, in a few seconds.
constexpr double kPartWidthM = 1.0;

double exact_cell_lx(const RunCase& rc, const Strip& s, int k) {
    static constexpr double kNodes[] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                        0.8611363115940526};
    static constexpr double kWeights[] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                          0.3478548451374538};
    const SkyModel sky = report_sky(rc.cie_type);
    const Vec3 center = s.first_center + static_cast<double>(k) * s.step;
    const Vec3 along = glm::normalize(s.step);
    const int parts = static_cast<int>(std::lround(s.width_m / kPartWidthM));
    const daylight_reference::Transmittance t = rc.glazed ? daylight_reference::clear_glass_6mm()
                                                          : daylight_reference::Transmittance{};
    double sum = 0.0;
    for (int part = 0; part < parts; ++part) {
        const Vec3 part_center = center + (kPartWidthM * (part + 0.5) - 0.5 * s.width_m) * s.across;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const Vec3 p = part_center + 0.5 * kPartWidthM * kNodes[i] * s.across + 0.25 * kNodes[j] * along;
                const daylight_reference::SkyComponentQuery q{p, s.normal, rc.opening, rc.obstructions, t};
                sum += 0.25 * kWeights[i] * kWeights[j] * daylight_reference::sky_component(sky, q, 1e-5);
            }
    }
    return kDiffuseHorizontalLx * sum / parts;
}

}  // namespace luxtrace::cie171
