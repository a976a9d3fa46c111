// ies2rad's luminaires read back as photometry; see radiance_luminaire.hpp.
#include "luxtrace/scene/radiance_luminaire.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "luxtrace/scene/radiance_xform.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

constexpr double kDeg = kPi / 180.0;

// source.cal's corrections, as ies2rad picks them: corr for a sphere, flatcorr for flat
// emitters, boxcorr and cylcorr for boxes and cylinders with luminous sides.
enum class Correction { none, flat, box, cylinder };

// The azimuth functions ies2rad writes, by the horizontal angles the .dat then holds.
struct AzimuthRule {
    std::string_view name;
    double last_deg;  // the table's horizontal angles run 0..last
};
constexpr AzimuthRule kAzimuths[] = {{"src_phi", 360.0}, {"src_phi2", 180.0}, {"src_phi4", 90.0}};

bool is_emitter(const std::string& type) {
    return type == "light" || type == "illum" || type == "spotlight" || type == "glow";
}

// A parsed ies2rad brightdata: `func data.dat source.cal coord... [transform]`, reals.
struct Pattern {
    Correction correction = Correction::none;
    std::string data;                 // as written
    std::vector<std::string> coords;  // one per .dat dimension
    std::string azimuth;              // src_phi, src_phi2, src_phi4, or "" (one dimension)
    bool theta_first = false;         // the .dat's outer dimension is gamma (old hand-made files)
    glm::dmat4 transform{1.0};        // pattern -> top file's model units
    double a1 = 1.0;                  // the multiplier (source.cal's A1)
    double dim[3] = {0.0, 0.0, 0.0};  // boxcorr: x, y, z sizes; cylcorr: diameter, height (metres)
};

Pattern parse_pattern(const RadianceModel& model, const RadianceModifier& m) {
    const std::string at = model.where(m.at) + ": brightdata '" + m.name + "': ";
    if (m.type != "brightdata") throw InputError(at + "is a " + m.type + ", not a brightdata");
    const auto& s = m.strings;
    if (s.size() < 4) throw InputError(at + "needs a function, a data file, a .cal file and coordinates");
    Pattern p;
    if (s[0] == "corr") p.correction = Correction::none;
    else if (s[0] == "flatcorr") p.correction = Correction::flat;
    else if (s[0] == "boxcorr") p.correction = Correction::box;
    else if (s[0] == "cylcorr") p.correction = Correction::cylinder;
    else
        throw InputError(at + "function '" + s[0] +
                         "' is not one of ies2rad's (corr, flatcorr, boxcorr, cylcorr over source.cal)");
    if (fs::path(s[2]).filename() != "source.cal")
        throw InputError(at + "function file '" + s[2] + "' is not source.cal, the one ies2rad's luminaires use");
    p.data = s[1];
    std::size_t i = 3;
    // Coordinates up to the first transform option ("-t", "-rz", ...).
    for (; i < s.size() && !(s[i].size() > 1 && s[i][0] == '-' && std::isalpha(static_cast<unsigned char>(s[i][1])));
         ++i)
        p.coords.push_back(s[i]);
    if (i < s.size()) {
        std::vector<std::string> words(s.begin() + static_cast<std::ptrdiff_t>(i), s.end());
        words.push_back("pattern");  // parse_xform wants a file; a pattern's transform names none
        const radiance::XformCommand xf = radiance::parse_xform(words, model.where(m.at));
        if (xf.copies.size() != 1) throw InputError(at + "a pattern's transform cannot make copies (-a)");
        p.transform = xf.copies.front().matrix;
    }
    p.transform = m.transform * p.transform;
    if (p.coords.empty() || p.coords.size() > 2) throw InputError(at + "expects one or two coordinates");
    const auto theta = std::find(p.coords.begin(), p.coords.end(), "src_theta");
    const std::string azimuth = p.coords.size() == 2 ? p.coords[theta == p.coords.begin() ? 1 : 0] : "";
    if (theta == p.coords.end() || (p.coords.size() == 2 && azimuth == "src_theta")) {
        const bool type_b = std::any_of(p.coords.begin(), p.coords.end(),
                                        [](const std::string& c) { return c.starts_with("srcB_"); });
        throw InputError(at + (type_b ? "type B photometry (srcB_horiz, srcB_vert) is not read back: name the "
                                        "luminaire's IES file instead"
                                      : "coordinates '" + p.coords.front() +
                                            (p.coords.size() > 1 ? " " + p.coords.back() : "") +
                                            "' are not ies2rad's (src_theta with src_phi, src_phi2 or src_phi4)"));
    }
    p.theta_first = theta == p.coords.begin();
    p.azimuth = azimuth;
    if (p.coords.size() == 2) {
        const bool known = std::any_of(std::begin(kAzimuths), std::end(kAzimuths),
                                       [&](const AzimuthRule& r) { return r.name == p.azimuth; });
        if (!known)
            throw InputError(at + "azimuth '" + p.azimuth + "' is not read back" +
                             (p.azimuth == "src_phi2+90" ? " (an LM-63-1995 table of the 90-270 planes)" : "") +
                             ": name the luminaire's IES file instead");
    }
    const auto& r = m.reals;
    if (!r.empty()) p.a1 = r[0];
    if (p.correction == Correction::box || p.correction == Correction::cylinder) {
        const std::size_t need = p.correction == Correction::box ? 4 : 3;
        if (r.size() < need)
            throw InputError(at + s[0] + " takes " + std::to_string(need) + " real arguments (multiplier and " +
                             (need == 4 ? "the box's x, y, z sizes" : "the cylinder's diameter and height") +
                             " in metres), not " + std::to_string(r.size()));
        for (std::size_t k = 1; k < need; ++k) {
            if (!(r[k] > 0.0)) throw InputError(at + "the emitter's sizes must be positive");
            p.dim[k - 1] = r[k];
        }
    }
    if (!(p.a1 >= 0.0)) throw InputError(at + "the multiplier must not be negative");
    return p;
}

