// Pictures of a result that other tools read: the XDMF companion (ParaView/VisIt). Each
// test runs a tiny scene with the luxtrace binary and judges the files against the
// result's own counts and the physics. (Detector pictures are the Python package's:
// python/tests/test_plot.py.)
#include "luxtrace/io/result_reader.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;
using luxtrace::ResultReader;

namespace {

using Outcome = luxtrace::test_support::CommandOutcome;
Outcome run(const std::string& args) { return luxtrace::test_support::run_luxtrace(args); }

// ------------------------------------------------------------------ a minimal XML reader
// Enough for XDMF: elements, attributes, text, <?..?>, <!..>, comments. Fails on
// unbalanced or unclosed tags.
struct XmlNode {
    std::string tag, text;
    std::map<std::string, std::string> attr;
    std::vector<XmlNode> kids;
    const XmlNode* child(const std::string& tag_name) const {
        for (const XmlNode& k : kids)
            if (k.tag == tag_name) return &k;
        return nullptr;
    }
};

std::string unescape(const std::string& s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] != '&') {
            out += s[i];
            continue;
        }
        const std::size_t semi = s.find(';', i);
        const std::string e = s.substr(i + 1, semi - i - 1);
        out += e == "amp" ? '&' : e == "lt" ? '<' : e == "gt" ? '>' : e == "quot" ? '"' : e == "apos" ? '\'' : '?';
        i = semi;
    }
    return out;
}

