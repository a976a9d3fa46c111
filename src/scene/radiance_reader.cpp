#include "luxtrace/scene/radiance_reader.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/radiance_shapes.hpp"
#include "luxtrace/scene/radiance_xform.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

// Materials read, with their real-argument counts (Radiance's reference manual) and how
// many string arguments they may have (mirror and illum: an alternate material).
struct MaterialRule {
    std::string_view type;
    std::size_t reals_min, reals_max, strings_max;
};
constexpr MaterialRule kMaterials[] = {
    {"plastic", 5, 5, 0}, {"metal", 5, 5, 0}, {"trans", 7, 7, 0}, {"glass", 3, 4, 0},     {"dielectric", 5, 5, 0},
    {"mirror", 3, 3, 1},  {"light", 3, 3, 0}, {"glow", 4, 4, 0},  {"spotlight", 7, 7, 0}, {"illum", 3, 3, 1},
};
// Anisotropic materials read as their isotropic forms: type, isotropic type, reals.
struct AnisotropicRule {
    std::string_view type, isotropic;
    std::size_t reals;
};
constexpr AnisotropicRule kAnisotropic[] = {{"plastic2", "plastic", 6}, {"metal2", "metal", 6}, {"trans2", "trans", 8}};
// Surfaces and their real-argument counts (polygon: 3 per vertex, at least 3 vertices).
constexpr std::pair<std::string_view, std::size_t> kSurfaces[] = {
    {"polygon", 0}, {"ring", 8}, {"sphere", 4}, {"bubble", 4}, {"cylinder", 7},
    {"tube", 7},    {"cone", 8}, {"cup", 8},    {"source", 4},
};
// Every other type Radiance knows (otypes.h): refused by name.
constexpr std::string_view kRefused[] = {
    "instance",  "mesh",     "interface", "plasfunc",  "metfunc",    "brightfunc", "brighttext",
    "colorpict", "mist",     "transfunc", "BRTDfunc",  "BSDF",       "aBSDF",      "WGMDfunc",
    "plasdata",  "metdata",  "transdata", "colorfunc", "antimatter", "colordata",  "colortext",
    "texdata",   "mixfunc",  "mixdata",   "mixtext",   "mixpict",    "prism1",     "prism2",
    "ashik2",    "spectrum", "specfile",  "specfunc",  "specdata",   "specpict",
};

const MaterialRule* material_rule(std::string_view t) {
    for (const MaterialRule& r : kMaterials)
        if (r.type == t) return &r;
    return nullptr;
}
const AnisotropicRule* anisotropic_rule(std::string_view t) {
    for (const AnisotropicRule& r : kAnisotropic)
        if (r.type == t) return &r;
    return nullptr;
}
const std::size_t* surface_reals(std::string_view t) {
    for (const auto& s : kSurfaces)
        if (s.first == t) return &s.second;
    return nullptr;
}
bool refused(std::string_view t) {
    return std::find(std::begin(kRefused), std::end(kRefused), t) != std::end(kRefused);
}

std::string inverse_type(const std::string& t) {  // xform -I, Radiance's tinvers
    if (t == "sphere") return "bubble";
    if (t == "bubble") return "sphere";
    if (t == "cylinder") return "tube";
    if (t == "tube") return "cylinder";
    if (t == "cone") return "cup";
    if (t == "cup") return "cone";
    return t;
}

// Reals i, i+1, i+2 as a point or vector.
Vec3 point(const std::vector<double>& a, std::size_t i) { return Vec3(a[i], a[i + 1], a[i + 2]); }

// Where a file is read from: the transform of the xforms that included it.
struct Context {
    glm::dmat4 matrix{1.0};    // file -> model units of the top file
    bool invert = false;       // an odd number of xform -I
    std::string prefix;        // xform -n
    std::string new_modifier;  // xform -m (the outermost wins)
    int depth = 0;
};

struct Word {
    std::string text;
    int line = 0;
};

// Radiance's scene syntax over one file's text: words separated by blanks (quotes keep
// blanks inside a word, as fgetword), '#' comments and '!' commands where an object may start.
class Cursor {
public:
    Cursor(std::string text, std::string name) : text_(std::move(text)), name_(std::move(name)) {}

