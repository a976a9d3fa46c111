// IES LM-63 reader and emission sampling; see ies.hpp.
//
// LM-63 rules applied by load_ies (1986, 1995 and 2002 layouts):
//  - Everything before the line starting with "TILT=" is header: an optional first line
//    "IESNA:LM-63-xxxx" and keyword lines "[KEY] value" ("[MORE]" continues the previous
//    keyword); other text (1986 files) is ignored.
//  - TILT=NONE is required. TILT=INCLUDE (tilt table in the file) and TILT=<file> change
//    the lamp output with the luminaire's tilt; they are rejected rather than ignored.
//  - After the TILT line come numbers separated by spaces, commas or newlines, in any
//    line layout: #lamps, lumens/lamp (-1 = absolute), candela multiplier, #vertical,
//    #horizontal, photometric type, units type, width, length, height; then ballast
//    factor, future use (the 1995 "ballast-lamp photometric factor", read and ignored),
//    input watts; then the vertical angles, the horizontal angles, and #vertical candela
//    values for each horizontal angle in turn. Nothing may follow.
//  - Only photometric type 1 (C) is supported. Vertical angles lie in [0,180] and
//    horizontal ones in [0,360], both strictly increasing. Horizontal angles must be
//    0 (rotational), 0-90 (quadrant), 0-180 (bilateral), 90-270 (bilateral, 1995) or
//    0-360 (none).
//  - Candela values are >= 0; they are scaled by the candela multiplier times the ballast
//    factor, both of which must be > 0.
#include "luxtrace/light/ies.hpp"

#include "luxtrace/core/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace luxtrace {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kAngleTol = 1e-6;  // degrees; file angles are written with few digits

std::string fmt(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

std::string_view trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r\f\v");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t\r\f\v");
    return s.substr(b, e - b + 1);
}

bool iequals(std::string_view a, std::string_view b) {
    return std::ranges::equal(a, b, [](char x, char y) {
        return std::tolower(static_cast<unsigned char>(x)) ==
               std::tolower(static_cast<unsigned char>(y));
    });
}

[[noreturn]] void fail_at(const std::string& file, int line, const std::string& what) {
    throw InputError(file + ":" + std::to_string(line) + ": " + what);
}

// "TILT=..." (spaces allowed around '='); returns the value after '='.
std::optional<std::string_view> tilt_value(std::string_view l) {
    l = trim(l);
    if (l.size() < 4 || !iequals(l.substr(0, 4), "TILT")) return std::nullopt;
    const std::string_view rest = trim(l.substr(4));
    if (!rest.starts_with('=')) return std::nullopt;
    return trim(rest.substr(1));
}

bool near(double a, double b) { return std::abs(a - b) <= kAngleTol; }

struct Token {
    std::string_view text;
    int line;
};

// Hands out the numeric fields after the TILT line; every error names file and line.
class Reader {
public:
    Reader(std::string file, std::vector<Token> tokens, int last_line)
        : file_(std::move(file)), tokens_(std::move(tokens)), last_line_(last_line) {}

    [[noreturn]] void fail(int line, const std::string& what) const {
        fail_at(file_, line, what);
    }
    bool done() const { return pos_ == tokens_.size(); }
    std::size_t remaining() const { return tokens_.size() - pos_; }
    int line() const { return done() ? last_line_ : tokens_[pos_].line; }  // next token's
    int prev_line() const { return pos_ == 0 ? last_line_ : tokens_[pos_ - 1].line; }

