// Detector pictures with cairo: maps, error histogram, sections (see detector_plot.hpp).
#include "luxtrace/render/detector_plot.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_file.hpp"

#include <cairo.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------- colour maps
// Perceptually ordered maps computed here: a path through CIELAB with lightness rising
// linearly (so the order of values reads as the order of brightness, also in grey print)
// while the hue turns; chroma is cut back where the path would leave the sRGB gamut.
struct Rgb { double r, g, b; };

double srgb_gamma(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

// Linear sRGB of a CIELAB colour (D65); components may fall outside [0, 1].
Rgb lab_to_linear(double L, double a, double b) {
    const double fy = (L + 16.0) / 116.0, fx = fy + a / 500.0, fz = fy - b / 200.0;
    auto finv = [](double t) { return t > 6.0 / 29.0 ? t * t * t : 3.0 * (6.0 / 29.0) * (6.0 / 29.0) * (t - 4.0 / 29.0); };
    const double X = 0.95047 * finv(fx), Y = finv(fy), Z = 1.08883 * finv(fz);
    return {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
            0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
}

class ColourMap {
public:
    // Lightness l0 -> l1, hue h0 -> h1 (degrees), chroma quadratic c0 + c1 t + c2 t^2.
    ColourMap(double l0, double l1, double h0, double h1, double c0, double c1, double c2) {
        for (int k = 0; k < kN; ++k) {
            const double t = k / double(kN - 1);
            const double L = l0 + (l1 - l0) * t, h = (h0 + (h1 - h0) * t) * kPi / 180.0;
            const double c_want = std::max(0.0, c0 + c1 * t + c2 * t * t);
            auto at = [&](double c) { return lab_to_linear(L, c * std::cos(h), c * std::sin(h)); };
            auto inside = [](const Rgb& x) { return x.r >= 0 && x.r <= 1 && x.g >= 0 && x.g <= 1 && x.b >= 0 && x.b <= 1; };
            double c = c_want;
            if (!inside(at(c))) {  // the largest chroma still in gamut
                double lo = 0.0, hi = c;
                for (int it = 0; it < 30; ++it) (inside(at(0.5 * (lo + hi))) ? lo : hi) = 0.5 * (lo + hi);
                c = lo;
            }
            const Rgb x = at(c);
            table_[k] = {srgb_gamma(std::clamp(x.r, 0.0, 1.0)), srgb_gamma(std::clamp(x.g, 0.0, 1.0)),
                         srgb_gamma(std::clamp(x.b, 0.0, 1.0))};
        }
    }
    Rgb operator()(double t) const {
        if (!std::isfinite(t)) t = 0.0;
        return table_[static_cast<std::size_t>(std::lround(std::clamp(t, 0.0, 1.0) * (kN - 1)))];
    }

private:
    static constexpr int kN = 256;
    std::array<Rgb, kN> table_{};
};

// Values: dark violet -> blue -> teal -> green -> yellow. Errors: black-violet -> red -> yellow.
const ColourMap& value_map() {
    static const ColourMap m(18.0, 92.0, 315.0, 97.0, 52.0, -110.0, 144.0);
    return m;
}
const ColourMap& error_map() {
    static const ColourMap m(10.0, 94.0, 300.0, 460.0, 35.0, 120.0, -95.0);
    return m;
}
const Rgb kNoHit{0.62, 0.62, 0.62};

// ---------------------------------------------------------------- the data
// Units as printed: cd/m^2 with a superscript.
std::string units_text(const std::string& u) { return u == "cd/m^2" ? "cd/m\u00b2" : u; }

struct DetectorData {
    std::string name, type, units, band_note;
    int nx = 1, ny = 1;
    double size_u = 1, size_v = 1;
    std::array<double, 3> u{}, up{};
    std::vector<double> value, sigma_rel;  // [ny * nx], band-summed; sigma_rel NaN: no hits
    double mean_value = 0, mean_sigma_rel = 0, rel_arith = 0, rel_quad = 0;
    std::uint64_t received = 0, photons = 0;
    double at(int i, int j) const { return value[static_cast<std::size_t>(j) * nx + i]; }
    double rel(int i, int j) const { return sigma_rel[static_cast<std::size_t>(j) * nx + i]; }
};

std::array<double, 3> vec3(const std::vector<double>& v) {
    return v.size() == 3 ? std::array<double, 3>{v[0], v[1], v[2]} : std::array<double, 3>{0, 0, 0};
}

DetectorData read_detector(const fs::path& result, const std::string& name) {
    const ResultReader r(result);
    const std::string g = "/detectors/" + name;
    if (name.empty() || name.find('/') != std::string::npos || !r.has(g)) {
        std::string known;
        for (const std::string& n : r.children("/detectors")) known += (known.empty() ? "" : ", ") + n;
        throw InputError(result.string() + ": no detector '" + name + "' (the file has: " +
                         (known.empty() ? "none" : known) + ")");
    }
    DetectorData d;
    d.name = name;
    d.type = r.attr_str(g, "type");
    d.units = units_text(r.attr_str(g, "units"));
    const std::vector<double> cells = r.f64_attr_array(g, "cells"), size = r.f64_attr_array(g, "size");
    // The scene loader's limits: whole cells, at most 1e8 of them, a positive finite size.
    if (cells.size() != 2 || !(cells[0] >= 1 && cells[1] >= 1 && cells[0] * cells[1] <= 1e8) ||
        cells[0] != std::floor(cells[0]) || cells[1] != std::floor(cells[1]))
        throw InputError(result.string() + ": " + g + "@cells is damaged");
    if (size.size() != 2 || !(size[0] > 0 && size[1] > 0 && std::isfinite(size[0]) && std::isfinite(size[1])))
        throw InputError(result.string() + ": " + g + "@size is damaged");
    d.nx = static_cast<int>(cells[0]);
    d.ny = static_cast<int>(cells[1]);
    d.size_u = size[0];
    d.size_v = size[1];
    const auto n = vec3(r.f64_attr_array(g, "normal"));
    d.up = vec3(r.f64_attr_array(g, "up"));
    const auto& v = d.up;  // u = up x normal (Detector::finalize)
    d.u = {v[1] * n[2] - v[2] * n[1], v[2] * n[0] - v[0] * n[2], v[0] * n[1] - v[1] * n[0]};
    d.mean_value = r.attr_f64(g, "mean_value");
    d.mean_sigma_rel = r.attr_f64(g, "mean_sigma_rel");
    d.rel_arith = r.attr_f64(g, "sigma_rel_arithmetic");
    d.rel_quad = r.attr_f64(g, "sigma_rel_quadratic");
    d.received = r.attr_u64(g, "photons_received");
    d.photons = r.attr_u64("/", "photons");
    const std::vector<std::string> bands = r.attr_strs("/", "bands");
    std::vector<std::size_t> shape;
    const std::vector<double> value = r.f64(g + "/value", &shape);
    const std::size_t K = static_cast<std::size_t>(d.nx) * d.ny, B = shape.size() == 3 ? shape[2] : 1;
    if (shape.size() != 3 || shape[0] != static_cast<std::size_t>(d.ny) || shape[1] != static_cast<std::size_t>(d.nx))
        throw InputError(result.string() + ": " + g + "/value does not match the detector's cells");
    d.value.assign(K, 0.0);
    d.sigma_rel.assign(K, kNaN);
    if (B == 0) throw InputError(result.string() + ": " + g + "/value has no bands");
    if (B == 1) {
        d.value = value;
        d.sigma_rel = r.f64(g + "/sigma_rel");
        if (d.sigma_rel.size() != K)
            throw InputError(result.string() + ": " + g + "/sigma_rel does not match the detector's cells");
        d.band_note = bands.empty() ? "" : "band " + bands[0];
    } else {
        // A photon carries one band, so counts and sums of squares add over bands and
        // eq. (8) holds for the sum as for one band.
        const std::vector<std::uint64_t> cnt = r.u64(g + "/count"), sq = r.u64(g + "/sumsq");
        if (cnt.size() != K * B || sq.size() != K * B)
            throw InputError(result.string() + ": " + g + "/count or /sumsq does not match /value");
        const double inv_n = d.photons > 0 ? 1.0 / static_cast<double>(d.photons) : 0.0;
        for (std::size_t c = 0; c < K; ++c) {
            double nn = 0, qq = 0;
            for (std::size_t b = 0; b < B; ++b) {
                d.value[c] += value[c * B + b];
                nn += static_cast<double>(cnt[c * B + b]);
                qq += static_cast<double>(sq[c * B + b]);
            }
            if (nn > 0) d.sigma_rel[c] = std::sqrt(std::max(0.0, qq / (nn * nn) - inv_n));
        }
        d.band_note = "sum of " + std::to_string(B) + " bands";
    }
    return d;
}

std::pair<int, int> parse_cell(const std::string& cell, const DetectorData& d) {
    if (cell.empty()) {  // the brightest cell
        std::size_t best = 0;
        for (std::size_t c = 1; c < d.value.size(); ++c)
            if (d.value[c] > d.value[best]) best = c;
        return {static_cast<int>(best % d.nx), static_cast<int>(best / d.nx)};
    }
    int i = -1, j = -1, used = 0;
    if (std::sscanf(cell.c_str(), " %d , %d %n", &i, &j, &used) != 2 || used != static_cast<int>(cell.size()))
        throw InputError("--cell: '" + cell + "' is not i,j (two integers)");
    if (i < 0 || i >= d.nx || j < 0 || j >= d.ny)
        throw InputError("--cell: " + cell + " is outside detector '" + d.name + "' (i in 0.." +
                         std::to_string(d.nx - 1) + ", j in 0.." + std::to_string(d.ny - 1) + ")");
    return {i, j};
}

// ---------------------------------------------------------------- drawing helpers
std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// Tick label with as many decimals as the tick step needs.
std::string tick_label(double v, double step) {
    const int dec = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", dec, std::abs(v) < 1e-12 * step ? 0.0 : v);
    return buf;
}

// Shortest of the usual lengths for a value with three significant digits.
std::string sig3(double v) {
    if (!std::isfinite(v)) return "n/a";
    if (v != 0.0 && (std::abs(v) >= 1e5 || std::abs(v) < 1e-3)) return fmt("%.2e", v);
    const int dec = v == 0.0 ? 0 : std::clamp(2 - static_cast<int>(std::floor(std::log10(std::abs(v)))), 0, 6);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", dec, v);
    return buf;
}

double nice_step(double range, int count) {
    const double raw = range / std::max(1, count);
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * p >= raw * (1 - 1e-9)) return m * p;
    return 10.0 * p;
}

std::vector<double> ticks(double lo, double hi, int count, double* step_out = nullptr) {
    std::vector<double> out;
    if (!(hi > lo)) return {lo};
    const double step = nice_step(hi - lo, count);
    for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) out.push_back(t);
    if (step_out) *step_out = step;
    return out;
}

