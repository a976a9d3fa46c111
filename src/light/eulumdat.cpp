// EULUMDAT reader; see eulumdat.hpp and docs/PHOTOMETRY.md.
//
// The format is line based, one field a line:
//   1 company, 2 Ityp, 3 Isym, 4 Mc, 5 Dc, 6 Ng, 7 Dg, 8 report, 9 luminaire name,
//   10 luminaire number, 11 file name, 12 date/user, 13-15 luminaire length (diameter),
//   width (0: round) and height in mm, 16-17 luminous area length (diameter) and width
//   (0: round) in mm, 18-21 luminous area heights at C0, C90, C180, C270 in mm,
//   22 downward flux fraction %, 23 light output ratio LORL %, 24 conversion factor,
//   25 tilt during measurement, 26 number of lamp sets n, then per set: number of lamps,
//   type, total lamp flux (lm), colour, colour rendering, wattage (W); then 10 direct
//   ratios, Mc C angles, Ng gamma angles and the intensities in cd/klm.
// Isym says which C planes the intensities cover: 0 all Mc, 1 one (rotational), 2
// C0-C180 (mirrored about that plane), 3 the half from C270 through C0 to C90 (mirrored
// about the C90-C270 plane), 4 C0-C90 (mirrored about both).
// A negative number of lamps marks absolute photometry: the set's flux is then the
// luminaire's (LORL 100 %).
#include "luxtrace/light/eulumdat.hpp"