    // Skips blanks; false at the end of the text.
    bool more() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
        return pos_ < text_.size();
    }
    char peek() const { return text_[pos_]; }
    int line() const { return line_; }
    std::string where(int line) const { return name_ + ":" + std::to_string(line); }

    // The rest of the line (a comment or a command), backslash-newline joining lines.
    std::string rest_of_line() {
        std::string s;
        while (pos_ < text_.size() && text_[pos_] != '\n') {
            if (text_[pos_] == '\\' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') {
                pos_ += 2;
                ++line_;
                s += ' ';
                continue;
            }
            s += text_[pos_++];
        }
        if (!s.empty() && s.back() == '\r') s.pop_back();
        return s;
    }

    Word word(const char* what, const std::string& object) {
        if (!more())
            throw InputError(where(last_word_line_) + ": the file ends" +
                             (object.empty() ? "" : " inside '" + object + "'") + " where " + what + " was expected");
        Word w{{}, line_};
        last_word_line_ = line_;
        char quote = 0;
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (quote != 0 && c == quote) {
                quote = 0;
            } else if (quote == 0 && (c == '"' || c == '\'')) {
                quote = c;
            } else {
                if (quote == 0 && std::isspace(static_cast<unsigned char>(c))) break;
                if (c == '\n') ++line_;
                w.text += c;
            }
            ++pos_;
        }
        return w;
    }

    std::size_t count(const char* what, const std::string& object) {
        const Word w = word(what, object);
        std::size_t n = 0;
        const auto [end, ec] = std::from_chars(w.text.data(), w.text.data() + w.text.size(), n);
        if (ec != std::errc() || end != w.text.data() + w.text.size() || n > 100000000)
            throw InputError(where(w.line) + ": '" + object + "': " + what + " must be a whole number, not '" + w.text +
                             "'");
        return n;
    }

    double real(const std::string& object) {
        const Word w = word("a real argument", object);
        std::string_view s = w.text;
        if (!s.empty() && s.front() == '+') s.remove_prefix(1);
        double v = 0.0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
            throw InputError(where(w.line) + ": '" + object + "': real argument '" + w.text + "' is not a number");
        return v;
    }

private:
    std::string text_;
    std::string name_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int last_word_line_ = 1;  // where the file's last word began, for "the file ends" messages
};

class Reader {
public:
    Reader(const RadianceOptions& options, RadianceModel& model) : options_(options), model_(model) {}

    void read_file(const fs::path& path, const Context& ctx, const std::string& included_at) {
        // xform arrays of files that include others multiply: a bound on the work.
        if (++files_read_ > kMaxFileReads)
            throw InputError(included_at + ": more than " + std::to_string(kMaxFileReads) +
                             " files read through xform (arrays of nested includes?)");
        std::ifstream in(path, std::ios::binary);
        std::error_code ec;  // a name the file system cannot look up is a missing file, not a crash
        if (!in || fs::is_directory(path, ec))
            throw InputError(included_at.empty() ? "cannot open Radiance file '" + path.string() + "'"
                                                 : included_at + ": cannot open '" + path.string() + "'");
        std::ostringstream buf;
        buf << in.rdbuf();
        const int file = static_cast<int>(model_.files.size());
        model_.files.push_back(path.string());
        Cursor cur(buf.str(), path.string());
        while (cur.more()) {
            const int line = cur.line();
            if (cur.peek() == '#') {
                cur.rest_of_line();
            } else if (cur.peek() == '!') {
                command(cur.rest_of_line().substr(1), path, ctx, {file, line}, cur.where(line));
            } else {
                object(cur, ctx, file);
            }
        }
    }

private:
    void warn(const RadianceLocation& at, const std::string& what) {
        model_.warnings.push_back(model_.where(at) + ": " + what);
    }