    double number(const std::string& what) {
        if (done()) fail(last_line_, "unexpected end of file, expected " + what);
        const Token& t = tokens_[pos_++];
        std::string_view s = t.text;
        if (s.size() > 1 && s.front() == '+') s.remove_prefix(1);  // from_chars rejects '+'
        double v = 0.0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
            fail(t.line, "expected a number for " + what + ", found '" + std::string(t.text) + "'");
        return v;
    }
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
std::vector<double> read_angles(Reader& rd, int n, const char* kind, double lo, double hi,
                                int counts_line) {
    std::vector<double> a;
    for (int i = 0; i < n; ++i) {
        const double v = rd.number(std::string(kind) + " angle " + std::to_string(i + 1) +
                                   " of " + std::to_string(n));
        if (v < lo - kAngleTol || v > hi + kAngleTol)
            rd.fail(rd.prev_line(), std::string(kind) + " angle " + fmt(v) + " is outside [" +
                                        fmt(lo) + "," + fmt(hi) + "] for type C photometry");
        if (!a.empty() && v <= a.back())
            rd.fail(rd.prev_line(),
                    std::string(kind) + " angles must increase, found " + fmt(v) + " after " +
                        fmt(a.back()) + " (are the angle counts on line " +
                        std::to_string(counts_line) + " right?)");
        a.push_back(v);
    }
    return a;
}

std::optional<IesSymmetry> symmetry_of(const std::vector<double>& h) {
    if (h.size() == 1) return IesSymmetry::Rotational;
    if (h.empty()) return std::nullopt;
    if (near(h.front(), 90.0) && near(h.back(), 270.0)) return IesSymmetry::Bilateral90;
    if (!near(h.front(), 0.0)) return std::nullopt;
    if (near(h.back(), 90.0)) return IesSymmetry::Quadrant;
    if (near(h.back(), 180.0)) return IesSymmetry::Bilateral;
    if (near(h.back(), 360.0)) return IesSymmetry::Full;
    return std::nullopt;
}

// Index i of the interval [a[i], a[i+1]] holding x (a has >= 2 entries, x clamped).
std::size_t interval(const std::vector<double>& a, double x) {
    const auto it = std::upper_bound(a.begin(), a.end(), x);
    const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - a.begin() - 1, 0));
    return std::min(i, a.size() - 2);
}

}  // namespace

IesSymmetry IesPhotometry::symmetry() const {
    if (const auto s = symmetry_of(horizontal_deg)) return *s;
    throw std::logic_error("IesPhotometry: horizontal angles fit no LM-63 symmetry");
}

double IesPhotometry::intensity_cd(double gamma_rad, double c_rad) const {
    const double g = gamma_rad / kDeg;
    const auto& v = vertical_deg;
    if (v.size() < 2 || g < v.front() - kAngleTol || g > v.back() + kAngleTol) return 0.0;
    const std::size_t i = interval(v, g);
    const double s = std::clamp((g - v[i]) / (v[i + 1] - v[i]), 0.0, 1.0);
    const auto along_gamma = [&](std::size_t plane) {
        return (1.0 - s) * candela_cd[plane][i] + s * candela_cd[plane][i + 1];
    };

    const IesSymmetry sym = symmetry();
    if (sym == IesSymmetry::Rotational) return along_gamma(0);

    double c = std::fmod(c_rad / kDeg, 360.0);
    if (c < 0.0) c += 360.0;
    // Fold c into the file's range by the mirror planes of its symmetry.
    switch (sym) {
    case IesSymmetry::Quadrant:
        if (c > 270.0) c = 360.0 - c;
        else if (c > 180.0) c = c - 180.0;
        else if (c > 90.0) c = 180.0 - c;
        break;
    case IesSymmetry::Bilateral:
        if (c > 180.0) c = 360.0 - c;
        break;
    case IesSymmetry::Bilateral90:
        if (c < 90.0) c = 180.0 - c;
        else if (c > 270.0) c = 540.0 - c;
        break;
    default:
        break;
    }
    const auto& h = horizontal_deg;
    const std::size_t j = interval(h, c);
    const double t = std::clamp((c - h[j]) / (h[j + 1] - h[j]), 0.0, 1.0);
    return (1.0 - t) * along_gamma(j) + t * along_gamma(j + 1);
}