// A Radiance data file: `n`, per dimension `first last count` (first == last: `count`
// angles follow), then the values, the last dimension varying fastest. '#' starts a comment.
struct DataTable {
    std::vector<std::vector<double>> axes;
    std::vector<int> axis_lines;  // where each dimension's angles end
    std::vector<double> values;
};

std::string read_whole_file(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError("cannot open '" + file.string() + "'");
    std::ostringstream buf;
    buf << in.rdbuf();
    return buf.str();
}

// A data file's words with their lines: blanks and commas separate them.
struct DataToken {
    std::string_view text;
    int line;
};

std::vector<DataToken> data_tokens(std::string_view text) {
    std::vector<DataToken> tokens;
    int line = 1;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
            continue;
        }
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != ',') ++i;
        tokens.push_back({text.substr(start, i - start), line});
    }
    return tokens;
}

// Hands out a data file's numbers; every error names the file and line.
class DataReader {
public:
    DataReader(std::string name, std::vector<DataToken> tokens) : name_(std::move(name)), tokens_(std::move(tokens)) {}

    [[noreturn]] void fail(int line, const std::string& what) const {
        throw InputError(name_ + ":" + std::to_string(line) + ": " + what);
    }
    bool done() const { return next_ >= tokens_.size(); }
    int line() const { return tokens_[next_].line; }           // the next word's
    int prev_line() const { return tokens_[next_ - 1].line; }  // the last word read's
    std::string prev_text() const { return std::string(tokens_[next_ - 1].text); }

    // The next word as a number, with its line.
    std::pair<double, int> number(const std::string& what) {
        if (done()) fail(tokens_.empty() ? 1 : tokens_.back().line, "the file ends where " + what + " was expected");
        const DataToken t = tokens_[next_++];
        std::string_view s = t.text;
        if (!s.empty() && s.front() == '+') s.remove_prefix(1);
        double v = 0.0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
            fail(t.line, what + " '" + std::string(t.text) + "' is not a number");
        return std::pair{v, t.line};
    }

    // The next word as a whole number in [lo, hi].
    int count(const std::string& what, int lo, int hi) {
        const auto [v, l] = number(what);
        if (v != std::floor(v) || v < lo || v > hi)
            fail(l, what + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], not " +
                        prev_text());
        return static_cast<int>(v);
    }

private:
    std::string name_;
    std::vector<DataToken> tokens_;
    std::size_t next_ = 0;
};