    void command(const std::string& line, const fs::path& path, const Context& ctx, const RadianceLocation& at,
                 const std::string& where) {
        const std::size_t start = line.find_first_not_of(" \t");
        if (start == std::string::npos) throw InputError(where + ": an empty '!' command");
        const std::string first = line.substr(start, line.find_first_of(" \t", start) - start);
        const std::string program = fs::path(first).filename().string();
        if (program == "gensky" || program == "gendaylit") {
            std::vector<std::string> words = radiance::split_command(line, where);
            words.erase(words.begin());
            model_.sky_commands.push_back({program, words, ctx.matrix, at});
            // Its output defines the sky's brightness pattern, which the sky's glow names.
            RadianceModifier sky;
            sky.name = "skyfunc";
            sky.type = "brightfunc";
            sky.sky_command = static_cast<int>(model_.sky_commands.size() - 1);
            sky.at = at;
            define(std::move(sky));
            return;
        }
        if (program != "xform")
            throw InputError(where + ": the command '!" + line +
                             "' would run a program; a scene file never runs one (read are !xform, !gensky and "
                             "!gendaylit): expand it with Radiance first");
        std::vector<std::string> words = radiance::split_command(line, where);
        words.erase(words.begin());
        if (ctx.depth >= 32) throw InputError(where + ": xform nested more than 32 deep (does a file include itself?)");
        const radiance::XformCommand xf = radiance::parse_xform(words, where);
        for (const radiance::XformCopy& copy : xf.copies)
            for (const std::string& f : xf.files) {
                Context inner;
                inner.matrix = ctx.matrix * copy.matrix;
                inner.invert = ctx.invert != xf.invert;
                inner.prefix = ctx.prefix;
                if (!copy.name_prefix.empty())
                    inner.prefix = ctx.prefix.empty() ? copy.name_prefix : ctx.prefix + "." + copy.name_prefix;
                inner.new_modifier = ctx.new_modifier.empty() ? xf.new_modifier : ctx.new_modifier;
                inner.depth = ctx.depth + 1;
                const fs::path p = fs::path(f).is_absolute() ? fs::path(f) : path.parent_path() / f;
                std::error_code ec;
                if (!fs::is_regular_file(p, ec))
                    throw InputError(where + ": xform file '" + f + "' does not exist (looked for '" + p.string() +
                                     "')");
                read_file(p, inner, where);
            }
    }

    void define(RadianceModifier m) {
        by_name_[m.name] = static_cast<int>(model_.modifiers.size());
        model_.modifiers.push_back(std::move(m));
    }

    int lookup(const Word& name, const Cursor& cur, const std::string& object) const {
        const auto it = by_name_.find(name.text);
        if (it == by_name_.end())
            throw InputError(cur.where(name.line) + ": '" + object + "': modifier '" + name.text +
                             "' is not defined before it is used");
        return it->second;
    }

    // The material a surface's modifier stands for, past ignored texfuncs.
    int material_of(int m, const Cursor& cur, int line, const std::string& object) const {
        while (m >= 0 && model_.modifiers[m].type == "texfunc") m = model_.modifiers[m].modifier;
        if (m < 0) return -1;
        const RadianceModifier& r = model_.modifiers[m];
        if (material_rule(r.type) == nullptr)
            throw InputError(cur.where(line) + ": surface '" + object + "': its modifier '" + r.name + "' is a " +
                             r.type + ", not a material");
        return m;
    }