double IesPhotometry::flux_lm() const {
    const auto& v = vertical_deg;
    if (v.size() < 2 || horizontal_deg.empty()) return 0.0;
    // Per plane, the exact integral over gamma of the linear interpolant times sin(gamma):
    // on [a,b] the hat weights integrate to
    //   W0 = ((b-a) cos a - (sin b - sin a)) / (b-a),  W1 = (sin b - sin a - (b-a) cos b) / (b-a).
    std::vector<double> plane(horizontal_deg.size(), 0.0);
    for (std::size_t i = 0; i + 1 < v.size(); ++i) {
        const double a = v[i] * kDeg, b = v[i + 1] * kDeg, w = b - a;
        const double ds = std::sin(b) - std::sin(a);
        const double w0 = (w * std::cos(a) - ds) / w;
        const double w1 = (ds - w * std::cos(b)) / w;
        for (std::size_t k = 0; k < plane.size(); ++k)
            plane[k] += w0 * candela_cd[k][i] + w1 * candela_cd[k][i + 1];
    }
    if (plane.size() == 1) return 2.0 * kPi * plane[0];
    // Linear in c between planes (trapezoid is exact); the symmetry repeats the file's
    // span of planes 360/span times around the circle.
    const auto& h = horizontal_deg;
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < h.size(); ++k)
        sum += 0.5 * (plane[k] + plane[k + 1]) * (h[k + 1] - h[k]) * kDeg;
    return sum * 360.0 / (h.back() - h.front());
}

IesPhotometry load_ies(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
        throw InputError(name + ": not a regular file");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name + ": cannot open IES file");
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) {
        if (!l.empty() && l.back() == '\r') l.pop_back();
        lines.push_back(std::move(l));
    }
    const int last_line = std::max(1, static_cast<int>(lines.size()));

    IesPhotometry p;
    // Header up to the TILT line.
    std::size_t tilt = 0;
    std::optional<std::string_view> tilt_val;
    for (; tilt < lines.size(); ++tilt) {
        const std::string_view l = trim(lines[tilt]);
        if ((tilt_val = tilt_value(l))) break;
        if (l.starts_with('[')) {
            const auto close = l.find(']');
            if (close == std::string_view::npos) continue;
            const std::string key(l.substr(1, close - 1));
            const std::string value(trim(l.substr(close + 1)));
            if (key == "MORE" && !p.keywords.empty())
                p.keywords.back().second += "\n" + value;
            else
                p.keywords.emplace_back(key, value);
        }
    }
    if (!tilt_val) fail_at(name, last_line, "no TILT= line found; is this an IES LM-63 file?");
    const int tilt_line = static_cast<int>(tilt) + 1;
    const std::string_view tv = *tilt_val;
    if (iequals(tv, "INCLUDE"))
        fail_at(name, tilt_line, "TILT=INCLUDE is not supported (only TILT=NONE)");
    if (!iequals(tv, "NONE")) {
        // A tilt file is named relative to the IES file. A name the file system cannot
        // even look up (too long, say) is as absent as a missing file.
        std::error_code tilt_ec;
        if (tv.empty() || !std::filesystem::exists(file.parent_path() / std::string(tv), tilt_ec))
            fail_at(name, tilt_line, "TILT file '" + std::string(tv) + "' not found");
        fail_at(name, tilt_line, "TILT=" + std::string(tv) + " is not supported (only TILT=NONE)");
    }

    std::vector<Token> tokens;
    for (std::size_t k = tilt + 1; k < lines.size(); ++k) {
        const std::string_view l = lines[k];
        std::size_t pos = 0;
        while (pos < l.size()) {
            const auto b = l.find_first_not_of(" \t\r\f\v,", pos);
            if (b == std::string_view::npos) break;
            auto e = l.find_first_of(" \t\r\f\v,", b);
            if (e == std::string_view::npos) e = l.size();
            tokens.push_back({l.substr(b, e - b), static_cast<int>(k) + 1});
            pos = e;
        }
    }
    Reader rd(name, std::move(tokens), last_line);

    p.num_lamps = rd.integer("number of lamps");
    p.lumens_per_lamp = rd.number("lumens per lamp");
    const double multiplier = rd.number("candela multiplier");
    if (multiplier <= 0.0)
        rd.fail(rd.prev_line(), "candela multiplier must be > 0, found " + fmt(multiplier));
    const int counts_line = rd.line();
    const int n_v = rd.integer("number of vertical angles");
    if (n_v < 2) rd.fail(rd.prev_line(), "need at least 2 vertical angles, found " + fmt(n_v));
    const int n_h = rd.integer("number of horizontal angles");
    if (n_h < 1) rd.fail(rd.prev_line(), "need at least 1 horizontal angle, found " + fmt(n_h));
    const int type = rd.integer("photometric type");
    if (type == 2 || type == 3)
        rd.fail(rd.prev_line(), std::string("type ") + (type == 2 ? "B" : "A") +
                                    " photometry (photometric type " + fmt(type) +
                                    ") is not supported, only type C (1)");
    if (type != 1)
        rd.fail(rd.prev_line(), "photometric type must be 1 (type C), found " + fmt(type));
    const int units = rd.integer("units type");
    if (units != 1 && units != 2)
        rd.fail(rd.prev_line(), "units type must be 1 (feet) or 2 (meters), found " + fmt(units));
    rd.number("luminaire width");
    rd.number("luminaire length");
    rd.number("luminaire height");
    const double ballast = rd.number("ballast factor");
    if (ballast <= 0.0)
        rd.fail(rd.prev_line(), "ballast factor must be > 0, found " + fmt(ballast));
    rd.number("future use (ballast-lamp photometric factor)");
    p.input_watts = rd.number("input watts");

    p.vertical_deg = read_angles(rd, n_v, "vertical", 0.0, 180.0, counts_line);
    p.horizontal_deg = read_angles(rd, n_h, "horizontal", 0.0, 360.0, counts_line);
    if (!symmetry_of(p.horizontal_deg))
        rd.fail(rd.prev_line(), "horizontal angles must run 0, 0-90, 0-180, 90-270 or 0-360 for "
                                "type C photometry, found " + fmt(p.horizontal_deg.front()) +
                                    "-" + fmt(p.horizontal_deg.back()));

    const std::size_t expected = static_cast<std::size_t>(n_v) * static_cast<std::size_t>(n_h);
    const auto count_error = [&](int line, std::size_t found) {
        rd.fail(line, "expected " + std::to_string(expected) + " candela values (" +
                          std::to_string(n_v) + " vertical x " + std::to_string(n_h) +
                          " horizontal), found " + std::to_string(found));
    };
    const double scale = multiplier * ballast;
    bool any_light = false;
    p.candela_cd.assign(n_h, {});
    for (int j = 0; j < n_h; ++j) {
        for (int i = 0; i < n_v; ++i) {
            if (rd.done()) count_error(rd.line(), static_cast<std::size_t>(j) * n_v + i);
            const double cd = rd.number("candela value");
            if (cd < 0.0) rd.fail(rd.prev_line(), "negative candela value " + fmt(cd));
            any_light = any_light || cd > 0.0;
            if (!std::isfinite(cd * scale))
                rd.fail(rd.prev_line(), "candela value " + fmt(cd) + " times the multipliers (" + fmt(scale) +
                                            ") is too large");
            p.candela_cd[j].push_back(cd * scale);
        }
    }
    if (!rd.done()) count_error(rd.line(), expected + rd.remaining());
    if (!any_light) fail_at(name, last_line, "all candela values are zero");
    const double flux = p.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux)))
        fail_at(name, last_line, "the photometry's flux (" + fmt(flux) + " lm) is not a positive number; "
                                 "are the angles or the candela values right?");
    return p;
}