// Upper end of a scale: the maximum rounded up to the next nice tick.
double nice_top(double max) {
    if (!(max > 0.0)) return 1.0;
    const double step = nice_step(max, 5);
    return std::ceil(max / step - 1e-9) * step;
}

class Canvas {
public:
    Canvas(int w, int h) : s_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h)), cr_(cairo_create(s_)) {
        cairo_set_source_rgb(cr_, 1, 1, 1);
        cairo_paint(cr_);
        cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    }
    ~Canvas() {
        cairo_destroy(cr_);
        cairo_surface_destroy(s_);
    }
    Canvas(const Canvas&) = delete;
    Canvas& operator=(const Canvas&) = delete;
    cairo_t* cr() const { return cr_; }

    // Atomic: a hidden temporary beside the target, then rename.
    void save(const fs::path& path) const {
        std::string tmp_name = path.filename().string();
        tmp_name.insert(tmp_name.begin(), '.');
        tmp_name += ".tmp." + std::to_string(::getpid());
        const fs::path tmp = path.parent_path() / tmp_name;
        cairo_surface_flush(s_);
        if (cairo_surface_write_to_png(s_, tmp.c_str()) != CAIRO_STATUS_SUCCESS) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw InputError(path.string() + ": cannot write the picture");
        }
        fs::rename(tmp, path);
    }

    // Text anchored at (x, y): ax 0 left / 0.5 centre / 1 right, ay likewise top to bottom.
    void text(const std::string& s, double x, double y, double size, double ax = 0, double ay = 0,
              bool bold = false, double angle = 0.0) const {
        cairo_save(cr_);
        cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                               bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr_, size);
        cairo_text_extents_t e;
        cairo_text_extents(cr_, s.c_str(), &e);
        cairo_translate(cr_, x, y);
        cairo_rotate(cr_, angle);
        // Anchor on the advance width and the font's cap height, not on the ink.
        cairo_move_to(cr_, -ax * e.x_advance, ay * 0.75 * size);
        cairo_set_source_rgb(cr_, 0.1, 0.1, 0.1);
        cairo_show_text(cr_, s.c_str());
        cairo_restore(cr_);
    }
    void colour(const Rgb& c) const { cairo_set_source_rgb(cr_, c.r, c.g, c.b); }
    void line(double x0, double y0, double x1, double y1, double width = 1.0) const {
        cairo_set_line_width(cr_, width);
        cairo_move_to(cr_, x0, y0);
        cairo_line_to(cr_, x1, y1);
        cairo_stroke(cr_);
    }

