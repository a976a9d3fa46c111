#include "luxtrace/render/image_io.hpp"

#include "luxtrace/render/tone_map.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <cairo.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace luxtrace {

namespace fs = std::filesystem;

LuminanceImage::LuminanceImage(int w, int h, std::vector<std::string> band_names)
    : width(w), height(h), bands(std::move(band_names)), values(static_cast<std::size_t>(w) * h * bands.size(), 0.0f) {}

double LuminanceImage::luminance(int x, int y) const {
    double s = 0.0;
    for (int b = 0; b < band_count(); ++b) s += at(x, y, b);
    return s;
}

std::vector<double> LuminanceImage::luminance() const {
    std::vector<double> out(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) out[static_cast<std::size_t>(y) * width + x] = luminance(x, y);
    return out;
}

bool LuminanceImage::is_rgb() const {
    return bands.size() == 3 && bands[0] == "R" && bands[1] == "G" && bands[2] == "B";
}

namespace {

// A temporary name in the target's folder, so the final rename is atomic.
fs::path temporary_for(const fs::path& path) {
    std::string name = ".";  // built in steps: GCC 12 warns falsely (-Wrestrict) on "." + string
    name += path.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    return path.parent_path() / name;
}

void commit(const fs::path& tmp, const fs::path& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(path.string() + ": cannot write (" + ec.message() + ")");
    }
}

std::string tick_label(double v) {
    char buf[32];
    const double a = std::abs(v);
    if (a != 0.0 && (a >= 1e5 || a < 1e-3)) std::snprintf(buf, sizeof buf, "%.0e", v);
    else std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

int legend_font_px(int image_height) { return std::clamp(image_height / 36, 11, 20); }

void draw_legend(cairo_t* cr, const FalseColourScale& scale, int x0, int height) {
    const int fs = legend_font_px(height);
    const int panel = legend_panel_width(height);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_rectangle(cr, x0, 0, panel, height);
    cairo_fill(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fs);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_text_extents_t ext;
    const char* units = "cd/m\xc2\xb2";  // UTF-8 superscript two
    cairo_text_extents(cr, units, &ext);
    cairo_move_to(cr, x0 + 0.5 * (panel - ext.x_advance), 1.4 * fs);
    cairo_show_text(cr, units);

    const double bar_x = x0 + 0.15 * panel, bar_w = std::max(8.0, 0.16 * panel);
    const double top = 2.4 * fs, bottom = height - 1.0 * fs;
    if (bottom - top < 4.0) return;
    // The bar, one row at a time, brightest at the top.
    for (int y = static_cast<int>(top); y < static_cast<int>(bottom); ++y) {
        const std::array<double, 3> c = colour_map((bottom - (y + 0.5)) / (bottom - top));
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_rectangle(cr, bar_x, y, bar_w, 1.0);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, bar_x + 0.5, std::floor(top) + 0.5, bar_w - 1.0, std::floor(bottom) - std::floor(top) - 1.0);
    cairo_stroke(cr);
    for (double v : scale.ticks()) {
        const double y = std::round(bottom - scale.position(v) * (bottom - top)) + 0.5;
        cairo_move_to(cr, bar_x + bar_w, y);
        cairo_line_to(cr, bar_x + bar_w + 0.4 * fs, y);
        cairo_stroke(cr);
        const std::string label = tick_label(v);
        cairo_text_extents(cr, label.c_str(), &ext);
        cairo_move_to(cr, bar_x + bar_w + 0.6 * fs, y - ext.y_bearing - 0.5 * ext.height);
        cairo_show_text(cr, label.c_str());
    }
}

}  // namespace

int legend_panel_width(int image_height) { return 40 + 5 * legend_font_px(image_height); }

void write_exr(const fs::path& path, const LuminanceImage& image) {
    const fs::path tmp = temporary_for(path);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        header.insert("luxtrace:units",
                      Imf::StringAttribute("cd/m^2 per band; the luminance is the sum of the channels"));
        const std::size_t nb = image.bands.size();
        Imf::FrameBuffer frame;
        for (std::size_t b = 0; b < nb; ++b) {
            header.channels().insert(image.bands[b], Imf::Channel(Imf::FLOAT));
            // Slice base pointer is for pixel (0, 0): the data window starts at the origin.
            frame.insert(image.bands[b],
                         Imf::Slice(Imf::FLOAT,
                                    const_cast<char*>(reinterpret_cast<const char*>(image.values.data() + b)),
                                    sizeof(float) * nb, sizeof(float) * nb * image.width));
        }
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
    } catch (const std::exception& e) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error(path.string() + ": cannot write OpenEXR: " + e.what());
    }
    commit(tmp, path);
}

void write_png(const fs::path& path, const DisplayImage& image, const FalseColourScale* legend) {
    const int width = image.width + (legend != nullptr ? legend_panel_width(image.height) : 0);
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, image.height);
    if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surface);
        throw std::runtime_error(path.string() + ": cannot make a " + std::to_string(width) + "x" +
                                 std::to_string(image.height) + " image");
    }
    cairo_surface_flush(surface);
    unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    for (int y = 0; y < image.height; ++y) {
        auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.pixel(x, y);
            row[x] = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | std::uint32_t{p[2]};
        }
    }
    cairo_surface_mark_dirty(surface);
    if (legend != nullptr) {
        cairo_t* cr = cairo_create(surface);
        draw_legend(cr, *legend, image.width, image.height);
        cairo_destroy(cr);
    }
    const fs::path tmp = temporary_for(path);
    const cairo_status_t st = cairo_surface_write_to_png(surface, tmp.c_str());
    cairo_surface_destroy(surface);
    if (st != CAIRO_STATUS_SUCCESS) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error(path.string() + ": cannot write PNG: " + cairo_status_to_string(st));
    }
    commit(tmp, path);
}

}  // namespace luxtrace