IesDistribution::IesDistribution(const IesPhotometry& p, int n_gamma, int n_c) {
    if (n_gamma < 1 || n_c < 1) throw std::invalid_argument("IesDistribution: grid size < 1");
    // The table covers only where light can go: the file's vertical range (the
    // interpolant is zero outside it) and one copy of its C-planes (the symmetry repeats
    // it `copies_` times around the circle; sample() picks the copy). Cell sizes stay
    // those of an n_gamma x n_c grid over the whole sphere, and the table shrinks with the
    // range: a downlight's quadrant-symmetric file needs an eighth of the full grid, which
    // stays in the core's cache.
    gamma0_ = std::clamp(p.vertical_deg.front(), 0.0, 180.0) * kDeg;
    const double gamma1 = std::clamp(p.vertical_deg.back(), 0.0, 180.0) * kDeg;
    n_gamma_ = std::max(1, static_cast<int>(std::ceil(n_gamma * (gamma1 - gamma0_) / kPi - 1e-9)));
    const double dg = (gamma1 - gamma0_) / n_gamma_;
    symmetry_ = p.symmetry();
    switch (symmetry_) {
    case IesSymmetry::Rotational: copies_ = 1; c0_ = 0.0; c_span_ = 2.0 * kPi; break;
    case IesSymmetry::Quadrant: copies_ = 4; c0_ = 0.0; c_span_ = 0.5 * kPi; break;
    case IesSymmetry::Bilateral: copies_ = 2; c0_ = 0.0; c_span_ = kPi; break;
    case IesSymmetry::Bilateral90: copies_ = 2; c0_ = 0.5 * kPi; c_span_ = kPi; break;
    case IesSymmetry::Full: copies_ = 1; c0_ = 0.0; c_span_ = 2.0 * kPi; break;
    }
    // Rotational symmetry: the same in every C-plane, so one column.
    n_c_ = symmetry_ == IesSymmetry::Rotational
               ? 1
               : std::max(1, static_cast<int>(std::ceil(n_c * c_span_ / (2.0 * kPi) - 1e-9)));
    const double dc = c_span_ / n_c_;
    cos_edge_.resize(n_gamma_ + 1);
    for (int i = 0; i <= n_gamma_; ++i) cos_edge_[i] = std::cos(gamma0_ + i * dg);
    if (gamma1 >= kPi) cos_edge_[n_gamma_] = -1.0;

    // Cell weight: intensity at the cell centre times the cell's exact solid angle.
    std::vector<double> row_flux(static_cast<std::size_t>(n_gamma_), 0.0), cells(static_cast<std::size_t>(n_c_));
    rows_.reserve(static_cast<std::size_t>(n_gamma_));
    for (int i = 0; i < n_gamma_; ++i) {
        const double g = gamma0_ + (i + 0.5) * dg;
        const double solid = (cos_edge_[i] - cos_edge_[i + 1]) * dc;
        double sum = 0.0;
        for (int j = 0; j < n_c_; ++j) sum += (cells[j] = p.intensity_cd(g, c0_ + (j + 0.5) * dc) * solid);
        row_flux[i] = sum;
        // A dark row is never chosen; it keeps a uniform table to stay well formed.
        if (!(sum > 0.0)) std::fill(cells.begin(), cells.end(), 1.0);
        rows_.emplace_back(cells);
    }
    double total = 0.0;
    for (double f : row_flux) total += f;
    flux_lm_ = total * copies_;
    if (!(flux_lm_ > 0.0) || !std::isfinite(flux_lm_)) throw std::invalid_argument("IesDistribution: zero flux");
    marginal_ = AliasTable(row_flux);
}