std::string trim(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool parse_xml(const std::string& s, XmlNode& root, std::string& err) {
    std::vector<XmlNode*> open{&root};
    std::size_t i = 0;
    while (i < s.size()) {
        const std::size_t lt = s.find('<', i);
        open.back()->text += unescape(s.substr(i, lt == std::string::npos ? std::string::npos : lt - i));
        if (lt == std::string::npos) break;
        if (s.compare(lt, 4, "<!--") == 0) {
            const std::size_t e = s.find("-->", lt);
            if (e == std::string::npos) return err = "unclosed comment", false;
            i = e + 3;
            continue;
        }
        const std::size_t gt = s.find('>', lt);
        if (gt == std::string::npos) return err = "unclosed tag at " + std::to_string(lt), false;
        std::string body = s.substr(lt + 1, gt - lt - 1);
        i = gt + 1;
        if (body.empty()) return err = "empty tag", false;
        if (body[0] == '?' || body[0] == '!') continue;
        if (body[0] == '/') {
            const std::string name = trim(body.substr(1));
            if (open.size() < 2 || open.back()->tag != name)
                return err = "</" + name + "> closes <" + open.back()->tag + ">", false;
            open.pop_back();
            continue;
        }
        const bool self_closing = body.back() == '/';
        if (self_closing) body.pop_back();
        XmlNode n;
        std::size_t p = body.find_first_of(" \t\r\n");
        n.tag = body.substr(0, p);
        while (p != std::string::npos && (p = body.find_first_not_of(" \t\r\n", p)) != std::string::npos) {
            const std::size_t eq = body.find('=', p);
            if (eq == std::string::npos || eq + 1 >= body.size())
                return err = "bad attribute in <" + n.tag + ">", false;
            const char q = body[eq + 1];
            const std::size_t end = body.find(q, eq + 2);
            if ((q != '"' && q != '\'') || end == std::string::npos)
                return err = "unquoted attribute in <" + n.tag + ">", false;
            n.attr[trim(body.substr(p, eq - p))] = unescape(body.substr(eq + 2, end - eq - 2));
            p = end + 1;
        }
        open.back()->kids.push_back(std::move(n));
        // Only the innermost open element gains children, so these pointers stay valid.
        if (!self_closing) open.push_back(&open.back()->kids.back());
    }
    if (open.size() != 1) return err = "<" + open.back()->tag + "> is never closed", false;
    return true;
}

std::vector<std::size_t> numbers(const std::string& s) {
    std::vector<std::size_t> v;
    std::istringstream in(s);
    for (std::size_t x; in >> x;) v.push_back(x);
    return v;
}

// ------------------------------------------------------------------ evaluating DataItems
// What ParaView would read: the values of a DataItem, resolved against the result file.
// Checks on the way that every HDF reference names an existing dataset of the declared
// dimensions and number type, and that hyperslabs stay inside their source.
struct Array {
    std::vector<std::size_t> dims;
    std::vector<double> v;
};

// SPEC §4 types of the datasets the companion may reference.
std::string spec_type(const std::string& path) {
    return path == "/mesh/triangles" || path == "/mesh/material" ? "UInt 4" : "Float 8";
}

Array eval(const XmlNode& item, const ResultReader& r, const std::string& h5name) {
    Array out;
    const std::vector<std::size_t> declared = numbers(item.attr.count("Dimensions") ? item.attr.at("Dimensions") : "");
    const std::string type = item.attr.count("ItemType") ? item.attr.at("ItemType") : "Uniform";
    if (type == "HyperSlab") {
        EXPECT_EQ(item.kids.size(), 2u);
        if (item.kids.size() != 2) return out;
        const Array sel = eval(item.kids[0], r, h5name), src = eval(item.kids[1], r, h5name);
        const std::size_t rank = src.dims.size();
        EXPECT_EQ(sel.v.size(), 3 * rank) << "start, stride, count per dimension";
        if (sel.v.size() != 3 * rank || rank < 1) return out;
        // Rows: start, stride, count, each with one number per dimension of the source.
        std::vector<std::size_t> start(rank), stride(rank), count(rank);
        for (std::size_t k = 0; k < rank; ++k) {
            start[k] = static_cast<std::size_t>(sel.v[k]);
            stride[k] = static_cast<std::size_t>(sel.v[rank + k]);
            count[k] = static_cast<std::size_t>(sel.v[2 * rank + k]);
            EXPECT_GE(count[k], 1u);
            EXPECT_LE(start[k] + stride[k] * (count[k] - 1), src.dims[k] - 1) << "dimension " << k;
            if (count[k] == 0 || start[k] + stride[k] * (count[k] - 1) >= src.dims[k]) return out;
        }
        out.dims = count;
        std::vector<std::size_t> at(rank, 0);  // the selected element, odometer order
        while (true) {
            std::size_t flat = 0;
            for (std::size_t k = 0; k < rank; ++k) flat = flat * src.dims[k] + start[k] + at[k] * stride[k];
            out.v.push_back(src.v[flat]);
            std::size_t k = rank;
            while (k > 0 && ++at[k - 1] == count[k - 1]) at[--k] = 0;
            if (k == 0) break;
        }
    } else if (type == "Function") {
        const std::string f = item.attr.count("Function") ? item.attr.at("Function") : "";
        EXPECT_EQ(f, "$0 - $1") << "the only function the companion needs";
        EXPECT_EQ(item.kids.size(), 2u);
        if (f != "$0 - $1" || item.kids.size() != 2) return out;
        const Array a = eval(item.kids[0], r, h5name), b = eval(item.kids[1], r, h5name);
        EXPECT_EQ(a.v.size(), b.v.size());
        if (a.v.size() != b.v.size()) return out;
        out.dims = a.dims;
        for (std::size_t k = 0; k < a.v.size(); ++k) out.v.push_back(a.v[k] - b.v[k]);
    } else if (item.attr.count("Format") && item.attr.at("Format") == "HDF") {
        const std::string ref = trim(item.text);
        const std::size_t colon = ref.find(":/");
        EXPECT_NE(colon, std::string::npos) << ref;
        if (colon == std::string::npos) return out;
        EXPECT_EQ(ref.substr(0, colon), h5name) << "file reference relative to the XDMF file";
        const std::string path = ref.substr(colon + 1);
        EXPECT_TRUE(r.has(path)) << path << " is not in the result file";
        if (!r.has(path)) return out;
        out.v = r.f64(path, &out.dims);
        const std::string nt = item.attr.count("NumberType") ? item.attr.at("NumberType") : "Float";
        const std::string pr = item.attr.count("Precision") ? item.attr.at("Precision") : "4";
        EXPECT_EQ(nt + " " + pr, spec_type(path)) << path;
    } else {
        EXPECT_EQ(item.attr.count("Format") ? item.attr.at("Format") : "XML", "XML");
        std::istringstream in(item.text);
        for (double x; in >> x;) out.v.push_back(x);
        out.dims = declared;
    }
    EXPECT_EQ(out.dims, declared) << "declared Dimensions of a " << type << " DataItem";
    return out;
}

// ------------------------------------------------------------------ scenes
const char* kRgbRoom = R"(
[scene]
bands = ["R", "G", "B"]
[[material]]
name = "grey"
reflectance = [0.3, 0.5, 0.7]
[[shape]]
type = "box"
center = [0, 0, 1]
size = [2, 2, 2]
inward = true
material = "grey"
subdivisions = 2
[[light]]
type = "point"
position = [0.3, 0.2, 1.5]
flux_lm = 100
colour = [1, 2, 3]
[run]
photons = 30000
seed = 3
)";