#include "photometry_text.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {
namespace {

using detail::fail_at;
using detail::fmt;
using detail::trim;

constexpr double kAngleTol = 1e-6;

class LineReader {
public:
    LineReader(std::string file, const std::vector<std::string>& lines) : file_(std::move(file)), lines_(lines) {}
    [[noreturn]] void fail(int line, const std::string& what) const { fail_at(file_, line, what); }
    int line() const { return static_cast<int>(pos_) + 1; }   // the next line's number
    int prev_line() const { return static_cast<int>(pos_); }  // the last one read
    std::string text(const std::string& what) {
        if (pos_ >= lines_.size())
            fail(std::max(1, static_cast<int>(lines_.size())), "unexpected end of file, expected " + what);
        return std::string(trim(lines_[pos_++]));
    }
    double number(const std::string& what) {
        const std::string s = text(what);
        const auto v = detail::parse_number(s, true);
        if (!v) fail(prev_line(), "expected a number for " + what + ", found '" + s + "'");
        return *v;
    }
    int integer(const std::string& what) {
        const double v = number(what);
        if (v != std::floor(v) || std::abs(v) > 1e6)
            fail(prev_line(), "expected an integer for " + what + ", found " + fmt(v));
        return static_cast<int>(v);
    }
    // The remaining numbers, whitespace separated, with their lines.
    std::vector<std::pair<double, int>> rest() {
        std::vector<std::pair<double, int>> out;
        for (const detail::Token& t : detail::tokens_of(lines_, pos_)) {
            const auto v = detail::parse_number(t.text, true);
            if (!v) fail(t.line, "expected a number, found '" + t.text + "'");
            out.emplace_back(*v, t.line);
        }
        pos_ = lines_.size();
        return out;
    }

private:
    std::string file_;
    const std::vector<std::string>& lines_;
    std::size_t pos_ = 0;
};

// An integer field that must lie in [lo, hi]; `rule` says so in the error.
int integer_in(LineReader& rd, const std::string& what, int lo, int hi, const std::string& rule) {
    const int v = rd.integer(what);
    if (v < lo || v > hi) rd.fail(rd.prev_line(), rule + ", found " + fmt(v));
    return v;
}

// The header fields (lines 1-25) the table and the opening need.
struct Header {
    std::string company;
    int isym = 0, mc = 0, ng = 0;
    double la = 0.0, wa = 0.0, h[4] = {0.0, 0.0, 0.0, 0.0};  // luminous area (mm)
    double lorl = 0.0, conversion = 0.0;
};

// Lines 2-7: Ityp, Isym, Mc, Dc, Ng, Dg. Isym 2 and 3 store half the planes, 4 a quarter.
void read_indicators(LineReader& rd, Header& h) {
    integer_in(rd, "type indicator Ityp (line 2)", 0, 3, "type indicator Ityp must be 0, 1, 2 or 3");
    h.isym = integer_in(rd, "symmetry indicator Isym (line 3)", 0, 4, "symmetry indicator Isym must lie in 0-4");
    h.mc = integer_in(rd, "number of C planes Mc (line 4)", 1, 3600, "number of C planes Mc must lie in [1, 3600]");
    if ((h.isym == 2 || h.isym == 3) && h.mc % 2 != 0)
        rd.fail(rd.prev_line(), "Isym " + fmt(h.isym) + " needs an even number of C planes, found " + fmt(h.mc));
    if (h.isym == 4 && h.mc % 4 != 0)
        rd.fail(rd.prev_line(), "Isym 4 needs a number of C planes divisible by 4, found " + fmt(h.mc));
    rd.number("C plane distance Dc (line 5)");
    h.ng = integer_in(rd, "number of intensities per C plane Ng (line 6)", 2, 3600,
                      "number of gamma angles Ng must lie in [2, 3600]");
    rd.number("gamma angle distance Dg (line 7)");
}

// Lines 8-12: report number, luminaire name and number, file name, date/user.
void read_names(LineReader& rd, Photometry& p) {
    rd.text("measurement report number (line 8)");
    p.luminaire = rd.text("luminaire name (line 9)");
    rd.text("luminaire number (line 10)");
    rd.text("file name (line 11)");
    rd.text("date/user (line 12)");
}

// Lines 13-21: the luminaire's and the luminous area's sizes (mm).
void read_sizes(LineReader& rd, Header& h) {
    for (const char* what : {"luminaire length (line 13)", "luminaire width (line 14)", "luminaire height (line 15)"})
        rd.number(what);
    const int area_line = rd.line();
    h.la = rd.number("luminous area length or diameter (line 16)");
    h.wa = rd.number("luminous area width (line 17)");
    for (double& v : h.h) v = rd.number("luminous area height (lines 18-21)");
    for (const double v : {h.la, h.wa, h.h[0], h.h[1], h.h[2], h.h[3]})
        if (v < 0.0) rd.fail(area_line, "luminous area dimensions must not be negative, found " + fmt(v));
}

// Lines 22-25: downward flux fraction, LORL, conversion factor, tilt.
void read_output(LineReader& rd, Header& h) {
    rd.number("downward flux fraction (line 22)");
    h.lorl = rd.number("light output ratio LORL (line 23)");
    if (!(h.lorl > 0.0 && h.lorl <= 100.0 + 1e-9))
        rd.fail(rd.prev_line(), "light output ratio LORL must lie in (0, 100] %, found " + fmt(h.lorl));
    h.conversion = rd.number("conversion factor for intensities (line 24)");
    if (!(h.conversion > 0.0)) rd.fail(rd.prev_line(), "conversion factor must be > 0, found " + fmt(h.conversion));
    rd.number("tilt during measurement (line 25)");
}

// Line 26 and the lamp sets; the set asked for gives the lamps, watts and lamp flux.
// Returns that set's total lamp flux.
double read_lamp_sets(LineReader& rd, int lamp_set, const std::string& name, Photometry& p) {
    const int sets = integer_in(rd, "number of lamp sets (line 26)", 1, 20, "number of lamp sets must lie in [1, 20]");
    if (lamp_set < 1 || lamp_set > sets)
        throw InputError(name + ": lamp set " + std::to_string(lamp_set) + " asked for, the file has " +
                         std::to_string(sets));
    double set_flux = 0.0;
    for (int s = 1; s <= sets; ++s) {
        const int lamps = rd.integer("number of lamps of set " + std::to_string(s));
        const std::string lamp_type = rd.text("lamp type of set " + std::to_string(s));
        const double flux = rd.number("total lamp flux of set " + std::to_string(s));
        const int flux_line = rd.prev_line();
        rd.text("colour of set " + std::to_string(s));
        rd.text("colour rendering of set " + std::to_string(s));
        const double watts = rd.number("wattage of set " + std::to_string(s));
        if (s != lamp_set) continue;
        if (!(flux > 0.0))
            rd.fail(flux_line, "total lamp flux of set " + std::to_string(s) + " must be > 0, found " + fmt(flux));
        set_flux = flux;
        p.num_lamps = std::abs(lamps);
        p.input_watts = watts;
        p.lamp_flux_lm = lamps < 0 ? -1.0 : flux;  // negative count: the flux is the luminaire's
        if (!lamp_type.empty()) p.keywords.emplace_back("LAMP", lamp_type);
    }
    return set_flux;
}

// The numbers after the direct ratios, handed out in order, each with its line.
class Numbers {
public:
    Numbers(const LineReader& rd, std::vector<std::pair<double, int>> nums, int last_line)
        : rd_(rd), nums_(std::move(nums)), last_line_(last_line) {}
    [[noreturn]] void fail(int line, const std::string& what) const { rd_.fail(line, what); }
    std::pair<double, int> take(const std::string& what) {
        if (at_ >= nums_.size()) fail(last_line_, "unexpected end of file, expected " + what);
        return nums_[at_++];
    }
    bool done() const { return at_ >= nums_.size(); }
    int line() const { return nums_[at_].second; }  // the next number's

private:
    const LineReader& rd_;
    std::vector<std::pair<double, int>> nums_;
    int last_line_;
    std::size_t at_ = 0;
};

// n increasing angles ("C" or "gamma") for which `inside` holds; `range` names it.
std::vector<double> read_angles(Numbers& nums, int n, const std::string& kind, bool (*inside)(double),
                                const char* range) {
    std::vector<double> a;
    for (int k = 0; k < n; ++k) {
        const auto [v, line] = nums.take(kind + " angle " + std::to_string(k + 1) + " of " + std::to_string(n));
        if (!inside(v)) nums.fail(line, kind + " angle " + fmt(v) + " is outside " + range);
        if (!a.empty() && v <= a.back())
            nums.fail(line, kind + " angles must increase, found " + fmt(v) + " after " + fmt(a.back()));
        a.push_back(v);
    }
    return a;
}

// The planes stored under Isym, as indices into the C angles: Isym 3 stores the C90-C270
// half starting at C270 and running on through C0 to C90 (the planes of C270..C360..C90
// equal, by the symmetry, those of C270..C180..C90).
struct StoredPlanes {
    int first = 0, count = 0;
};

StoredPlanes stored_planes(int isym, int mc) {
    StoredPlanes s{0, mc};
    if (isym == 1) s.count = 1;
    else if (isym == 2) s.count = mc / 2 + 1;
    else if (isym == 3) {
        s.first = 3 * mc / 4;
        s.count = mc / 2 + 1;
    } else if (isym == 4) s.count = mc / 4 + 1;
    return s;
}

// "(Isym 2: 13 C planes x 19 gamma angles)", the layout the intensities follow.
std::string layout_text(int isym, int count, int ng) {
    return "(Isym " + fmt(isym) + ": " + fmt(count) + " C planes x " + fmt(ng) + " gamma angles)";
}

// The C angle stored plane k stands for.
double plane_angle(int isym, const StoredPlanes& s, const std::vector<double>& c_angles, int k) {
    if (isym == 1) return 0.0;
    if (isym != 3) return c_angles[static_cast<std::size_t>(k)];
    // C270 + k Dc, as the mirror image 180 - c in the C90..C270 half luxtrace keeps.
    const double c = c_angles[static_cast<std::size_t>((s.first + k) % static_cast<int>(c_angles.size()))];
    return std::fmod(540.0 - c, 360.0);
}

// Ng intensities (cd/klm) per stored plane, times `scale`, into the table by increasing C
// angle; false if all are zero.
bool read_intensities(Numbers& nums, const Header& h, const StoredPlanes& s, const std::vector<double>& c_angles,
                      double scale, Photometry& p) {
    bool any_light = false;
    std::vector<std::pair<double, std::vector<double>>> planes;  // (C angle, intensities)
    for (int k = 0; k < s.count; ++k) {
        std::vector<double> plane;
        for (int g = 0; g < h.ng; ++g) {
            const auto [v, line] = nums.take("intensity " + std::to_string(k * h.ng + g + 1) + " of " +
                                             std::to_string(s.count * h.ng) + " " + layout_text(h.isym, s.count, h.ng));
            if (v < 0.0) nums.fail(line, "negative intensity " + fmt(v));
            if (!std::isfinite(v * scale)) nums.fail(line, "intensity " + fmt(v) + " times the lamp flux is too large");
            any_light = any_light || v > 0.0;
            plane.push_back(v * scale);
        }
        planes.emplace_back(plane_angle(h.isym, s, c_angles, k), std::move(plane));
    }
    std::sort(planes.begin(), planes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [c, plane] : planes) {
        p.horizontal_deg.push_back(c);
        p.candela_cd.push_back(std::move(plane));
    }
    return any_light;
}

// The stored planes must be where Isym puts them (0, 90 or 180 first and last) and increase.
void check_plane_positions(const LineReader& rd, int angles_line, int isym, const Photometry& p) {
    const double lo = p.horizontal_deg.front(), hi = p.horizontal_deg.back();
    const double want_lo = isym == 3 ? 90.0 : 0.0;
    const double want_hi = isym == 0 ? 360.0 : isym == 1 ? 0.0 : isym == 2 ? 180.0 : isym == 3 ? 270.0 : 90.0;
    if (std::abs(lo - want_lo) > 1e-6 || std::abs(hi - want_hi) > 1e-6)
        rd.fail(angles_line, "Isym " + fmt(isym) + " stores C" + fmt(isym == 3 ? 270.0 : want_lo) + "-C" +
                                 fmt(isym == 3 ? 90.0 : want_hi) + ", but the C angles do not give those planes");
    for (std::size_t k = 1; k < p.horizontal_deg.size(); ++k)
        if (!(p.horizontal_deg[k] > p.horizontal_deg[k - 1]))
            rd.fail(angles_line, "the C angles of the stored planes must increase");
}

// Luminous area (mm): length along C0-C180 ... see docs/PHOTOMETRY.md. None when its
// length is 0.
void set_opening(const Header& h, const std::string& name, Photometry& p) {
    using S = LuminousOpening::Shape;
    const double hmax = std::max({h.h[0], h.h[1], h.h[2], h.h[3]});
    if (!(h.la > 0.0)) return;
    p.opening.length_m = h.la / 1000.0;
    p.opening.width_m = (h.wa > 0.0 ? h.wa : h.la) / 1000.0;
    p.opening.height_m = hmax / 1000.0;
    if (h.wa > 0.0) p.opening.shape = hmax > 0.0 ? S::box : S::rectangle;
    else p.opening.shape = hmax > 0.0 ? S::vertical_cylinder : S::ellipse;
    if (hmax > 0.0 && std::min({h.h[0], h.h[1], h.h[2], h.h[3]}) < hmax)
        p.notes.push_back(name + ": the luminous area's heights differ between C planes (" + fmt(h.h[0]) + ", " +
                          fmt(h.h[1]) + ", " + fmt(h.h[2]) + ", " + fmt(h.h[3]) + " mm); luxtrace uses " + fmt(hmax) +
                          " mm all round");
}

}  // namespace

