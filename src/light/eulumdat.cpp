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

}  // namespace

Photometry load_eulumdat(const std::filesystem::path& file, int lamp_set) {
    const std::string name = file.string();
    const std::vector<std::string> lines = detail::read_lines(file, "EULUMDAT file");
    const int last_line = std::max(1, static_cast<int>(lines.size()));
    LineReader rd(name, lines);
    Photometry p;
    p.format = "EULUMDAT";
    p.type = PhotometricType::C;
    const std::string company = rd.text("company identification (line 1)");
    const int ityp = rd.integer("type indicator Ityp (line 2)");
    if (ityp < 0 || ityp > 3) rd.fail(rd.prev_line(), "type indicator Ityp must be 0, 1, 2 or 3, found " + fmt(ityp));
    const int isym = rd.integer("symmetry indicator Isym (line 3)");
    if (isym < 0 || isym > 4) rd.fail(rd.prev_line(), "symmetry indicator Isym must lie in 0-4, found " + fmt(isym));
    const int mc = rd.integer("number of C planes Mc (line 4)");
    if (mc < 1 || mc > 3600) rd.fail(rd.prev_line(), "number of C planes Mc must lie in [1, 3600], found " + fmt(mc));
    if ((isym == 2 || isym == 3) && mc % 2 != 0)
        rd.fail(rd.prev_line(), "Isym " + fmt(isym) + " needs an even number of C planes, found " + fmt(mc));
    if (isym == 4 && mc % 4 != 0)
        rd.fail(rd.prev_line(), "Isym 4 needs a number of C planes divisible by 4, found " + fmt(mc));
    rd.number("C plane distance Dc (line 5)");
    const int ng = rd.integer("number of intensities per C plane Ng (line 6)");
    if (ng < 2 || ng > 3600)
        rd.fail(rd.prev_line(), "number of gamma angles Ng must lie in [2, 3600], found " + fmt(ng));
    rd.number("gamma angle distance Dg (line 7)");
    rd.text("measurement report number (line 8)");
    p.luminaire = rd.text("luminaire name (line 9)");
    rd.text("luminaire number (line 10)");
    rd.text("file name (line 11)");
    rd.text("date/user (line 12)");
    for (const char* what : {"luminaire length (line 13)", "luminaire width (line 14)", "luminaire height (line 15)"})
        rd.number(what);
    const int area_line = rd.line();
    const double la = rd.number("luminous area length or diameter (line 16)");
    const double wa = rd.number("luminous area width (line 17)");
    double h[4];
    for (double& v : h) v = rd.number("luminous area height (lines 18-21)");
    for (const double v : {la, wa, h[0], h[1], h[2], h[3]})
        if (v < 0.0) rd.fail(area_line, "luminous area dimensions must not be negative, found " + fmt(v));
    rd.number("downward flux fraction (line 22)");
    const double lorl = rd.number("light output ratio LORL (line 23)");
    if (!(lorl > 0.0 && lorl <= 100.0 + 1e-9))
        rd.fail(rd.prev_line(), "light output ratio LORL must lie in (0, 100] %, found " + fmt(lorl));
    const double conversion = rd.number("conversion factor for intensities (line 24)");
    if (!(conversion > 0.0)) rd.fail(rd.prev_line(), "conversion factor must be > 0, found " + fmt(conversion));
    rd.number("tilt during measurement (line 25)");
    const int sets = rd.integer("number of lamp sets (line 26)");
    if (sets < 1 || sets > 20) rd.fail(rd.prev_line(), "number of lamp sets must lie in [1, 20], found " + fmt(sets));
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
    for (int k = 0; k < 10; ++k) rd.number("direct ratio " + std::to_string(k + 1) + " of 10");
    p.stated_flux_lm = set_flux * lorl / 100.0;
    p.keywords.emplace_back("MANUFAC", company);
    p.keywords.emplace_back("LUMINAIRE", p.luminaire);

    const int angles_line = rd.line();
    const auto nums = rd.rest();
    std::size_t at = 0;
    const auto take = [&](const std::string& what) {
        if (at >= nums.size()) rd.fail(last_line, "unexpected end of file, expected " + what);
        return nums[at++];
    };
    std::vector<double> c_angles, g_angles;
    for (int k = 0; k < mc; ++k) {
        const auto [v, line] = take("C angle " + std::to_string(k + 1) + " of " + std::to_string(mc));
        if (v < -kAngleTol || v >= 360.0 - kAngleTol) rd.fail(line, "C angle " + fmt(v) + " is outside [0, 360)");
        if (!c_angles.empty() && v <= c_angles.back())
            rd.fail(line, "C angles must increase, found " + fmt(v) + " after " + fmt(c_angles.back()));
        c_angles.push_back(v);
    }
    for (int k = 0; k < ng; ++k) {
        const auto [v, line] = take("gamma angle " + std::to_string(k + 1) + " of " + std::to_string(ng));
        if (v < -kAngleTol || v > 180.0 + kAngleTol) rd.fail(line, "gamma angle " + fmt(v) + " is outside [0, 180]");
        if (!g_angles.empty() && v <= g_angles.back())
            rd.fail(line, "gamma angles must increase, found " + fmt(v) + " after " + fmt(g_angles.back()));
        g_angles.push_back(v);
    }
    // The planes stored under Isym, as indices into the C angles: Isym 3 stores the
    // C90-C270 half starting at C270 and running on through C0 to C90 (the planes of
    // C270..C360..C90 equal, by the symmetry, those of C270..C180..C90).
    int first = 0, count = mc;
    if (isym == 1) count = 1;
    else if (isym == 2) count = mc / 2 + 1;
    else if (isym == 3) {
        first = 3 * mc / 4;
        count = mc / 2 + 1;
    } else if (isym == 4) count = mc / 4 + 1;
    if (isym == 3 && mc % 4 != 0)
        rd.fail(angles_line, "Isym 3 needs a number of C planes divisible by 4, found " + fmt(mc));
    p.vertical_deg = g_angles;
    const double scale = set_flux / 1000.0 * conversion;
    bool any_light = false;
    std::vector<std::pair<double, std::vector<double>>> planes;  // (C angle, intensities)
    for (int k = 0; k < count; ++k) {
        std::vector<double> plane;
        for (int g = 0; g < ng; ++g) {
            const auto [v, line] = take("intensity " + std::to_string(k * ng + g + 1) + " of " +
                                        std::to_string(count * ng) + " (Isym " + fmt(isym) + ": " + fmt(count) +
                                        " C planes x " + fmt(ng) + " gamma angles)");
            if (v < 0.0) rd.fail(line, "negative intensity " + fmt(v));
            if (!std::isfinite(v * scale)) rd.fail(line, "intensity " + fmt(v) + " times the lamp flux is too large");
            any_light = any_light || v > 0.0;
            plane.push_back(v * scale);
        }
        double c = 0.0;
        if (isym == 3) {
            // C270 + k Dc, as the mirror image 180 - c in the C90..C270 half luxtrace keeps.
            c = c_angles[static_cast<std::size_t>((first + k) % mc)];
            c = std::fmod(540.0 - c, 360.0);
        } else if (isym != 1) {
            c = c_angles[static_cast<std::size_t>(k)];
        }
        planes.emplace_back(c, std::move(plane));
    }
    std::sort(planes.begin(), planes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [c, plane] : planes) {
        p.horizontal_deg.push_back(c);
        p.candela_cd.push_back(std::move(plane));
    }
    if (at < nums.size())
        rd.fail(nums[at].second, "unexpected data after the " + std::to_string(count * ng) + " intensities (Isym " +
                                     fmt(isym) + ": " + fmt(count) + " C planes x " + fmt(ng) + " gamma angles)");
    if (!any_light) rd.fail(last_line, "all intensities are zero");
    // Isym 0: the last plane is followed by C360 = C0.
    if (isym == 0) {
        p.horizontal_deg.push_back(360.0);
        p.candela_cd.push_back(p.candela_cd.front());
    }
    // The stored planes must be where Isym puts them (0, 90 or 180 first and last).
    const double lo = p.horizontal_deg.front(), hi = p.horizontal_deg.back();
    const double want_lo = isym == 3 ? 90.0 : 0.0;
    const double want_hi = isym == 0 ? 360.0 : isym == 1 ? 0.0 : isym == 2 ? 180.0 : isym == 3 ? 270.0 : 90.0;
    if (std::abs(lo - want_lo) > 1e-6 || std::abs(hi - want_hi) > 1e-6)
        rd.fail(angles_line, "Isym " + fmt(isym) + " stores C" + fmt(isym == 3 ? 270.0 : want_lo) + "-C" +
                                 fmt(isym == 3 ? 90.0 : want_hi) + ", but the C angles do not give those planes");
    for (std::size_t k = 1; k < p.horizontal_deg.size(); ++k)
        if (!(p.horizontal_deg[k] > p.horizontal_deg[k - 1]))
            rd.fail(angles_line, "the C angles of the stored planes must increase");

    // Luminous area (mm): length along C0-C180 ... see docs/PHOTOMETRY.md.
    using S = LuminousOpening::Shape;
    const double hmax = std::max({h[0], h[1], h[2], h[3]});
    if (la > 0.0) {
        p.opening.length_m = la / 1000.0;
        p.opening.width_m = (wa > 0.0 ? wa : la) / 1000.0;
        p.opening.height_m = hmax / 1000.0;
        if (wa > 0.0) p.opening.shape = hmax > 0.0 ? S::box : S::rectangle;
        else p.opening.shape = hmax > 0.0 ? S::vertical_cylinder : S::ellipse;
        if (hmax > 0.0 && std::min({h[0], h[1], h[2], h[3]}) < hmax)
            p.notes.push_back(name + ": the luminous area's heights differ between C planes (" + fmt(h[0]) + ", " +
                              fmt(h[1]) + ", " + fmt(h[2]) + ", " + fmt(h[3]) + " mm); luxtrace uses " + fmt(hmax) +
                              " mm all round");
    }
    const double flux = p.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux)))
        rd.fail(last_line, "the photometry's flux (" + fmt(flux) + " lm) is not a positive number");
    return p;
}

}  // namespace luxtrace