private:
    cairo_surface_t* s_;
    cairo_t* cr_;
};

std::string vec_text(const std::array<double, 3>& v) {
    std::string s(1, '(');
    for (int k = 0; k < 3; ++k) {
        if (k > 0) s += ", ";
        s += fmt("%.3g", std::abs(v[k]) < 1e-12 ? 0.0 : v[k]);  // no "-0"
    }
    return s + ')';
}

// Photon counts: exact when short, else three digits and a power of ten (3.00e6).
std::string count_text(std::uint64_t n) {
    if (n < 1000000) return std::to_string(n);
    const int e = static_cast<int>(std::floor(std::log10(static_cast<double>(n))));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2fe%d", static_cast<double>(n) / std::pow(10.0, e), e);
    return buf;
}

// A vertical colour bar at (x, y) of height h for [0, top], ticks labelled in `units`.
void colour_bar(const Canvas& cv, const ColourMap& map, double x, double y, double h, double top,
                const std::string& units, double scale = 1.0) {
    cairo_t* cr = cv.cr();
    constexpr double w = 22;
    for (int k = 0; k < static_cast<int>(h); ++k) {
        cv.colour(map(1.0 - (k + 0.5) / h));
        cairo_rectangle(cr, x, y + k, w, 1.0);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, x + 0.5, y + 0.5, w - 1, h - 1);
    cairo_stroke(cr);
    double step = 1.0;
    for (double t : ticks(0.0, top * scale, 6, &step)) {
        const double py = y + h - t / (top * scale) * h;
        cv.line(x + w, py, x + w + 5, py);
        cv.text(tick_label(t, step), x + w + 8, py, 12, 0, 0.5);
    }
    cv.text(units, x + w / 2, y - 10, 13, 0.5, 0);
}