// Dimension k + 1: `first last count`, the angles listed when first == last, spaced evenly
// otherwise; they must run one way.
void read_axis(DataReader& rd, int k, DataTable& d) {
    const std::string dim = "dimension " + std::to_string(k + 1);
    const double first = rd.number(dim + "'s first angle").first;
    const double last = rd.number(dim + "'s last angle").first;
    const int ne = rd.count(dim + "'s number of angles", 2, 100000);
    std::vector<double> a(static_cast<std::size_t>(ne));
    if (first == last) {
        for (double& x : a) x = rd.number(dim + "'s angle").first;
    } else {
        for (int j = 0; j < ne; ++j) a[j] = first + (last - first) * j / (ne - 1);
    }
    const int at = rd.prev_line();
    bool up = true, down = true;
    for (std::size_t j = 1; j < a.size(); ++j) {
        up = up && a[j] > a[j - 1];
        down = down && a[j] < a[j - 1];
    }
    if (!up && !down) rd.fail(at, dim + "'s angles must increase or decrease");
    d.axes.push_back(std::move(a));
    d.axis_lines.push_back(at);
}

// `total` values, none negative, and nothing after them.
void read_values(DataReader& rd, std::size_t total, DataTable& d) {
    d.values.reserve(total);
    for (std::size_t k = 0; k < total; ++k) {
        const auto [v, l] = rd.number("value " + std::to_string(k + 1) + " of " + std::to_string(total));
        if (v < 0.0) rd.fail(l, "negative value " + rd.prev_text());
        d.values.push_back(v);
    }
    if (!rd.done()) rd.fail(rd.line(), "more values than the " + std::to_string(total) + " its dimensions hold");
}

DataTable read_data(const fs::path& file) {
    const std::string text = read_whole_file(file);
    DataReader rd(file.string(), data_tokens(text));
    DataTable d;
    const int n = rd.count("the number of dimensions", 1, 2);
    std::size_t total = 1;
    for (int k = 0; k < n; ++k) {
        read_axis(rd, k, d);
        total *= d.axes.back().size();
    }
    read_values(rd, total, d);
    return d;
}

// An emitting triangle in scene coordinates: area (m^2) and unit normal (its front side).
struct Facet {
    double area_m2;
    Vec3 normal;
};

struct Emitters {
    std::vector<std::size_t> surfaces;
    std::vector<Facet> facets;
    std::vector<Vec3> vertices;
    double luminance_weight = 0.0;  // Y of the emitting material's colour (one per luminaire)
    bool any_ring = false;
};

// The surfaces lit by brightdata `b`: those of light, illum or spotlight materials it
// modifies; glow ones only when there are none (ies2rad's -g impostors are glow inside an illum).
Emitters emitters_of(const RadianceModel& model, std::size_t b) {
    Emitters e;
    const auto feeds = [&](int m) { return m >= 0 && model.modifiers[m].modifier == static_cast<int>(b); };
    for (const bool glow : {false, true}) {
        for (std::size_t s = 0; s < model.surfaces.size(); ++s) {
            const RadianceSurface& sf = model.surfaces[s];
            if (!feeds(sf.modifier)) continue;
            const RadianceModifier& mat = model.modifiers[sf.modifier];
            if (!is_emitter(mat.type) || (mat.type == "glow") != glow) continue;
            const double y = kRadianceLuminanceWeights[0] * mat.reals[0] + kRadianceLuminanceWeights[1] * mat.reals[1] +
                             kRadianceLuminanceWeights[2] * mat.reals[2];
            if (!e.surfaces.empty() && std::abs(y - e.luminance_weight) > 1e-9 * std::abs(y))
                throw InputError(model.where(sf.at) + ": surface '" + sf.name + "' of luminaire '" +
                                 model.modifiers[b].name +
                                 "' has a light colour of another luminance than the luminaire's other surfaces");
            e.luminance_weight = y;
            e.surfaces.push_back(s);
            e.any_ring = e.any_ring || sf.type == "ring";
            for (std::size_t t = sf.first_triangle; t < sf.first_triangle + sf.triangle_count; ++t) {
                const glm::uvec3 k = model.mesh.triangles[t];
                const Vec3 &p0 = model.mesh.vertices[k.x], &p1 = model.mesh.vertices[k.y],
                           &p2 = model.mesh.vertices[k.z];
                const Vec3 c = glm::cross(p1 - p0, p2 - p0);
                const double len = glm::length(c);
                if (len > 0.0) e.facets.push_back({0.5 * len, c / len});
                e.vertices.insert(e.vertices.end(), {p0, p1, p2});
            }
        }
        if (!e.surfaces.empty()) break;
    }
    if (e.surfaces.empty())
        throw InputError(model.where(model.modifiers[b].at) + ": brightdata '" + model.modifiers[b].name +
                         "' lights no surface (no light, illum, spotlight or glow it modifies is used)");
    return e;
}