Vec3 IesDistribution::sample(double u1, double u2) const {
    constexpr double kOneMinus = 1.0 - 0x1p-53;
    u1 = std::clamp(u1, 0.0, kOneMinus);
    u2 = std::clamp(u2, 0.0, kOneMinus);
    const auto [i, t1] = marginal_.sample(u1);
    const double cg = cos_edge_[i] + t1 * (cos_edge_[i + 1] - cos_edge_[i]);
    const double sg = std::sqrt(std::max(0.0, 1.0 - cg * cg));
    // Which copy of the table's C-planes: u2's leading part; the rest of u2 samples c.
    const int copy = std::min(copies_ - 1, static_cast<int>(u2 * copies_));
    const double u_c = std::clamp(u2 * copies_ - copy, 0.0, kOneMinus);
    double c = 0.0;
    if (symmetry_ == IesSymmetry::Rotational) {
        c = 2.0 * kPi * u_c;
    } else {
        const auto [j, t2] = rows_[static_cast<std::size_t>(i)].sample(u_c);
        c = c0_ + (j + t2) * (c_span_ / n_c_);
        // The copy by the file's mirror planes (IesPhotometry::intensity_cd folds back).
        switch (symmetry_) {
        case IesSymmetry::Quadrant:
            if (copy == 1) c = kPi - c;
            else if (copy == 2) c = kPi + c;
            else if (copy == 3) c = 2.0 * kPi - c;
            break;
        case IesSymmetry::Bilateral:
            if (copy == 1) c = 2.0 * kPi - c;
            break;
        case IesSymmetry::Bilateral90:
            if (copy == 1) c = kPi - c;  // mirrored about the 90-270 plane
            break;
        default:
            break;
        }
    }
    // The azimuth in float (good to 1e-7, as Embree takes directions), renormalised.
    const auto cf = static_cast<float>(c);
    return glm::normalize(Vec3(sg * static_cast<double>(std::cos(cf)), sg * static_cast<double>(std::sin(cf)), cg));
}

}  // namespace luxtrace