// Ticks in metres along both map edges, positions relative to the detector centre.
void map_axes(const Canvas& cv, const DetectorMapLayout& l, const DetectorData& d) {
    cairo_set_source_rgb(cv.cr(), 0.2, 0.2, 0.2);
    double step = 1.0;
    for (double u : ticks(-d.size_u / 2, d.size_u / 2, std::max(2, l.map_w / 90), &step)) {
        const double px = l.map_x + (u / d.size_u + 0.5) * l.map_w;
        cv.line(px, l.map_y + l.map_h, px, l.map_y + l.map_h + 5);
        cv.text(tick_label(u, step), px, l.map_y + l.map_h + 9, 12, 0.5, 1);
    }
    for (double v : ticks(-d.size_v / 2, d.size_v / 2, std::max(2, l.map_h / 60), &step)) {
        const double py = l.map_y + (0.5 - v / d.size_v) * l.map_h;
        cv.line(l.map_x - 5, py, l.map_x, py);
        cv.text(tick_label(v, step), l.map_x - 8, py, 12, 1, 0.5);
    }
    cv.text("u (m) along " + vec_text(d.u), l.map_x + l.map_w / 2.0, l.map_y + l.map_h + 32, 13, 0.5, 1);
    cv.text("v (m) along up " + vec_text(d.up), l.map_x - 62, l.map_y + l.map_h / 2.0, 13, 0.5, 0.5, false,
            -kPi / 2);
}