struct Placement {
    Frame frame;    // t = C0, b = t x n, n = nadir
    Vec3 x, y, z;   // the pattern's own axes in the scene (unit)
    bool mirrored;  // the pattern's transform mirrors: its C90 is -b
    Vec3 centre;
    Vec3 extent;  // the emitters' sizes along x, y, z (m)
};

Placement place(const Pattern& p, const Emitters& e) {
    const glm::dmat3 m(p.transform);
    Placement pl;
    pl.x = glm::normalize(m * Vec3(1, 0, 0));
    pl.y = glm::normalize(m * Vec3(0, 1, 0));
    pl.z = glm::normalize(m * Vec3(0, 0, 1));
    pl.mirrored = glm::determinant(m) < 0.0;
    pl.frame.n = -pl.z;
    pl.frame.t = pl.x;
    pl.frame.b = glm::cross(pl.frame.t, pl.frame.n);
    Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const Vec3& v : e.vertices) {
        const Vec3 l(glm::dot(v, pl.x), glm::dot(v, pl.y), glm::dot(v, pl.z));
        lo = glm::min(lo, l);
        hi = glm::max(hi, l);
    }
    const Vec3 c = 0.5 * (lo + hi);
    pl.centre = c.x * pl.x + c.y * pl.y + c.z * pl.z;
    pl.extent = hi - lo;
    return pl;
}

// The geometry factor G toward scene direction d (pattern direction dp): see the header.
double geometry(const Pattern& p, const Emitters& e, const Vec3& d, const Vec3& dp) {
    double front = 0.0, projected = 0.0;
    for (const Facet& f : e.facets) {
        const double c = glm::dot(f.normal, d);
        if (c > 0.0) {
            front += f.area_m2;
            projected += f.area_m2 * c;
        }
    }
    switch (p.correction) {
    case Correction::none: return projected;
    case Correction::flat: return front;
    case Correction::box:
        return projected / (std::abs(dp.x) * p.dim[1] * p.dim[2] + std::abs(dp.y) * p.dim[0] * p.dim[2] +
                            std::abs(dp.z) * p.dim[0] * p.dim[1]);
    case Correction::cylinder: {
        const double dz = std::min(std::abs(dp.z), 1.0);
        return projected / (p.dim[0] * p.dim[1] * std::sqrt(1.0 - dz * dz) + 0.25 * kPi * p.dim[0] * p.dim[0] * dz);
    }
    }
    return 0.0;
}

// G at a table direction; where an emitter is seen edge-on (the 90 degree row of a flat
// source, where flatcorr divides by zero) the limits from the table's sides are averaged.
double geometry_at(const Pattern& p, const Emitters& e, const Placement& pl, double c_deg, double g_deg, bool below,
                   bool above) {
    auto direction = [&](double g) {
        const Vec3 dp(std::sin(g * kDeg) * std::cos(c_deg * kDeg), std::sin(g * kDeg) * std::sin(c_deg * kDeg),
                      -std::cos(g * kDeg));
        return std::pair{dp.x * pl.x + dp.y * pl.y + dp.z * pl.z, dp};
    };
    // Not a structured binding: clang 14 (the fuzz build's) cannot capture one in a lambda.
    const auto at = direction(g_deg);
    const Vec3 d = at.first, dp = at.second;
    const bool edge_on = std::any_of(e.facets.begin(), e.facets.end(),
                                     [&](const Facet& f) { return std::abs(glm::dot(f.normal, d)) < 1e-9; });
    if (!edge_on) return geometry(p, e, d, dp);
    constexpr double kNudge_deg = 1e-4;
    double sum = 0.0;
    int n = 0;
    for (const double g : {g_deg - kNudge_deg, g_deg + kNudge_deg}) {
        if ((g < g_deg && !below) || (g > g_deg && !above)) continue;
        const auto [dn, dpn] = direction(g);
        sum += geometry(p, e, dn, dpn);
        ++n;
    }
    return n > 0 ? sum / n : geometry(p, e, d, dp);
}