    void object(Cursor& cur, const Context& ctx, int file) {
        const Word mod = cur.word("a modifier", "");
        const Word type = cur.word("a type", mod.text);
        const Word id = cur.word("an identifier", mod.text + " " + type.text);
        const RadianceLocation at{file, mod.line};
        const std::string& name = id.text;
        const bool is_surface = surface_reals(type.text) != nullptr;
        if (!is_surface && (name == "void" || name == "inherit"))
            throw InputError(cur.where(id.line) + ": a modifier cannot be named '" + name + "'");
        int modifier = -1;
        // xform -m replaces a surface's modifier: the one written is then never looked up.
        const bool replaced = is_surface && !ctx.new_modifier.empty();
        if (mod.text != "void" && !(type.text == "alias" && mod.text == "inherit") && !replaced)
            modifier = lookup(mod, cur, name);
        if (type.text == "alias") {  // `mod alias new old`: a copy of old, under mod if not void
            const Word ref = cur.word("the aliased modifier", name);
            RadianceModifier m = model_.modifiers[lookup(ref, cur, name)];
            m.name = name;
            if (modifier >= 0) m.modifier = modifier;
            m.at = at;
            define(std::move(m));
            return;
        }
        std::vector<std::string> strings(cur.count("the number of string arguments", name));
        for (std::string& s : strings) s = cur.word("a string argument", name).text;
        const Word ni = cur.word("the number of integer arguments", name);
        if (ni.text != "0")
            throw InputError(cur.where(ni.line) + ": '" + name + "': " + type.text +
                             " takes no integer arguments (the count must be 0, not '" + ni.text + "')");
        std::vector<double> reals(cur.count("the number of real arguments", name));
        for (double& r : reals) r = cur.real(name);
        auto bad_args = [&](const std::string& what) {
            return InputError(cur.where(mod.line) + ": " + type.text + " '" + name + "': " + what);
        };
        if (is_surface) {
            if (!strings.empty()) throw bad_args("a surface takes no string arguments");
            surface(type.text, name, modifier, std::move(reals), ctx, at, cur);
            return;
        }
        RadianceModifier m{name, type.text, "", modifier, -1, std::move(strings), std::move(reals), at, ctx.matrix};
        if (const MaterialRule* r = material_rule(type.text)) {
            if (m.reals.size() < r->reals_min || m.reals.size() > r->reals_max)
                throw bad_args("takes " + std::to_string(r->reals_min) +
                               (r->reals_max > r->reals_min ? " or " + std::to_string(r->reals_max) : "") +
                               " real arguments, not " + std::to_string(m.reals.size()));
            if (m.strings.size() > r->strings_max) throw bad_args("takes no string arguments");
        } else if (const AnisotropicRule* a = anisotropic_rule(type.text)) {
            if (m.reals.size() != a->reals) throw bad_args("takes " + std::to_string(a->reals) + " real arguments");
            const std::size_t u = a->reals - 2;
            const double roughness = std::sqrt(std::abs(m.reals[u] * m.reals[u + 1]));
            m.reals.resize(u + 1);
            m.reals[u] = roughness;
            m.strings.clear();
            m.read_as = m.type;
            m.type = std::string(a->isotropic);
            warn(at, m.read_as + " '" + name + "' read as " + m.type + " with roughness sqrt(u v) = " +
                         std::to_string(roughness) + " (the anisotropic lobe is not modelled)");
        } else if (type.text == "texfunc") {
            warn(at, "texfunc '" + name + "' ignored: it only perturbs surface normals");
        } else if (type.text == "brightdata") {
            if (m.strings.size() < 3)
                throw bad_args("takes at least 3 string arguments (function, data file, .cal file)");
        } else if (refused(type.text)) {
            throw InputError(cur.where(mod.line) + ": '" + name + "': the primitive '" + type.text +
                             "' is not supported (docs/RADIANCE.md lists what is read)");
        } else {
            throw InputError(cur.where(type.line) + ": '" + name + "': unknown type '" + type.text + "'");
        }
        define(std::move(m));
    }

    // A surface as written, for its errors: "file:line: TYPE 'NAME': what".
    struct Written {
        const std::string& type;
        const std::string& name;
        const RadianceLocation& at;
    };
    InputError bad(const Written& s, const std::string& what) const {
        return InputError(model_.where(s.at) + ": " + s.type + " '" + s.name + "': " + what);
    }

    void surface(const std::string& type_in, const std::string& name_in, int modifier, std::vector<double> a,
                 const Context& ctx, const RadianceLocation& at, const Cursor& cur) {
        const Written written{type_in, name_in, at};
        check_argument_count(written, a);
        std::string name = ctx.prefix.empty() ? name_in : ctx.prefix + "." + name_in;
        if (!ctx.new_modifier.empty()) modifier = lookup({ctx.new_modifier, at.line}, cur, name);
        const int material = material_of(modifier, cur, at.line, name);
        if (material < 0) {
            warn(at, type_in + " '" + name + "' has no material (void): left out");
            return;
        }
        const glm::dmat4 world = to_world(ctx);
        if (type_in == "source") {
            add_source(written, a, std::move(name), material, world);
            return;
        }
        std::string type = type_in;
        if (!tessellate(written, a, name, type)) return;
        if (ctx.invert) type = inverse_type(type);
        add_triangles(written, std::move(name), type, material, ctx, world);
    }