// The cells as crisp blocks: an nx x ny image scaled up with nearest-neighbour filtering.
void draw_cells(const Canvas& cv, const DetectorMapLayout& l, const DetectorData& d,
                const std::vector<double>& field, double top, const ColourMap& map) {
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, d.nx, d.ny);
    unsigned char* px = cairo_image_surface_get_data(img);
    const int stride = cairo_image_surface_get_stride(img);
    for (int j = 0; j < d.ny; ++j)
        for (int i = 0; i < d.nx; ++i) {
            const double f = field[static_cast<std::size_t>(j) * d.nx + i];
            const Rgb c = std::isfinite(f) ? map(f / top) : kNoHit;
            // Row 0 at the bottom of the picture.
            auto* p = reinterpret_cast<std::uint32_t*>(px + static_cast<std::ptrdiff_t>(d.ny - 1 - j) * stride) + i;
            *p = (static_cast<std::uint32_t>(std::lround(c.r * 255)) << 16) |
                 (static_cast<std::uint32_t>(std::lround(c.g * 255)) << 8) | static_cast<std::uint32_t>(std::lround(c.b * 255));
        }
    cairo_surface_mark_dirty(img);
    cairo_t* cr = cv.cr();
    cairo_save(cr);
    cairo_translate(cr, l.map_x, l.map_y);
    cairo_scale(cr, l.cell_w, l.cell_h);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_rectangle(cr, 0, 0, d.nx, d.ny);
    cairo_fill(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
}

std::string title_head(const DetectorData& d) {
    return d.name + " \u2014 " + d.type + (d.band_note.empty() ? "" : " (" + d.band_note + ")");
}

std::string grid_line(const DetectorData& d) {
    const double cu = d.size_u / d.nx, cv = d.size_v / d.ny;
    const bool mm = std::max(cu, cv) < 1.0;  // one unit for both sides
    const double k = mm ? 1000.0 : 1.0;
    return std::to_string(d.nx) + " \u00d7 " + std::to_string(d.ny) + " cells of " + fmt("%.3g", cu * k) +
           " \u00d7 " + fmt("%.3g", cv * k) + (mm ? " mm" : " m") + ", " + count_text(d.received) +
           " photons received of " + count_text(d.photons) + " emitted";
}

void value_picture(const DetectorData& d, const fs::path& path) {
    const DetectorMapLayout l = detector_map_layout(d.nx, d.ny, d.size_u, d.size_v);
    Canvas cv(l.width, l.height);
    double vmax = 0.0;
    for (double v : d.value) vmax = std::max(vmax, v);
    const double top = nice_top(vmax);
    cv.text(title_head(d) + ", mean " + sig3(d.mean_value) + " " + d.units + " \u00b1 " +
                sig3(100.0 * d.mean_sigma_rel) + " %", 16, 14, 16, 0, 1, true);
    cv.text(grid_line(d), 16, 40, 12, 0, 1);
    draw_cells(cv, l, d, d.value, top, value_map());
    map_axes(cv, l, d);
    const bool lux = d.units == "lx";
    colour_bar(cv, value_map(), l.map_x + l.map_w + 30, l.map_y, std::max(l.map_h, 240), top,
               (lux ? "E (" : "L (") + d.units + ")");
    cv.save(path);
}