// A point light above a floor detector, a black screen shading its two left columns,
// everything black: direct light only.
const char* kDetectorScene = R"(
[[material]]
name = "black"
type = "black"
[[shape]]
type = "rectangle"
center = [0, 0, 0]
normal = [0, 0, 1]
size = [3, 2]
material = "black"
[[shape]]
type = "rectangle"
center = [-0.7, 0, 0.05]
normal = [0, 0, 1]
size = [0.8, 1.2]
material = "black"
[[light]]
type = "point"
position = [0.625, 0.375, 0.5]
flux_lm = 100
[[detector]]
name = "floor"
center = [0, 0, 0]
normal = [0, 0, 1]
up = [0, 1, 0]
size = [2, 1]
cells = [8, 4]
[run]
photons = 200000
seed = 7
)";

class Pictures : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("luxtrace_pictures_" + std::to_string(::getpid()) + "_" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir);
    }
    // Runs `scene_text` and returns the result path.
    fs::path simulate(const std::string& name, const std::string& scene_text) {
        std::ofstream(dir / (name + ".toml")) << scene_text;
        const fs::path out = dir / (name + ".h5");
        const Outcome o = run("run " + (dir / (name + ".toml")).string() + " --threads 2 --quiet --output " +
                              out.string());
        EXPECT_EQ(o.code, 0) << o.out;
        return out;
    }
    fs::path dir;
};

struct Companion {
    XmlNode root;
    std::map<std::string, Array> attributes;  // evaluated cell data by name
    std::size_t triangles = 0;
};

// Reads `xdmf` as ParaView would and checks its structure against the result file.
// `h5ref` is how the companion must name the result (default: its bare file name).
Companion read_companion(const fs::path& xdmf, const fs::path& result, std::string h5ref = "") {
    Companion c;
    std::stringstream ss;
    ss << std::ifstream(xdmf).rdbuf();
    std::string err;
    EXPECT_TRUE(parse_xml(ss.str(), c.root, err)) << xdmf << ": " << err;
    const ResultReader r(result);
    const XmlNode* x = c.root.child("Xdmf");
    const XmlNode* grid = x && x->child("Domain") ? x->child("Domain")->child("Grid") : nullptr;
    EXPECT_NE(grid, nullptr) << "Xdmf/Domain/Grid";
    if (grid == nullptr) return c;
    const std::string h5 = h5ref.empty() ? result.filename().string() : h5ref;
    const XmlNode* topo = grid->child("Topology");
    const XmlNode* geom = grid->child("Geometry");
    EXPECT_TRUE(topo && geom);
    if (!topo || !geom) return c;
    EXPECT_EQ(topo->attr.at("TopologyType"), "Triangle");
    EXPECT_EQ(geom->attr.at("GeometryType"), "XYZ");
    const Array tri = eval(topo->kids.at(0), r, h5), xyz = eval(geom->kids.at(0), r, h5);
    c.triangles = tri.dims.at(0);
    EXPECT_EQ(numbers(topo->attr.at("NumberOfElements")), std::vector<std::size_t>{c.triangles});
    // The geometry the viewer builds has the triangle areas the result states.
    const std::vector<double> area = r.f64("/mesh/area");
    for (std::size_t t = 0; t < c.triangles; ++t) {
        double e[2][3];
        for (int k = 0; k < 2; ++k)
            for (int a = 0; a < 3; ++a)
                e[k][a] = xyz.v[static_cast<std::size_t>(tri.v[3 * t + k + 1]) * 3 + a] -
                          xyz.v[static_cast<std::size_t>(tri.v[3 * t]) * 3 + a];
        const double cx = e[0][1] * e[1][2] - e[0][2] * e[1][1], cy = e[0][2] * e[1][0] - e[0][0] * e[1][2],
                     cz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
        EXPECT_NEAR(0.5 * std::sqrt(cx * cx + cy * cy + cz * cz), area[t], 1e-5 * area[t]) << "triangle " << t;
    }
    for (const XmlNode& a : grid->kids) {
        if (a.tag != "Attribute") continue;
        EXPECT_EQ(a.attr.at("Center"), "Cell") << a.attr.at("Name");
        EXPECT_EQ(a.kids.size(), 1u) << a.attr.at("Name");
        Array v = eval(a.kids.at(0), r, h5);
        EXPECT_EQ(v.v.size(), c.triangles) << a.attr.at("Name") << ": one value per triangle";
        c.attributes[a.attr.at("Name")] = std::move(v);
    }
    return c;
}

}  // namespace

