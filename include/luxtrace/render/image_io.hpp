#pragma once
// Images of `luxtrace render`: the luminance image in cd/m^2 (one float per band) and
// the 8-bit display image made from it by tone mapping; writing them as OpenEXR and PNG.
// Both writers are atomic: a temporary file in the target's folder, then rename.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

struct FalseColourScale;

// Luminance per band in cd/m^2, row 0 at the top. With the scene's bands as channels;
// the photometric luminance of a pixel is the sum over its bands (each band carries its
// share of the lumens, SPEC §3).
struct LuminanceImage {
    int width = 0, height = 0;
    std::vector<std::string> bands;
    std::vector<float> values;  // [y][x][band]

    LuminanceImage() = default;
    LuminanceImage(int w, int h, std::vector<std::string> band_names);
    int band_count() const { return static_cast<int>(bands.size()); }
    float& at(int x, int y, int b) { return values[(static_cast<std::size_t>(y) * width + x) * bands.size() + b]; }
    float at(int x, int y, int b) const { return values[(static_cast<std::size_t>(y) * width + x) * bands.size() + b]; }
    double luminance(int x, int y) const;   // sum over bands
    std::vector<double> luminance() const;  // per pixel, row-major
    // Three bands named R, G, B: shown in colour; anything else is shown grey.
    bool is_rgb() const;
};

// 8-bit RGB for display, row 0 at the top.
struct DisplayImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb;  // [y][x][3]

    DisplayImage() = default;
    DisplayImage(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}
    std::uint8_t* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
    const std::uint8_t* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

// Float OpenEXR with one channel per band, named after the band ("Y" or "R","G","B"),
// values in cd/m^2; header attribute "luxtrace:units". Throws std::runtime_error.
void write_exr(const std::filesystem::path& path, const LuminanceImage& image);

// PNG through cairo. With `legend`, a vertical colour bar with labelled ticks in cd/m^2
// is drawn in a panel to the right of the picture (the PNG is then wider than the
// picture by legend_panel_width(height) pixels). Throws std::runtime_error.
void write_png(const std::filesystem::path& path, const DisplayImage& image, const FalseColourScale* legend = nullptr);
int legend_panel_width(int image_height);

}  // namespace luxtrace