    void check_argument_count(const Written& s, const std::vector<double>& a) const {
        const std::size_t want = *surface_reals(s.type);
        if (s.type == "polygon" ? (a.size() < 9 || a.size() % 3 != 0) : a.size() != want)
            throw bad(s,
                      s.type == "polygon"
                          ? "takes 3 real arguments per vertex and at least 3 vertices, not " + std::to_string(a.size())
                          : "takes " + std::to_string(want) + " real arguments, not " + std::to_string(a.size()));
    }

    // File coordinates -> the model's, in metres.
    glm::dmat4 to_world(const Context& ctx) const {
        return glm::dmat4(glm::dvec4(options_.scale, 0, 0, 0), glm::dvec4(0, options_.scale, 0, 0),
                          glm::dvec4(0, 0, options_.scale, 0), glm::dvec4(0, 0, 0, 1)) *
               ctx.matrix;
    }

    // A distant source: direction and full angle.
    void add_source(const Written& s, const std::vector<double>& a, std::string name, int material,
                    const glm::dmat4& world) {
        const Vec3 d(a[0], a[1], a[2]);
        if (!(glm::length(d) > 0.0)) throw bad(s, "the direction is zero");
        if (!(a[3] > 0.0 && a[3] <= 360.0)) throw bad(s, "the angle must be in (0, 360] degrees");
        const Vec3 dw = glm::normalize(glm::dmat3(world) * d);
        model_.sources.push_back({std::move(name), material, dw, a[3], s.at});
    }

    // The surface as triangles in scratch_, in file coordinates; false if it is left out.
    // Negative radii turn spheres, cylinders and cones inside out: `type` becomes the inverse.
    bool tessellate(const Written& s, const std::vector<double>& a, const std::string& name, std::string& type) {
        scratch_.vertices.clear();
        scratch_.triangles.clear();
        if (type == "polygon") return tessellate_polygon(a, name, s.at);
        if (type == "ring") tessellate_ring(s, a);
        else if (type == "sphere" || type == "bubble") tessellate_sphere(s, a, name, type);
        else tessellate_cone(s, a, name, type);  // cylinder, tube, cone, cup
        return true;
    }

    bool tessellate_polygon(const std::vector<double>& a, const std::string& name, const RadianceLocation& at) {
        std::vector<Vec3> v;
        for (std::size_t i = 0; i < a.size(); i += 3) v.push_back(point(a, i));
        if (v.size() > 3 && v.front() == v.back()) v.pop_back();  // a closed outline, as face.c
        if (!(glm::length(radiance::polygon_area_vector(v)) > 0.0)) {
            warn(at, "polygon '" + name + "' has zero area: left out");
            return false;
        }
        if (!radiance::append_polygon(v, scratch_))
            warn(at, "polygon '" + name + "' crosses itself: triangulated as well as it goes");
        return true;
    }

    void tessellate_ring(const Written& s, const std::vector<double>& a) {
        double r0 = a[6], r1 = a[7];
        if (r0 < 0.0 || r1 < 0.0 || r0 == r1) throw bad(s, "radii must be positive and differ");
        if (!(glm::length(point(a, 3)) > 0.0)) throw bad(s, "the normal is zero");
        radiance::append_ring(point(a, 0), point(a, 3), std::min(r0, r1), std::max(r0, r1), options_.chord_tolerance,
                              scratch_);
    }

    void tessellate_sphere(const Written& s, const std::vector<double>& a, const std::string& name, std::string& type) {
        double r = a[3];
        if (r < 0.0) {  // as Radiance: a negative radius turns it inside out
            warn(s.at, type + " '" + name + "' has a negative radius: turned inside out");
            type = inverse_type(type);
            r = -r;
        }
        if (!(r > 0.0)) throw bad(s, "the radius must not be 0");
        radiance::append_sphere(point(a, 0), r, options_.chord_tolerance, type == "bubble", scratch_);
    }