// The companion written by `run` is well-formed XML, every HDF reference names a dataset
// of the declared size, and each attribute evaluates to what SPEC §3 defines from the
// raw counts: E = (n_odd + n_even) E0 / A per band, direct likewise, secondary = the
// difference, odd/even difference = 2 (n_odd - n_even) E0 / A summed over bands.
TEST_F(Pictures, XdmfOfAnRgbRunEvaluatesToTheSpecMaps) {
    const fs::path result = simulate("rgb", kRgbRoom);
    const fs::path xdmf = dir / "rgb.xdmf";
    ASSERT_TRUE(fs::exists(xdmf)) << "luxtrace run writes the XDMF companion beside the result";
    ASSERT_EQ(std::system("command -v xmllint > /dev/null 2>&1"), 0)
        << "xmllint is missing (scripts/install_deps.sh installs libxml2-utils)";
    EXPECT_EQ(std::system(("xmllint --noout " + xdmf.string()).c_str()), 0) << "xmllint rejects " << xdmf;
    const Companion c = read_companion(xdmf, result);
    ASSERT_GT(c.triangles, 0u);
    const ResultReader r(result);
    const double e0 = r.attr_f64("/", "flux_per_photon_lm");
    const std::vector<double> area = r.f64("/mesh/area");
    const auto no = r.u64("/global/count_odd"), ne = r.u64("/global/count_even");
    const auto dO = r.u64("/global/direct_odd"), dE = r.u64("/global/direct_even");
    const std::vector<std::string> bands{"R", "G", "B"};
    const std::vector<std::string> sides{"_front", "_back"};  // format 2: [T, 2, B]
    double secondary_sum = 0.0;
    for (std::size_t side = 0; side < 2; ++side)
        for (std::size_t b = 0; b < bands.size(); ++b) {
            const std::string s = sides[side] + "_" + bands[b] + "_lx";
            for (const std::string name : {"illuminance", "direct", "secondary"})
                ASSERT_TRUE(c.attributes.count(name + s)) << name + s;
            const auto& all = c.attributes.at("illuminance" + s).v;
            const auto& direct = c.attributes.at("direct" + s).v;
            const auto& secondary = c.attributes.at("secondary" + s).v;
            for (std::size_t t = 0; t < c.triangles; ++t) {
                const std::size_t k = (t * 2 + side) * bands.size() + b;
                const double want = static_cast<double>(no[k] + ne[k]) * e0 / area[t];
                const double want_direct = static_cast<double>(dO[k] + dE[k]) * e0 / area[t];
                EXPECT_NEAR(all[t], want, 1e-12 * want) << bands[b] << " triangle " << t;
                EXPECT_NEAR(direct[t], want_direct, 1e-12 * want_direct) << bands[b] << " triangle " << t;
                EXPECT_NEAR(secondary[t], want - want_direct, 1e-9 * want) << bands[b] << " triangle " << t;
                EXPECT_GE(secondary[t], 0.0) << "first hits are a subset of all arrivals";
                secondary_sum += secondary[t];
            }
        }
    EXPECT_GT(secondary_sum, 0.0) << "grey walls reflect: some light arrives after a bounce";
    double s = 0.0, d2 = 0.0;
    for (std::size_t side = 0; side < 2; ++side) {
        ASSERT_TRUE(c.attributes.count("odd_even_difference" + sides[side] + "_lx"));
        ASSERT_TRUE(c.attributes.count("sigma" + sides[side] + "_lx"));
        const auto& oe = c.attributes.at("odd_even_difference" + sides[side] + "_lx").v;
        for (std::size_t t = 0; t < c.triangles; ++t) {
            double d = 0.0, n = 0.0;
            for (std::size_t b = 0; b < bands.size(); ++b) {
                const std::size_t k = (t * 2 + side) * 3 + b;
                d += static_cast<double>(no[k]) - static_cast<double>(ne[k]);
                n += static_cast<double>(no[k] + ne[k]);
            }
            EXPECT_NEAR(oe[t], 2.0 * d * e0 / area[t], 1e-9 * (std::abs(oe[t]) + 1.0)) << "triangle " << t;
            if (n > 0) {  // eq. (5) runs over the lit sides
                s += area[t];
                d2 += area[t] * oe[t] * oe[t];
            }
        }
    }
    // Its area-weighted RMS is the stored D of eq. (5).
    EXPECT_NEAR(std::sqrt(d2 / s), r.attr_f64("/global", "odd_even_rms_lx"), 1e-9 * std::sqrt(d2 / s));
    ASSERT_TRUE(c.attributes.count("material") && c.attributes.count("area_m2"));
    for (std::size_t t = 0; t < c.triangles; ++t) EXPECT_EQ(c.attributes.at("area_m2").v[t], area[t]);
    // No temporary file is left.
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// With black walls no photon arrives after a bounce: the secondary map is exactly zero
// while the direct light is not.
TEST_F(Pictures, XdmfSecondaryIsZeroInABlackRoom) {
    std::string scene = kRgbRoom;
    scene.replace(scene.find("reflectance = [0.3, 0.5, 0.7]"), 29, "type = \"black\"");
    const fs::path result = simulate("black", scene);
    const Companion c = read_companion(dir / "black.xdmf", result);
    double direct = 0.0;
    for (const std::string side : {"_front_", "_back_"})
        for (const std::string b : {"R", "G", "B"}) {
            ASSERT_TRUE(c.attributes.count("secondary" + side + b + "_lx"));
            for (double v : c.attributes.at("secondary" + side + b + "_lx").v) EXPECT_EQ(v, 0.0);
            for (double v : c.attributes.at("direct" + side + b + "_lx").v) direct += v;
        }
    EXPECT_GT(direct, 0.0);
}

// export-xdmf: a bare file name beside the result, an absolute path from elsewhere; a
// file that is not a result is bad input (exit 2) and writes nothing.
TEST_F(Pictures, ExportXdmfNamesTheResultSoTheViewerFindsIt) {
    const fs::path result = simulate("one", kDetectorScene);
    fs::create_directories(dir / "elsewhere");
    const fs::path other = dir / "elsewhere" / "view.xdmf";
    const Outcome o = run("export-xdmf " + result.string() + " -o " + other.string());
    ASSERT_EQ(o.code, 0) << o.out;
    const Companion c = read_companion(other, result, fs::absolute(result).lexically_normal().string());
    EXPECT_TRUE(c.attributes.count("illuminance_front_lx")) << "one band: no band suffix";
    EXPECT_TRUE(c.attributes.count("secondary_back_lx"));
    std::ofstream(dir / "not_a_result.h5") << "plain text";
    const Outcome bad = run("export-xdmf " + (dir / "not_a_result.h5").string());
    EXPECT_EQ(bad.code, 2) << bad.out;
    EXPECT_FALSE(fs::exists(dir / "not_a_result.xdmf"));
}
