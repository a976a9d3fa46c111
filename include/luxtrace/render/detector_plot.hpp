#pragma once
// Detector pictures (PNG, drawn with cairo) from a result file: the value map in lux or
// cd/m^2, the relative error per cell, the histogram of those errors and sections
// through one cell. `luxtrace render RESULT --detector NAME` draws them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

namespace luxtrace {

// Writes into `out_dir` (created if missing), each file atomically:
//   NAME_value.png       false-colour map with colour bar; row 0 at the bottom, so the
//                        detector's `up` points up and its u = up x normal to the right
//                        (as seen from the front side)
//   NAME_error.png       relative error per cell (eq. 8) in %, cells without hits marked
//   NAME_error_hist.png  histogram of the per-cell relative errors, eq. (9) values marked
//   NAME_sections.png    row and column through `cell`: value with a +-1 sigma band
// `cell` is "i,j" (column i along u, row j along up) or empty for the brightest cell.
// With several bands the pictures show the band sum (the titles say so).
// Throws InputError for an unknown detector, a bad cell or a file that is not a result.
void render_detector_pictures(const std::filesystem::path& result, const std::string& detector,
                              const std::string& cell, const std::filesystem::path& out_dir);

// Geometry of the two map pictures: cells are blocks of cell_w x cell_h pixels with the
// detector's aspect ratio, about 640 pixels on the longer side; margins hold the title,
// the axes and the colour bar.
struct DetectorMapLayout {
    int width = 0, height = 0;          // whole picture
    int map_x = 0, map_y = 0;           // top-left corner of the map
    int map_w = 0, map_h = 0;           // = nx * cell_w, ny * cell_h
    int cell_w = 1, cell_h = 1;
};

inline DetectorMapLayout detector_map_layout(int nx, int ny, double size_u, double size_v) {
    constexpr int kTarget = 640, kLeft = 96, kRight = 170, kTop = 78, kBottom = 72;
    constexpr int kMinWidth = 760, kMinArea = 240;  // room for the title and the colour bar
    DetectorMapLayout l;
    const double aspect = (size_v / ny) / (size_u / nx);  // cell height / cell width
    l.cell_w = std::max(1, kTarget / nx);
    l.cell_h = std::max(1, static_cast<int>(std::lround(l.cell_w * aspect)));
    if (ny * l.cell_h > kTarget) {
        l.cell_h = std::max(1, kTarget / ny);
        l.cell_w = std::max(1, static_cast<int>(std::lround(l.cell_h / aspect)));
    }
    l.map_w = nx * l.cell_w;
    l.map_h = ny * l.cell_h;
    l.map_x = kLeft;
    l.map_y = kTop;
    l.width = std::max(kLeft + l.map_w + kRight, kMinWidth);
    l.height = kTop + std::max(l.map_h, kMinArea) + kBottom;
    return l;
}

// Fixed sizes of the histogram and sections pictures.
constexpr int kDetectorHistWidth = 800, kDetectorHistHeight = 500;
constexpr int kDetectorSectionsWidth = 800, kDetectorSectionsHeight = 760;

}  // namespace luxtrace
