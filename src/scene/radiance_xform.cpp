#include "luxtrace/scene/radiance_xform.hpp"

#include "luxtrace/core/error.hpp"
#include "luxtrace/core/math.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

namespace luxtrace::radiance {

namespace {

// A run of options repeated `count` times (-i), or stepped 0..count-1 times over the
// copies (-a).
struct Run {
    bool array = false;
    int count = 1;
    glm::dmat4 matrix{1.0};
};

double number(const std::vector<std::string>& w, std::size_t i, const std::string& where, const std::string& opt) {
    if (i >= w.size()) throw InputError(where + ": xform " + opt + " needs a number after it");
    std::string_view s = w[i];
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
        throw InputError(where + ": xform " + opt + " takes a number, not '" + w[i] + "'");
    return v;
}

int count(const std::vector<std::string>& w, std::size_t i, const std::string& where, const std::string& opt) {
    const double v = number(w, i, where, opt);
    if (v != std::floor(v) || v < 0.0 || v > 1e6)
        throw InputError(where + ": xform " + opt + " takes a whole count from 0 to 1e6, not '" + w[i] + "'");
    return static_cast<int>(v);
}

glm::dmat4 rotation(int axis, double degrees) {
    const double a = degrees * kPi / 180.0, c = std::cos(a), s = std::sin(a);
    glm::dmat4 m(1.0);
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // counter-clockwise looking down the axis
    m[i][i] = c;
    m[j][j] = c;
    m[i][j] = s;  // glm: m[column][row]
    m[j][i] = -s;
    return m;
}

glm::dmat4 power(const glm::dmat4& m, int n) {
    glm::dmat4 r(1.0);
    for (int k = 0; k < n; ++k) r = m * r;
    return r;
}

// The options before the transform: -n, -m, -c, -e, -I (-f refused). Returns the index of
// the first word after them.
std::size_t read_leading_options(const std::vector<std::string>& w, const std::string& where, XformCommand& cmd,
                                 std::vector<std::string>& names) {
    std::size_t i = 0;
    for (; i < w.size(); ++i) {
        const std::string& o = w[i];
        if (o == "-n" || o == "-m") {
            if (i + 1 >= w.size()) throw InputError(where + ": xform " + o + " needs a name after it");
            if (o == "-n") names.push_back(w[++i]);
            else if (cmd.new_modifier.empty()) cmd.new_modifier = w[++i];
            else ++i;
        } else if (o == "-c" || o == "-e") {
        } else if (o == "-I") {
            cmd.invert = !cmd.invert;
        } else if (o == "-f") {
            throw InputError(where + ": xform -f (arguments from a file) is not read; write the copies out");
        } else {
            break;
        }
    }
    return i;
}

// The transform of option w[i] (-t x y z, -rx/-ry/-rz degrees, -s factor, -mx/-my/-mz),
// leaving i on its last argument.
glm::dmat4 option_matrix(const std::vector<std::string>& w, std::size_t& i, const std::string& where) {
    const std::string& o = w[i];
    glm::dmat4 m(1.0);
    if (o == "-t") {
        m[3] = glm::dvec4(number(w, i + 1, where, o), number(w, i + 2, where, o), number(w, i + 3, where, o), 1.0);
        i += 3;
    } else if (o == "-rx" || o == "-ry" || o == "-rz") {
        m = rotation(o[2] - 'x', number(w, ++i, where, o));
    } else if (o == "-s") {
        const double s = number(w, ++i, where, o);
        if (s == 0.0) throw InputError(where + ": xform -s 0 would collapse the objects");
        m = glm::dmat4(s);
        m[3][3] = 1.0;
    } else if (o == "-mx" || o == "-my" || o == "-mz") {
        m[o[2] - 'x'][o[2] - 'x'] = -1.0;
    } else {
        throw InputError(where + ": xform option '" + o +
                         "' is not read (known: -n -m -c -e -I -t -rx -ry -rz -s -mx -my -mz -i -a)");
    }
    return m;
}

// The transform options from w[i] on, in runs: each -i or -a starts a run, which the
// options after it build up. Leaves i on the first file.
std::vector<Run> read_runs(const std::vector<std::string>& w, std::size_t& i, const std::string& where) {
    std::vector<Run> runs(1);
    for (; i < w.size() && w[i].size() > 1 && w[i][0] == '-'; ++i) {
        const std::string& o = w[i];
        if (o == "-i" || o == "-a") {
            Run r;
            r.array = o == "-a";
            r.count = count(w, ++i, where, o);
            if (r.array && r.count == 0) throw InputError(where + ": xform -a 0 makes no copy");
            runs.push_back(r);
            continue;
        }
        const glm::dmat4 m = option_matrix(w, i, where);
        runs.back().matrix = m * runs.back().matrix;
    }
    return runs;
}

// The files from w[i] on; at least one, and no option among them.
void read_files(const std::vector<std::string>& w, std::size_t i, const std::string& where, XformCommand& cmd) {
    for (; i < w.size(); ++i) {
        if (w[i].size() > 1 && w[i][0] == '-')
            throw InputError(where + ": xform option '" + w[i] + "' after the first file");
        cmd.files.push_back(w[i]);
    }
    if (cmd.files.empty())
        throw InputError(where +
                         ": xform names no file (it would read its standard input, which a scene file has not)");
}

// Copy k's matrix is the run applied k times, built once per run and in the order power()
// multiplies: one product per copy, however many -a makes.
std::vector<glm::dmat4> run_steps(const Run& r, int copies) {
    std::vector<glm::dmat4> steps{glm::dmat4(1.0)};
    if (r.array)
        for (int k = 1; k < copies; ++k) steps.push_back(r.matrix * steps.back());
    else steps.front() = power(r.matrix, r.count);
    return steps;
}

// Every combination of the arrays' indices, the first -a varying slowest; unnamed arrays'
// copies are named "a0", "a0.1", ... after `prefix` (the -n names).
std::vector<XformCopy> expand_copies(const std::vector<Run>& runs, const std::string& prefix,
                                     const std::string& where) {
    std::vector<std::pair<glm::dmat4, std::string>> partial{{glm::dmat4(1.0), prefix}};
    for (const Run& r : runs) {
        std::vector<std::pair<glm::dmat4, std::string>> next;
        const int copies = r.array ? r.count : 1;
        if (partial.size() * static_cast<std::size_t>(copies) > 1000000)
            throw InputError(where + ": xform -a makes more than a million copies");
        const std::vector<glm::dmat4> steps = run_steps(r, copies);
        for (const auto& [m, name] : partial)
            for (int k = 0; k < copies; ++k) {
                std::string id = name;
                if (r.array) {
                    id = name.empty() ? std::string("a") : name + ".";
                    id += std::to_string(k);
                }
                next.emplace_back(steps[static_cast<std::size_t>(k)] * m, id);
            }
        partial = std::move(next);
    }
    std::vector<XformCopy> out;
    for (auto& [m, name] : partial) out.push_back({m, name});
    return out;
}

}  // namespace

std::vector<std::string> split_command(const std::string& line, const std::string& where) {
    std::vector<std::string> words;
    std::string word;
    bool in_word = false;
    char quote = 0;
    for (char c : line) {
        if (quote != 0) {
            if (c == quote) quote = 0;
            else word += c;
            continue;
        }
        if (c == '"' || c == '\'') {
            quote = c;
            in_word = true;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            if (in_word) words.push_back(word);
            word.clear();
            in_word = false;
        } else if (std::string_view("|;&<>`$(){}*?[]\\").find(c) != std::string_view::npos) {
            throw InputError(where + ": the command '" + line + "' uses the shell ('" + std::string(1, c) +
                             "'); a scene file never runs a program: expand it with Radiance first");
        } else {
            word += c;
            in_word = true;
        }
    }
    if (quote != 0) throw InputError(where + ": the command '" + line + "' has an unclosed quote");
    if (in_word) words.push_back(word);
    return words;
}

XformCommand parse_xform(const std::vector<std::string>& w, const std::string& where) {
    XformCommand cmd;
    std::vector<std::string> names;
    // The leading options, then the transform, then the files (xform.c's order).
    std::size_t i = read_leading_options(w, where, cmd, names);
    const std::vector<Run> runs = read_runs(w, i, where);
    read_files(w, i, where, cmd);
    std::string prefix;
    for (const std::string& n : names) prefix += (prefix.empty() ? "" : ".") + n;
    cmd.copies = expand_copies(runs, prefix, where);
    return cmd;
}

}  // namespace luxtrace::radiance
