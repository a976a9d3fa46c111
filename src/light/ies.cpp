// IES LM-63 reader; see ies.hpp and docs/PHOTOMETRY.md.
//
// LM-63 rules applied here:
//  - Everything before the line starting with "TILT=" is header: an optional first line
//    "IESNA:LM-63-1995", "IESNA:LM-63-2002", "IES:LM-63-2019" (or "IESNA91"), and keyword
//    lines "[KEY] value" ("[MORE]" continues the previous keyword); other text (1986
//    files) is ignored.
//  - TILT=NONE, TILT=INCLUDE (the tilt data follows) or TILT=<file> (the same data in a
//    file next to this one): lamp-to-luminaire geometry (1-3), the number of pairs, the
//    angles, the multipliers.
//  - Then numbers separated by spaces, commas or newlines, in any line layout: #lamps,
//    lumens/lamp (-1 = absolute), candela multiplier, #vertical, #horizontal, photometric
//    type (1 C, 2 B, 3 A), units type (1 feet, 2 metres), width, length, height; then
//    ballast factor, the 1986/1991 "ballast-lamp photometric factor" (1995 and 2002:
//    "future use", 2019: "file generation type"; neither multiplies), input watts; then the vertical
//    angles, the horizontal angles, and #vertical candela values per horizontal angle.
//    Nothing may follow.
//  - Type C: vertical angles in [0,180]; horizontal angles 0 (rotational), 0-90, 0-180,
//    90-270 or 0-360. A table running from 0 to an angle above 180 but short of 360
//    (0-345, common in LUMCat exports) has no symmetry: C360 is C0.
//  - Types B and A: both angle sets in [-90,90]; horizontal angles from 0 mean lateral
//    symmetry (mirrored to negative angles here).
//  - Candela values are >= 0; multiplier and ballast factors must be > 0.
//  - The luminous opening follows the signs of width, length and height, by the table of
//    the file's version (opening_of).
#include "luxtrace/light/ies.hpp"

#include "photometry_text.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

namespace luxtrace {
namespace {

using detail::fail_at;
using detail::fmt;
using detail::iequals;
using detail::trim;

constexpr double kAngleTol = 1e-6;  // degrees
constexpr double kFoot_m = 0.3048;

bool near(double a, double b) { return std::abs(a - b) <= kAngleTol; }

// "TILT=..." (spaces allowed around '='); returns the value after '='.
std::optional<std::string_view> tilt_value(std::string_view l) {
    l = trim(l);
    if (l.size() < 4 || !iequals(l.substr(0, 4), "TILT")) return std::nullopt;
    const std::string_view rest = trim(l.substr(4));
    if (!rest.starts_with('=')) return std::nullopt;
    return trim(rest.substr(1));
}

using detail::Token;

// IES numbers may also be separated by commas.
std::vector<Token> tokens_of(const std::vector<std::string>& lines, std::size_t first) {
    return detail::tokens_of(lines, first, ",");
}

// Hands out numeric fields; every error names file and line.
class Reader {
public:
    Reader(std::string file, std::vector<Token> tokens, int last_line)
        : file_(std::move(file)), tokens_(std::move(tokens)), last_line_(last_line) {}

    [[noreturn]] void fail(int line, const std::string& what) const { fail_at(file_, line, what); }
    bool done() const { return pos_ == tokens_.size(); }
    std::size_t remaining() const { return tokens_.size() - pos_; }
    int line() const { return done() ? last_line_ : tokens_[pos_].line; }  // next token's
    int prev_line() const { return pos_ == 0 ? last_line_ : tokens_[pos_ - 1].line; }