fs::path find_data(const RadianceModel& model, const RadianceModifier& m, const std::string& data,
                   const RadianceLuminaireOptions& options) {
    const std::string defined_in = m.at.file >= 0 && static_cast<std::size_t>(m.at.file) < model.files.size()
                                       ? model.files[m.at.file]
                                       : "";
    std::vector<fs::path> dirs{fs::path(defined_in).parent_path()};
    dirs.insert(dirs.end(), options.search_path.begin(), options.search_path.end());
    std::string looked;
    for (const fs::path& dir : dirs) {
        const fs::path f = fs::path(data).is_absolute() ? fs::path(data) : dir / data;
        std::error_code ec;
        if (fs::is_regular_file(f, ec)) return f;
        looked += (looked.empty() ? "" : ", ") + ("'" + f.string() + "'");
    }
    throw InputError(model.where(m.at) + ": brightdata '" + m.name + "': data file '" + data +
                     "' not found (looked for " + looked + ")");
}

LuminousOpening opening_of(const Pattern& p, const Emitters& e, const Placement& pl) {
    using S = LuminousOpening::Shape;
    LuminousOpening o;
    switch (p.correction) {
    case Correction::box: o = {S::box, p.dim[0], p.dim[1], p.dim[2]}; break;
    case Correction::cylinder: o = {S::vertical_cylinder, p.dim[0], p.dim[0], p.dim[1]}; break;
    case Correction::none: o = {S::ellipsoid, pl.extent.x, pl.extent.y, pl.extent.z}; break;
    case Correction::flat: o = {e.any_ring ? S::ellipse : S::rectangle, pl.extent.x, pl.extent.y, 0.0}; break;
    }
    return o;
}

// What both readings share: the pattern, its surfaces and where they put the luminaire.
struct Started {
    Pattern pattern;
    Emitters emitters;
    Placement placement;
    RadianceLuminaire luminaire;  // name, position, frame and surfaces filled in
};

Started start(const RadianceModel& model, std::size_t brightdata) {
    if (brightdata >= model.modifiers.size()) throw std::out_of_range("radiance_luminaire: no such modifier");
    const RadianceModifier& m = model.modifiers[brightdata];
    Started s{parse_pattern(model, m), emitters_of(model, brightdata), {}, {}};
    s.placement = place(s.pattern, s.emitters);
    s.luminaire.name = m.name;
    s.luminaire.position_m = s.placement.centre;
    s.luminaire.frame = s.placement.frame;
    s.luminaire.surfaces = s.emitters.surfaces;
    return s;
}

}  // namespace

std::vector<std::size_t> radiance_luminaire_modifiers(const RadianceModel& model) {
    std::vector<bool> used(model.modifiers.size(), false);
    for (const RadianceSurface& s : model.surfaces) {
        if (s.modifier < 0) continue;
        const RadianceModifier& mat = model.modifiers[s.modifier];
        if (is_emitter(mat.type) && mat.modifier >= 0 && model.modifiers[mat.modifier].type == "brightdata")
            used[mat.modifier] = true;
    }
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < used.size(); ++i)
        if (used[i]) out.push_back(i);
    return out;
}