Photometry load_eulumdat(const std::filesystem::path& file, int lamp_set) {
    const std::string name = file.string();
    const std::vector<std::string> lines = detail::read_lines(file, "EULUMDAT file");
    const int last_line = std::max(1, static_cast<int>(lines.size()));
    LineReader rd(name, lines);
    Photometry p;
    p.format = "EULUMDAT";
    p.type = PhotometricType::C;

    Header h;
    h.company = rd.text("company identification (line 1)");
    read_indicators(rd, h);
    read_names(rd, p);
    read_sizes(rd, h);
    read_output(rd, h);
    const double set_flux = read_lamp_sets(rd, lamp_set, name, p);
    for (int k = 0; k < 10; ++k) rd.number("direct ratio " + std::to_string(k + 1) + " of 10");
    p.stated_flux_lm = set_flux * h.lorl / 100.0;
    p.keywords.emplace_back("MANUFAC", h.company);
    p.keywords.emplace_back("LUMINAIRE", p.luminaire);

    // The C angles, the gamma angles and the intensities, whitespace separated.
    const int angles_line = rd.line();
    Numbers nums(rd, rd.rest(), last_line);
    const std::vector<double> c_angles = read_angles(
        nums, h.mc, "C", [](double v) { return !(v < -kAngleTol || v >= 360.0 - kAngleTol); }, "[0, 360)");
    p.vertical_deg = read_angles(
        nums, h.ng, "gamma", [](double v) { return !(v < -kAngleTol || v > 180.0 + kAngleTol); }, "[0, 180]");
    const StoredPlanes stored = stored_planes(h.isym, h.mc);
    if (h.isym == 3 && h.mc % 4 != 0)
        rd.fail(angles_line, "Isym 3 needs a number of C planes divisible by 4, found " + fmt(h.mc));
    const bool any_light = read_intensities(nums, h, stored, c_angles, set_flux / 1000.0 * h.conversion, p);
    if (!nums.done())
        rd.fail(nums.line(), "unexpected data after the " + std::to_string(stored.count * h.ng) + " intensities " +
                                 layout_text(h.isym, stored.count, h.ng));
    if (!any_light) rd.fail(last_line, "all intensities are zero");
    // Isym 0: the last plane is followed by C360 = C0.
    if (h.isym == 0) {
        p.horizontal_deg.push_back(360.0);
        p.candela_cd.push_back(p.candela_cd.front());
    }
    check_plane_positions(rd, angles_line, h.isym, p);

    set_opening(h, name, p);
    const double flux = p.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux)))
        rd.fail(last_line, "the photometry's flux (" + fmt(flux) + " lm) is not a positive number");
    return p;
}

}  // namespace luxtrace