void error_picture(const DetectorData& d, const fs::path& path) {
    const DetectorMapLayout l = detector_map_layout(d.nx, d.ny, d.size_u, d.size_v);
    Canvas cv(l.width, l.height);
    double emax = 0.0;
    int empty = 0;
    for (double e : d.sigma_rel) {
        if (std::isfinite(e)) emax = std::max(emax, e);
        else ++empty;
    }
    const double top = nice_top(100.0 * emax) / 100.0;
    cv.text(d.name + " \u2014 relative error per cell (eq. 8)" + (d.band_note.empty() ? "" : ", " + d.band_note),
            16, 14, 16, 0, 1, true);
    cv.text("eq. (9): " + sig3(100.0 * d.rel_arith) + " % arithmetic, " + sig3(100.0 * d.rel_quad) +
                " % quadratic; " + std::to_string(empty) + " of " + std::to_string(d.nx * d.ny) +
                " cells without hits",
            16, 40, 12, 0, 1);
    draw_cells(cv, l, d, d.sigma_rel, top, error_map());
    cairo_t* cr = cv.cr();
    // Cells without hits: grey with a cross, when the blocks are big enough for one.
    if (l.cell_w >= 6 && l.cell_h >= 6) {
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
        for (int j = 0; j < d.ny; ++j)
            for (int i = 0; i < d.nx; ++i) {
                if (std::isfinite(d.rel(i, j))) continue;
                const double x = l.map_x + i * l.cell_w, y = l.map_y + (d.ny - 1 - j) * l.cell_h;
                cv.line(x + 1, y + 1, x + l.cell_w - 1, y + l.cell_h - 1);
                cv.line(x + l.cell_w - 1, y + 1, x + 1, y + l.cell_h - 1);
            }
    }
    map_axes(cv, l, d);
    const double bar_x = l.map_x + l.map_w + 30, bar_h = std::max(l.map_h, 240);
    colour_bar(cv, error_map(), bar_x, l.map_y, bar_h, top, "\u03c3 rel (%)", 100.0);
    // Legend of the no-hit mark under the bar.
    cv.colour(kNoHit);
    const double sy = l.map_y + bar_h + 14;
    cairo_rectangle(cr, bar_x, sy, 22, 14);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cv.line(bar_x + 1, sy + 1, bar_x + 21, sy + 13);
    cv.line(bar_x + 21, sy + 1, bar_x + 1, sy + 13);
    cv.text("no hits", bar_x + 30, sy + 7, 12, 0, 0.5);
    cv.save(path);
}

// A plotting frame: data coordinates to pixels, with axes, ticks and labels.
struct Frame {
    double x0, y0, w, h, xlo, xhi, ylo, yhi;
    double px(double x) const { return x0 + (x - xlo) / (xhi - xlo) * w; }
    double py(double y) const { return y0 + h - (y - ylo) / (yhi - ylo) * h; }
    void axes(const Canvas& cv, const std::string& xlabel, const std::string& ylabel) const {
        cairo_t* cr = cv.cr();
        double step = 1.0;
        cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
        for (double t : ticks(ylo, yhi, 6)) cv.line(x0, py(t), x0 + w, py(t));
        cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
        cairo_set_line_width(cr, 1.0);
        cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, w, h);
        cairo_stroke(cr);
        for (double t : ticks(xlo, xhi, static_cast<int>(w / 80), &step)) {
            cv.line(px(t), y0 + h, px(t), y0 + h + 5);
            cv.text(tick_label(t, step), px(t), y0 + h + 9, 12, 0.5, 1);
        }
        for (double t : ticks(ylo, yhi, 6, &step)) {
            cv.line(x0 - 5, py(t), x0, py(t));
            cv.text(tick_label(t, step), x0 - 8, py(t), 12, 1, 0.5);
        }
        cv.text(xlabel, x0 + w / 2, y0 + h + 30, 13, 0.5, 1);
        cv.text(ylabel, x0 - 60, y0 + h / 2, 13, 0.5, 0.5, false, -kPi / 2);
    }
};