    void tessellate_cone(const Written& s, const std::vector<double>& a, const std::string& name, std::string& type) {
        const bool cylinder = type == "cylinder" || type == "tube";
        double r0 = a[6], r1 = cylinder ? a[6] : a[7];
        auto sign = [](double r) { return r > 0.0 ? 1 : (r < 0.0 ? -1 : 0); };
        // As Radiance's cone.c: radii of one sign (one may be 0), negative ones turning
        // the surface inside out.
        if (sign(r0) + sign(r1) == 0) throw bad(s, "the radii must not be 0 or of opposite signs");
        if (r0 < 0.0 || r1 < 0.0) {
            warn(s.at, type + " '" + name + "' has negative radii: turned inside out");
            type = inverse_type(type);
            r0 = std::abs(r0);
            r1 = std::abs(r1);
        }
        if (!(glm::length(point(a, 3) - point(a, 0)) > 0.0)) throw bad(s, "its two ends are the same point");
        const bool inward = type == "tube" || type == "cup";
        radiance::append_cone(point(a, 0), point(a, 3), r0, r1, options_.chord_tolerance, inward, scratch_);
    }

    // scratch_'s triangles into the model in model units, as surface `name`.
    void add_triangles(const Written& s, std::string name, const std::string& type, int material, const Context& ctx,
                       const glm::dmat4& world) {
        // A mirroring transform turns the winding; xform -I turns the surface.
        const bool flip = (glm::determinant(glm::dmat3(ctx.matrix)) < 0.0) != ctx.invert;
        if (model_.mesh.vertices.size() + scratch_.vertices.size() > kMaxVertices)
            throw bad(s, "the model would hold more than " + std::to_string(kMaxVertices) + " vertices");
        const auto base = static_cast<std::uint32_t>(model_.mesh.vertices.size());
        for (const Vec3& v : scratch_.vertices) model_.mesh.vertices.push_back(Vec3(world * glm::dvec4(v, 1.0)));
        RadianceSurface r{std::move(name),           type, material, model_.mesh.triangles.size(),
                          scratch_.triangles.size(), s.at};
        for (const glm::uvec3& t : scratch_.triangles)
            model_.mesh.triangles.push_back(flip ? glm::uvec3(base + t.x, base + t.z, base + t.y) : base + t);
        model_.triangle_modifier.insert(model_.triangle_modifier.end(), scratch_.triangles.size(),
                                        static_cast<std::uint32_t>(material));
        model_.surfaces.push_back(std::move(r));
    }

    static constexpr int kMaxFileReads = 100000;
    static constexpr std::size_t kMaxVertices = std::size_t{1} << 30;  // indices are 32-bit

    const RadianceOptions& options_;
    RadianceModel& model_;
    int files_read_ = 0;
    std::unordered_map<std::string, int> by_name_;  // the latest definition of each name
    TriangleMesh scratch_;
};

}  // namespace

std::string RadianceModel::where(const RadianceLocation& at) const {
    const std::string f = at.file >= 0 && static_cast<std::size_t>(at.file) < files.size() ? files[at.file] : "?";
    return f + ":" + std::to_string(at.line);
}

RadianceModel read_radiance(const fs::path& path, const RadianceOptions& options) {
    return read_radiance(std::vector<fs::path>{path}, options);
}

RadianceModel read_radiance(const std::vector<fs::path>& paths, const RadianceOptions& options) {
    const std::string first = paths.empty() ? std::string() : paths.front().string();
    if (paths.empty()) throw InputError("no Radiance file to read");
    if (!(options.scale > 0.0 && std::isfinite(options.scale)))
        throw InputError("Radiance file '" + first + "': scale must be a positive number");
    if (!(options.chord_tolerance >= 1e-6 && options.chord_tolerance <= 0.25))
        throw InputError("Radiance file '" + first + "': chord_tolerance must be in [1e-6, 0.25]");
    RadianceModel model;
    Reader reader(options, model);
    for (const fs::path& p : paths) reader.read_file(p, Context{}, "");
    return model;
}

}  // namespace luxtrace