RadianceLuminaire radiance_luminaire(const RadianceModel& model, std::size_t brightdata,
                                     const RadianceLuminaireOptions& options) {
    Started s = start(model, brightdata);
    const RadianceModifier& m = model.modifiers[brightdata];
    const Pattern& p = s.pattern;
    const Emitters& e = s.emitters;
    const Placement& pl = s.placement;
    const fs::path file = find_data(model, m, p.data, options);
    DataTable d = read_data(file);
    const std::string where = model.where(m.at) + ": brightdata '" + m.name + "': ";
    if (d.axes.size() != p.coords.size())
        throw InputError(where + "'" + file.string() + "' has " + std::to_string(d.axes.size()) +
                         " dimensions for the " + std::to_string(p.coords.size()) + " coordinates named");

    RadianceLuminaire& out = s.luminaire;
    out.data_file = file.string();
    Photometry& ph = out.photometry;
    ph.format = "Radiance ies2rad data";
    ph.type = PhotometricType::C;
    ph.luminaire = m.name;
    // The .dat's last dimension varies fastest; gamma is src_theta's, C the other's.
    const std::size_t gi = p.theta_first ? 0 : d.axes.size() - 1;
    std::vector<double> gamma = d.axes[gi];
    std::vector<double> c_deg = d.axes.size() == 2 ? d.axes[1 - gi] : std::vector<double>{0.0};
    const std::size_t nv = gamma.size(), nh = c_deg.size();
    auto value = [&](std::size_t h, std::size_t v) {
        return p.theta_first ? d.values[v * nh + h] : d.values[h * nv + v];
    };
    // Angles as photometry wants them: increasing.
    const bool flip_v = gamma.front() > gamma.back(), flip_h = c_deg.front() > c_deg.back();
    if (flip_v) std::reverse(gamma.begin(), gamma.end());
    if (flip_h) std::reverse(c_deg.begin(), c_deg.end());
    if (gamma.front() < -1e-6 || gamma.back() > 180.0 + 1e-6)
        throw InputError(file.string() + ":" + std::to_string(d.axis_lines[gi]) + ": src_theta's angles run " +
                         std::to_string(gamma.front()) + " to " + std::to_string(gamma.back()) +
                         "; they must lie in [0, 180]");
    if (nh > 1) {
        const double last = std::find_if(std::begin(kAzimuths), std::end(kAzimuths), [&](const AzimuthRule& r) {
                                return r.name == p.azimuth;
                            })->last_deg;
        if (std::abs(c_deg.front()) > 1e-6 || std::abs(c_deg.back() - last) > 1e-6)
            throw InputError(file.string() + ":" + std::to_string(d.axis_lines[1 - gi]) + ": " + p.azimuth +
                             " reads horizontal angles 0 to " + std::to_string(static_cast<int>(last)) +
                             ", the file's run " + std::to_string(c_deg.front()) + " to " +
                             std::to_string(c_deg.back()));
    }
    const double k = kRadianceEfficacy_lm_per_W * e.luminance_weight * p.a1;
    const bool rows_below = (gamma.front() < 90.0 - 1e-9), rows_above = (gamma.back() > 90.0 + 1e-9);
    ph.vertical_deg = gamma;
    ph.horizontal_deg = c_deg;
    ph.candela_cd.assign(nh, std::vector<double>(nv, 0.0));
    for (std::size_t h = 0; h < nh; ++h)
        for (std::size_t v = 0; v < nv; ++v) {
            const double dat = value(flip_h ? nh - 1 - h : h, flip_v ? nv - 1 - v : v);
            const double g = geometry_at(p, e, pl, c_deg[h], gamma[v], rows_below, rows_above);
            ph.candela_cd[h][v] = k * dat * g;
        }
    // A mirroring transform turns C counter-clockwise about the pattern's nadir into
    // clockwise about the scene's: the table is mirrored about its 0-180 plane.
    if (pl.mirrored && nh > 1 && c_deg.back() > 180.0 + 1e-6) {
        std::reverse(ph.candela_cd.begin(), ph.candela_cd.end());
        std::vector<double> h(nh);
        for (std::size_t j = 0; j < nh; ++j) h[j] = 360.0 - c_deg[nh - 1 - j];
        ph.horizontal_deg = std::move(h);
        out.notes.push_back(model.where(m.at) + ": luminaire '" + m.name +
                            "' is mirrored by its transform: its C-planes are mirrored about C0-C180");
    }
    ph.opening = opening_of(p, e, pl);
    if (const int tilt = m.modifier; tilt >= 0)
        out.notes.push_back(model.where(m.at) + ": luminaire '" + m.name + "': the lamp tilt pattern '" +
                            model.modifiers[tilt].name + "' is not applied (name the IES file to use its TILT table)");
    const double flux = ph.flux_lm();
    if (!(flux > 0.0 && std::isfinite(flux)))
        throw InputError(where + "emits no light (all values of '" + file.string() + "' or its multiplier are 0)");
    return out;
}

RadianceLuminaire radiance_luminaire_named(const RadianceModel& model, std::size_t brightdata,
                                           const Photometry& photometry) {
    Started s = start(model, brightdata);
    const RadianceModifier& m = model.modifiers[brightdata];
    RadianceLuminaire& out = s.luminaire;
    out.photometry = photometry;
    if (s.placement.mirrored)
        out.notes.push_back(model.where(m.at) + ": luminaire '" + m.name +
                            "' is mirrored by its transform; the named photometry is placed unmirrored");
    return out;
}

}  // namespace luxtrace