void histogram_picture(const DetectorData& d, const fs::path& path) {
    Canvas cv(kDetectorHistWidth, kDetectorHistHeight);
    cairo_t* cr = cv.cr();
    std::vector<double> e;
    for (double s : d.sigma_rel)
        if (std::isfinite(s)) e.push_back(100.0 * s);
    double emax = 0.0;
    for (double x : e) emax = std::max(emax, x);
    const double colour_top = nice_top(emax);  // the error map's scale: bars in its colours
    // Marks must stay on the axis even when they exceed every cell's error.
    for (double m : {d.rel_arith, d.rel_quad})
        if (std::isfinite(m)) emax = std::max(emax, 100.0 * m);
    const double top = nice_top(emax * 1.04);  // the largest error not on the frame
    const int bins = std::clamp(static_cast<int>(std::lround(std::sqrt(static_cast<double>(e.size())))), 10, 60);
    std::vector<int> hist(static_cast<std::size_t>(bins), 0);
    // Clamped as a double: a damaged file's error can be far beyond int (or 0/0 when top is 0).
    for (double x : e) {
        const double pos = top > 0.0 ? x / top * bins : 0.0;
        ++hist[static_cast<std::size_t>(std::isfinite(pos) ? std::clamp(pos, 0.0, bins - 1.0) : bins - 1.0)];
    }
    int hmax = 1;
    for (int c : hist) hmax = std::max(hmax, c);
    const std::size_t empty = d.sigma_rel.size() - e.size();
    cv.text(d.name + " \u2014 relative errors of the cells" + (d.band_note.empty() ? "" : " (" + d.band_note + ")"),
            16, 14, 16, 0, 1, true);
    cv.text(std::to_string(e.size()) + " cells with hits" +
                (empty > 0 ? ", " + std::to_string(empty) + " without (not counted)" : std::string()),
            16, 40, 12, 0, 1);
    const Frame f{86, 76, kDetectorHistWidth - 86.0 - 30, kDetectorHistHeight - 76.0 - 70, 0.0, top, 0.0,
                  nice_top(hmax * 1.1)};
    f.axes(cv, "relative error per cell (%)", "cells");
    for (int b = 0; b < bins; ++b) {
        if (hist[static_cast<std::size_t>(b)] == 0) continue;
        const double x0 = f.px(top * b / bins), x1 = f.px(top * (b + 1) / bins), y = f.py(hist[static_cast<std::size_t>(b)]);
        cv.colour(error_map()(top * (b + 0.5) / bins / colour_top));
        cairo_rectangle(cr, x0, y, x1 - x0, f.py(0) - y);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
        cairo_set_line_width(cr, 0.8);
        cairo_stroke(cr);
    }
    // Eq. (9) marks with a legend.
    const std::pair<double, std::string> marks[] = {{d.rel_arith, "eq. (9) arithmetic: "},
                                                    {d.rel_quad, "eq. (9) quadratic: "}};
    const Rgb mark_colour[] = {{0.05, 0.35, 0.85}, {0.05, 0.6, 0.3}};
    const double dashes[] = {7.0, 4.0};
    for (int k = 0; k < 2; ++k) {
        const double m = 100.0 * marks[k].first;
        const double ly = f.y0 + 18 + 20 * k, lx = f.x0 + f.w - 250;
        cv.colour(mark_colour[k]);
        cairo_set_dash(cr, dashes, k == 0 ? 0 : 2, 0);
        if (std::isfinite(m)) cv.line(f.px(m), f.y0, f.px(m), f.y0 + f.h, 2.0);
        cv.colour(mark_colour[k]);
        cv.line(lx, ly, lx + 28, ly, 2.0);
        cairo_set_dash(cr, nullptr, 0, 0);
        cv.text(marks[k].second + sig3(m) + " %", lx + 36, ly, 12, 0, 0.5);
    }
    cv.save(path);
}

// One section: values of `n` cells at centres `pos` with their sigma, as steps with a band.
void section_panel(const Canvas& cv, const Frame& f, const std::vector<double>& pos, double width,
                   const std::vector<double>& val, const std::vector<double>& rel, double mark) {
    cairo_t* cr = cv.cr();
    const std::size_t n = pos.size();
    // +-1 sigma band, per cell block; cells without hits have no band.
    cairo_set_source_rgba(cr, 0.25, 0.45, 0.85, 0.30);
    for (std::size_t k = 0; k < n; ++k) {
        if (!std::isfinite(rel[k])) continue;
        const double s = rel[k] * val[k];
        const double ylo = std::max(f.ylo, val[k] - s), yhi = std::min(f.yhi, val[k] + s);
        cairo_rectangle(cr, f.px(pos[k] - width / 2), f.py(yhi), f.px(pos[k] + width / 2) - f.px(pos[k] - width / 2),
                        f.py(ylo) - f.py(yhi));
    }
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.05, 0.2, 0.6);
    cairo_set_line_width(cr, 1.8);
    for (std::size_t k = 0; k < n; ++k) {
        const double y = f.py(val[k]);
        if (k == 0) cairo_move_to(cr, f.px(pos[k] - width / 2), y);
        else cairo_line_to(cr, f.px(pos[k] - width / 2), y);
        cairo_line_to(cr, f.px(pos[k] + width / 2), y);
    }
    cairo_stroke(cr);
    // Cells without hits: value 0 without an error estimate; a grey cross says so.
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
    for (std::size_t k = 0; k < n; ++k) {
        if (std::isfinite(rel[k])) continue;
        const double x = f.px(pos[k]), y = f.py(f.ylo) - 6;
        cv.line(x - 4, y - 4, x + 4, y + 4, 1.5);
        cv.line(x - 4, y + 4, x + 4, y - 4, 1.5);
    }
    const double dash[] = {5.0, 4.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_source_rgb(cr, 0.8, 0.15, 0.1);
    cv.line(f.px(mark), f.y0, f.px(mark), f.y0 + f.h, 1.5);
    cairo_set_dash(cr, nullptr, 0, 0);
}