    double number(const std::string& what) {
        if (done()) fail(last_line_, "unexpected end of file, expected " + what);
        const Token& t = tokens_[pos_++];
        const auto v = detail::parse_number(t.text);
        if (!v) fail(t.line, "expected a number for " + what + ", found '" + t.text + "'");
        return *v;
    }
    bool peek_is(std::string_view word) const { return !done() && iequals(tokens_[pos_].text, word); }
    void skip() { ++pos_; }
    int integer(const std::string& what) {
        const double v = number(what);
        if (v != std::floor(v) || std::abs(v) > 1e6)
            fail(prev_line(), "expected an integer for " + what + ", found " + fmt(v));
        return static_cast<int>(v);
    }

private:
    std::string file_;
    std::vector<Token> tokens_;
    int last_line_;
    std::size_t pos_ = 0;
};

// Reads n strictly increasing angles within [lo, hi].
std::vector<double> read_angles(Reader& rd, int n, const char* kind, double lo, double hi, int counts_line,
                                const char* type_name) {
    std::vector<double> a;
    for (int i = 0; i < n; ++i) {
        const double v = rd.number(std::string(kind) + " angle " + std::to_string(i + 1) + " of " + std::to_string(n));
        if (v < lo - kAngleTol || v > hi + kAngleTol)
            rd.fail(rd.prev_line(), std::string(kind) + " angle " + fmt(v) + " is outside [" + fmt(lo) + "," + fmt(hi) +
                                        "] for " + type_name + " photometry");
        if (!a.empty() && v <= a.back())
            rd.fail(rd.prev_line(), std::string(kind) + " angles must increase, found " + fmt(v) + " after " +
                                        fmt(a.back()) + " (are the angle counts on line " +
                                        std::to_string(counts_line) + " right?)");
        a.push_back(v);
    }
    return a;
}

// The tilt block: geometry, count, angles, multipliers (from the IES file or a tilt file).
TiltTable read_tilt(Reader& rd) {
    TiltTable t;
    t.lamp_geometry = rd.integer("lamp-to-luminaire geometry (1, 2 or 3)");
    if (t.lamp_geometry < 1 || t.lamp_geometry > 3)
        rd.fail(rd.prev_line(), "lamp-to-luminaire geometry must be 1, 2 or 3, found " + fmt(t.lamp_geometry));
    const int n = rd.integer("number of tilt angles");
    if (n < 1 || n > 1000) rd.fail(rd.prev_line(), "number of tilt angles must lie in [1, 1000], found " + fmt(n));
    const int line = rd.prev_line();
    t.angle_deg = read_angles(rd, n, "tilt", 0.0, 180.0, line, "tilt");
    for (int i = 0; i < n; ++i) {
        const double m = rd.number("tilt multiplier " + std::to_string(i + 1) + " of " + std::to_string(n));
        if (!(m >= 0.0)) rd.fail(rd.prev_line(), "tilt multiplier must be >= 0, found " + fmt(m));
        t.multiplier.push_back(m);
    }
    return t;
}

// The luminous opening from the signs of width, length and height, by the table of the
// file's LM-63 version (as Radiance's ies2rad reads them):
//  - 2002 and 2019: (w, l, h) = (0,0,0) point, (+,+,0) rectangle, (+,+,+) box, (-,-,0)
//    disk or ellipse, (-,-,+) vertical cylinder, (-,+,-) horizontal cylinder along the
//    length (C0-C180), (+,-,-) along the width (C90-C270), (-,-,-) sphere or ellipsoid;
//  - 1995: a negative width is a round opening: (-,0,0) disk, (-,0,+) vertical
//    cylinder, (-,0,-) sphere, (-,+,0) horizontal cylinder along the length, (+,0,-)
//    one across it, (-,+,+) or (+,-,+) elliptic vertical cylinder, (-,+,-) or (+,-,-)
//    ellipsoid;
//  - 1986 and 1991: (-,0,0) disk, (-,0,+) vertical cylinder, (-,+,0) ellipse, (-,+,+)
//    ellipsoid.
// A missing size of a round shape is its diameter |w|. Anything else is a point, with a note.
LuminousOpening opening_of(double w, double l, double h, double unit_m, const std::string& version,
                           std::vector<std::string>& notes, const std::string& name) {
    using S = LuminousOpening::Shape;
    const auto sgn = [](double v) { return v > 0.0 ? 1 : v < 0.0 ? -1 : 0; };
    const int sw = sgn(w), sl = sgn(l), sh = sgn(h);
    const auto is = [&](int a, int b, int c) { return sw == a && sl == b && sh == c; };
    LuminousOpening o;
    o.width_m = std::abs(w) * unit_m;
    o.length_m = std::abs(l) * unit_m;
    o.height_m = std::abs(h) * unit_m;
    std::optional<S> shape;
    if (is(0, 0, 0)) shape = S::point;
    else if (is(1, 1, 0)) shape = S::rectangle;
    else if (is(1, 1, 1)) shape = S::box;
    else if (version >= "2002") {
        if (is(-1, -1, 0)) shape = S::ellipse;
        else if (is(-1, -1, 1)) shape = S::vertical_cylinder;
        else if (is(-1, 1, -1)) shape = S::cylinder_along_length;
        else if (is(1, -1, -1)) shape = S::cylinder_along_width;
        else if (is(-1, -1, -1)) shape = S::ellipsoid;
    } else if (version == "1995") {
        if (is(-1, 0, 0)) shape = S::ellipse;
        else if (is(-1, 0, 1)) shape = S::vertical_cylinder;
        else if (is(-1, 0, -1)) shape = S::ellipsoid;
        else if (is(-1, 1, 0)) shape = S::cylinder_along_length;
        else if (is(1, 0, -1)) shape = S::cylinder_along_width;
        else if (is(-1, 1, 1) || is(1, -1, 1)) shape = S::vertical_cylinder;
        else if (is(-1, 1, -1) || is(1, -1, -1)) shape = S::ellipsoid;
    } else {
        if (is(-1, 0, 0) || is(-1, 1, 0)) shape = S::ellipse;
        else if (is(-1, 0, 1)) shape = S::vertical_cylinder;
        else if (is(-1, 1, 1)) shape = S::ellipsoid;
    }
    if (!shape) {
        notes.push_back(name + ": luminous dimensions width " + fmt(w) + ", length " + fmt(l) + ", height " + fmt(h) +
                        " match no LM-63-" + version +
                        " luminous shape; the luminaire emits from its photometric centre");
        return LuminousOpening{};
    }
    o.shape = *shape;
    // Round shapes written with one size: the others are its diameter.
    const double d = o.width_m;
    if (o.length_m == 0.0 && *shape != S::point && *shape != S::rectangle && *shape != S::box) o.length_m = d;
    if (o.height_m == 0.0 && (*shape == S::ellipsoid || *shape == S::cylinder_along_length)) o.height_m = d;
    if (*shape == S::cylinder_along_width && o.height_m == 0.0) o.height_m = o.length_m;
    return o;
}

// --- The file's parts, in the order LM-63 gives them.

// The lines before TILT=.
struct Header {
    std::string version;         // "1986" (none stated), "1991", "1995", "2002", "2019", ...
    std::size_t tilt_index = 0;  // the TILT= line
    std::string tilt;            // its value: NONE, INCLUDE or a file name
};

// The version a first line states ("IESNA:LM-63-2002", "IESNA91", ...), "" if none.
std::string stated_version(std::string_view l) {
    if (l.starts_with("IESNA:LM-63-") || l.starts_with("IES:LM-63-")) return std::string(l.substr(l.rfind('-') + 1));
    if (l.starts_with("IESNA91")) return "1991";
    if (l.starts_with("IESNA95")) return "1995";
    return "";
}

// "[KEY] value"; "[MORE]" continues the previous keyword.
void read_keyword(std::string_view l, std::vector<std::pair<std::string, std::string>>& keywords) {
    const auto close = l.find(']');
    if (close == std::string_view::npos) return;
    const std::string key(l.substr(1, close - 1));
    const std::string value(trim(l.substr(close + 1)));
    if (key == "MORE" && !keywords.empty()) keywords.back().second += "\n" + value;
    else keywords.emplace_back(key, value);
}

// The version line and the keywords up to the TILT line (other text is ignored); sets the
// format, the keywords and the luminaire's name.
Header read_header(const std::vector<std::string>& lines, const std::string& name, int last_line, Photometry& p) {
    Header h;
    std::optional<std::string_view> tilt;
    for (; h.tilt_index < lines.size(); ++h.tilt_index) {
        const std::string_view l = trim(lines[h.tilt_index]);
        if ((tilt = tilt_value(l))) break;
        if (h.tilt_index == 0) h.version = stated_version(l);
        if (l.starts_with('[')) read_keyword(l, p.keywords);
    }
    if (!tilt) fail_at(name, last_line, "no TILT= line found; is this an IES LM-63 file?");
    if (h.version.empty()) h.version = "1986";
    h.tilt = std::string(*tilt);
    p.format = "IES LM-63-" + h.version;
    for (const auto& [k, v] : p.keywords)
        if (k == "LUMINAIRE" && p.luminaire.empty()) p.luminaire = v;
    return h;
}

// TILT=NONE: no table; TILT=INCLUDE: the table follows; TILT=<file>: the table is in that
// file.
TiltTable read_tilt_block(const Header& h, Reader& rd, const std::filesystem::path& file) {
    const std::string& tv = h.tilt;
    if (iequals(tv, "INCLUDE")) return read_tilt(rd);
    if (iequals(tv, "NONE")) return {};
    // A tilt file is named relative to the IES file. A name the file system cannot even
    // look up (too long, say) is as absent as a missing file.
    const std::filesystem::path tilt_file = file.parent_path() / tv;
    std::error_code ec;
    if (tv.empty() || !std::filesystem::exists(tilt_file, ec))
        fail_at(file.string(), static_cast<int>(h.tilt_index) + 1, "TILT file '" + tv + "' not found");
    const std::vector<std::string> tl = detail::read_lines(tilt_file, "TILT file");
    Reader trd(tilt_file.string(), tokens_of(tl, 0), std::max(1, static_cast<int>(tl.size())));
    TiltTable t = read_tilt(trd);
    if (!trd.done()) trd.fail(trd.line(), "unexpected data after the tilt multipliers");
    return t;
}

// What the numbers before the angles say about the table that follows.
struct Layout {
    int n_v = 0, n_h = 0;
    int counts_line = 0;  // where the angle counts are, for errors in the angles
    const char* type_name = "";
    double scale = 1.0;  // candela multiplier times the ballast factors that apply
};

// Number of lamps and lumens per lamp (-1 = absolute photometry).
void read_lamps(Reader& rd, Photometry& p) {
    p.num_lamps = rd.integer("number of lamps");
    const double lumens_per_lamp = rd.number("lumens per lamp");
    if (!(lumens_per_lamp > 0.0 || lumens_per_lamp == -1.0))
        rd.fail(rd.prev_line(),
                "lumens per lamp must be > 0, or -1 for absolute photometry, found " + fmt(lumens_per_lamp));
    p.lamp_flux_lm = lumens_per_lamp > 0.0 ? lumens_per_lamp * std::max(p.num_lamps, 1) : -1.0;
}

// Numbers of vertical and horizontal angles and the photometric type (1 C, 2 B, 3 A).
void read_counts_and_type(Reader& rd, Layout& t, Photometry& p) {
    t.counts_line = rd.line();
    t.n_v = rd.integer("number of vertical angles");
    if (t.n_v < 2) rd.fail(rd.prev_line(), "need at least 2 vertical angles, found " + fmt(t.n_v));
    t.n_h = rd.integer("number of horizontal angles");
    if (t.n_h < 1) rd.fail(rd.prev_line(), "need at least 1 horizontal angle, found " + fmt(t.n_h));
    const int type = rd.integer("photometric type");
    if (type < 1 || type > 3)
        rd.fail(rd.prev_line(), "photometric type must be 1 (type C), 2 (type B) or 3 (type A), found " + fmt(type));
    p.type = static_cast<PhotometricType>(type);
    t.type_name = type == 1 ? "type C" : type == 2 ? "type B" : "type A";
}

// Units type (1 feet, 2 metres) and the luminous width, length and height.
void read_opening(Reader& rd, const std::string& version, const std::string& name, Photometry& p) {
    const int units = rd.integer("units type");
    if (units != 1 && units != 2)
        rd.fail(rd.prev_line(), "units type must be 1 (feet) or 2 (meters), found " + fmt(units));
    const double w = rd.number("luminous width");
    const double l = rd.number("luminous length");
    const double h = rd.number("luminous height");
    p.opening = opening_of(w, l, h, units == 1 ? kFoot_m : 1.0, version, p.notes, name);
}

// Lamps, multiplier, counts and type, opening, ballast factor, ballast-lamp photometric
// factor and input watts.
Layout read_layout(Reader& rd, const std::string& version, const std::string& name, Photometry& p) {
    Layout t;
    read_lamps(rd, p);
    const double multiplier = rd.number("candela multiplier");
    if (multiplier <= 0.0) rd.fail(rd.prev_line(), "candela multiplier must be > 0, found " + fmt(multiplier));
    read_counts_and_type(rd, t, p);
    read_opening(rd, version, name, p);
    const double ballast = rd.number("ballast factor");
    if (ballast <= 0.0) rd.fail(rd.prev_line(), "ballast factor must be > 0, found " + fmt(ballast));
    // LM-63-1986 and -1991: the ballast-lamp photometric factor multiplies the candela
    // values. LM-63-1995 and -2002 made the field "future use" (1) and LM-63-2019 "file
    // generation type" (ies2rad reads it the same way).
    const bool blp_applies = version < "1995";
    const double blp = rd.number(blp_applies ? "ballast-lamp photometric factor" : "future use / file generation type");
    if (blp_applies && blp <= 0.0)
        rd.fail(rd.prev_line(), "ballast-lamp photometric factor must be > 0, found " + fmt(blp));
    p.input_watts = rd.number("input watts");
    t.scale = multiplier * ballast * (blp_applies ? blp : 1.0);
    return t;
}

// The vertical, then the horizontal angles, in the ranges of the type.
void read_angle_sets(Reader& rd, const Layout& t, Photometry& p) {
    if (p.type == PhotometricType::C) {
        p.vertical_deg = read_angles(rd, t.n_v, "vertical", 0.0, 180.0, t.counts_line, t.type_name);
        p.horizontal_deg = read_angles(rd, t.n_h, "horizontal", 0.0, 360.0, t.counts_line, t.type_name);
    } else {
        p.vertical_deg = read_angles(rd, t.n_v, "vertical", -90.0, 90.0, t.counts_line, t.type_name);
        p.horizontal_deg = read_angles(rd, t.n_h, "horizontal", -90.0, 90.0, t.counts_line, t.type_name);
        if (t.n_h < 2)
            rd.fail(rd.prev_line(),
                    std::string("need at least 2 horizontal angles for ") + t.type_name + " photometry");
    }
}

// A 0..X table with 180 < X < 360 covers the circle with no symmetry: C360 = C0.
bool wraps_around(const Photometry& p) {
    const auto& hz = p.horizontal_deg;
    return p.type == PhotometricType::C && hz.size() >= 2 && near(hz.front(), 0.0) && hz.back() > 180.0 + kAngleTol &&
           hz.back() < 360.0 - kAngleTol;
}

// The horizontal angles must give one of the layouts of the type.
void check_horizontal_range(const Reader& rd, int angles_line, const Photometry& p, bool wraps, const char* type_name) {
    const auto& hz = p.horizontal_deg;
    if (p.type == PhotometricType::C && !wraps && !c_plane_symmetry(hz))
        rd.fail(angles_line, "horizontal angles must run 0, 0-90, 0-180, 90-270 or 0-360 (or from 0 to above 180) "
                             "for type C photometry, found " +
                                 fmt(hz.front()) + "-" + fmt(hz.back()));
    if (p.type != PhotometricType::C && !(near(hz.front(), 0.0) || near(hz.front(), -90.0)))
        rd.fail(angles_line, std::string("horizontal angles must start at -90, or at 0 (lateral symmetry) for ") +
                                 type_name + " photometry, found " + fmt(hz.front()));
}

// #vertical candela values per horizontal angle, times the file's factors, and nothing
// after them; false if all are zero.
bool read_candela(Reader& rd, const Layout& t, Photometry& p) {
    const std::size_t expected = static_cast<std::size_t>(t.n_v) * static_cast<std::size_t>(t.n_h);
    const auto count_error = [&](int line, std::size_t found) {
        rd.fail(line, "expected " + std::to_string(expected) + " candela values (" + std::to_string(t.n_v) +
                          " vertical x " + std::to_string(t.n_h) + " horizontal), found " + std::to_string(found));
    };
    bool any_light = false;
    p.candela_cd.assign(t.n_h, {});
    for (int j = 0; j < t.n_h; ++j) {
        for (int i = 0; i < t.n_v; ++i) {
            if (rd.done()) count_error(rd.line(), static_cast<std::size_t>(j) * t.n_v + i);
            const double cd = rd.number("candela value");
            if (cd < 0.0) rd.fail(rd.prev_line(), "negative candela value " + fmt(cd));
            any_light = any_light || cd > 0.0;
            if (!std::isfinite(cd * t.scale))
                rd.fail(rd.prev_line(),
                        "candela value " + fmt(cd) + " times the multipliers (" + fmt(t.scale) + ") is too large");
            p.candela_cd[j].push_back(cd * t.scale);
        }
    }
    // Some 1986 exports close the table with a line "END".
    if (rd.remaining() == 1 && rd.peek_is("END")) rd.skip();
    if (!rd.done()) count_error(rd.line(), expected + rd.remaining());
    return any_light;
}

// A wrapping table (wraps_around) gets its C360 plane, a copy of C0.
void close_the_circle(Photometry& p, const std::string& name) {
    auto& hz = p.horizontal_deg;
    p.notes.push_back(name + ": horizontal angles run 0-" + fmt(hz.back()) + " with no symmetry; C360 is taken as C0");
    hz.push_back(360.0);
    p.candela_cd.push_back(p.candela_cd.front());
}

// Types B and A from 0 have lateral symmetry: the planes mirrored to -H.
void mirror_lateral_symmetry(Photometry& p) {
    auto& hz = p.horizontal_deg;
    const std::size_t n = hz.size();
    std::vector<double> angles;
    std::vector<std::vector<double>> cd;
    for (std::size_t k = n; k-- > 1;) {
        angles.push_back(-hz[k]);
        cd.push_back(p.candela_cd[k]);
    }
    angles.insert(angles.end(), hz.begin(), hz.end());
    cd.insert(cd.end(), p.candela_cd.begin(), p.candela_cd.end());
    hz = std::move(angles);
    p.candela_cd = std::move(cd);
}

// Type C: a table that stops short of 90 or 180 degrees with light in its last angle has
// cut the distribution off; luxtrace emits nothing beyond it (nor below its first angle).
void note_vertical_range(Photometry& p, const std::string& name) {
    const double last = p.vertical_deg.back(), first = p.vertical_deg.front();
    double edge_cd = 0.0;
    for (const auto& plane : p.candela_cd) edge_cd = std::max(edge_cd, plane.back());
    if (!near(last, 90.0) && !near(last, 180.0) && edge_cd > 0.0)
        p.notes.push_back(name + ": vertical angles stop at " + fmt(last) + " degrees with " + fmt(edge_cd) +
                          " cd there; LM-63 tables end at 90 or 180, and no light is emitted beyond " + fmt(last));
    if (!near(first, 0.0) && !near(first, 90.0))
        p.notes.push_back(name + ": vertical angles start at " + fmt(first) +
                          " degrees; LM-63 tables start at 0 or 90, and no light is emitted below " + fmt(first));
}

// The table's flux must be a positive number, and relative photometry cannot give out more
// light than its lamps (a few per cent for measurement and interpolation aside).
void check_flux(Photometry& p, const std::string& name, int last_line) {
    const double flux = p.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux)))
        fail_at(name, last_line,
                "the photometry's flux (" + fmt(flux) +
                    " lm) is not a positive number; "
                    "are the angles or the candela values right?");
    if (p.lamp_flux_lm > 0.0 && flux > 1.1 * p.lamp_flux_lm)
        p.notes.push_back(name + ": the table carries " + fmt(flux) + " lm, " + fmt(flux / p.lamp_flux_lm) +
                          " times the " + fmt(p.lamp_flux_lm) +
                          " lm of its lamps; check the file's multiplier and values");
}

}  // namespace

Photometry load_ies(const std::filesystem::path& file) {
    const std::string name = file.string();
    const std::vector<std::string> lines = detail::read_lines(file, "IES file");
    const int last_line = std::max(1, static_cast<int>(lines.size()));

    Photometry p;
    const Header header = read_header(lines, name, last_line, p);
    Reader rd(name, tokens_of(lines, header.tilt_index + 1), last_line);
    p.tilt = read_tilt_block(header, rd, file);
    const Layout layout = read_layout(rd, header.version, name, p);
    read_angle_sets(rd, layout, p);
    const int angles_line = rd.prev_line();
    const bool wraps = wraps_around(p);
    check_horizontal_range(rd, angles_line, p, wraps, layout.type_name);
    if (!read_candela(rd, layout, p)) fail_at(name, last_line, "all candela values are zero");
    if (wraps) close_the_circle(p, name);
    if (p.type != PhotometricType::C && near(p.horizontal_deg.front(), 0.0)) mirror_lateral_symmetry(p);
    if (p.type == PhotometricType::C) note_vertical_range(p, name);
    check_flux(p, name, last_line);
    return p;
}

}  // namespace luxtrace