void sections_picture(const DetectorData& d, int ci, int cj, const fs::path& path) {
    Canvas cv(kDetectorSectionsWidth, kDetectorSectionsHeight);
    const double du = d.size_u / d.nx, dv = d.size_v / d.ny;
    auto upos = [&](int i) { return -d.size_u / 2 + (i + 0.5) * du; };
    auto vpos = [&](int j) { return -d.size_v / 2 + (j + 0.5) * dv; };
    std::vector<double> hp, hv, hr, vp, vv, vr;
    for (int i = 0; i < d.nx; ++i) hp.push_back(upos(i)), hv.push_back(d.at(i, cj)), hr.push_back(d.rel(i, cj));
    for (int j = 0; j < d.ny; ++j) vp.push_back(vpos(j)), vv.push_back(d.at(ci, j)), vr.push_back(d.rel(ci, j));
    auto top_of = [](const std::vector<double>& v, const std::vector<double>& r) {
        double m = 0.0;
        for (std::size_t k = 0; k < v.size(); ++k)
            m = std::max(m, v[k] * (1.0 + (std::isfinite(r[k]) ? r[k] : 0.0)));
        return nice_top(m * 1.05);
    };
    const std::string q = d.units == "lx" ? "E (lx)" : "L (" + d.units + ")";
    cv.text(d.name + " \u2014 sections through cell i = " + std::to_string(ci) + ", j = " + std::to_string(cj) +
                (d.band_note.empty() ? "" : " (" + d.band_note + ")"),
            16, 14, 16, 0, 1, true);
    const std::string err = std::isfinite(d.rel(ci, cj)) ? " \u00b1 " + sig3(100.0 * d.rel(ci, cj)) + " %" : " (no hits)";
    cv.text("value " + sig3(d.at(ci, cj)) + " " + d.units + err + " at u = " + sig3(upos(ci)) + " m, v = " + sig3(vpos(cj)) +
                " m from the centre; band: \u00b1 1 \u03c3 per cell; \u00d7: no hits",
            16, 40, 12, 0, 1);
    const double x0 = 96, w = kDetectorSectionsWidth - 96.0 - 30, h = 250;
    const Frame fh{x0, 100, w, h, -d.size_u / 2, d.size_u / 2, 0.0, top_of(hv, hr)};
    cv.text("horizontal: row j = " + std::to_string(cj), x0, 84, 13, 0, 0.5, true);
    fh.axes(cv, "u (m) along " + vec_text(d.u), q);
    section_panel(cv, fh, hp, du, hv, hr, upos(ci));
    const Frame fv{x0, 100 + h + 110, w, h, -d.size_v / 2, d.size_v / 2, 0.0, top_of(vv, vr)};
    cv.text("vertical: column i = " + std::to_string(ci), x0, fv.y0 - 16, 13, 0, 0.5, true);
    fv.axes(cv, "v (m) along up " + vec_text(d.up), q);
    section_panel(cv, fv, vp, dv, vv, vr, vpos(cj));
    cv.save(path);
}

}  // namespace

void render_detector_pictures(const fs::path& result, const std::string& detector, const std::string& cell,
                              const fs::path& out_dir) {
    const DetectorData d = read_detector(result, detector);
    const auto [ci, cj] = parse_cell(cell, d);
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (!fs::is_directory(out_dir)) throw InputError(out_dir.string() + ": cannot create the picture folder");
    value_picture(d, out_dir / (detector + "_value.png"));
    error_picture(d, out_dir / (detector + "_error.png"));
    histogram_picture(d, out_dir / (detector + "_error_hist.png"));
    sections_picture(d, ci, cj, out_dir / (detector + "_sections.png"));
}

}  // namespace luxtrace
