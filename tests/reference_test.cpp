// docs/REFERENCE.md against the program: the scene keys of §2 are exactly the keys the
// loader accepts (scene_schema.cpp), every one of them is accepted by a scene that loads,
// and the command-line block of §1.2 is what `luxtrace reference cli` prints now.
#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/scene/scene_schema.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using Keys = std::map<std::string, std::set<std::string>>;  // table path -> keys

const fs::path kData = LUXTRACE_TEST_DATA_DIR;
const fs::path kReference = kData / ".." / ".." / "docs" / "REFERENCE.md";

std::vector<std::string> lines_of(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

// The first `...` span of a line, or "".
std::string first_code(const std::string& line) {
    const auto a = line.find('`');
    if (a == std::string::npos) return {};
    const auto b = line.find('`', a + 1);
    return b == std::string::npos ? std::string{} : line.substr(a + 1, b - a - 1);
}

// §2's tables: a heading "### `[[light]]`" (or "### `[[light]].grid`", "### Top level")
// names the table; each row "| `key` | ..." below it documents a key.
Keys documented_scene_keys() {
    Keys keys;
    bool in_scene = false;
    std::string path;
    bool have_path = false;
    for (const std::string& line : lines_of(kReference)) {
        if (line.rfind("## ", 0) == 0) in_scene = line.find("Scene file") != std::string::npos;
        if (!in_scene) continue;
        if (line.rfind("### ", 0) == 0) {
            have_path = true;
            if (line == "### Top level") {
                path.clear();
            } else {
                path.clear();
                for (char c : first_code(line))
                    if (c != '[' && c != ']') path += c;
                have_path = !path.empty();
            }
            if (have_path) keys[path];
        } else if (have_path && line.rfind("| `", 0) == 0) {
            keys[path].insert(first_code(line));
        }
    }
    return keys;
}

Keys schema_keys() {
    Keys keys;
    for (const luxtrace::SceneTableSchema& t : luxtrace::scene_schema())
        for (std::string_view k : t.keys) keys[std::string(t.path)].insert(std::string(k));
    return keys;
}

// Every (table, key) a TOML file uses, tables named by their dotted path as in the schema.
void collect(const toml::table& t, const std::string& path, Keys& out) {
    for (const auto& [k, v] : t) {
        const std::string key(k.str());
        out[path].insert(key);
        const std::string sub = path.empty() ? key : path + "." + key;
        if (const toml::table* tt = v.as_table()) collect(*tt, sub, out);
        if (const toml::array* a = v.as_array())
            for (const toml::node& e : *a)
                if (const toml::table* et = e.as_table()) collect(*et, sub, out);
    }
}

std::string show(const std::string& path) { return path.empty() ? "top level" : "[" + path + "]"; }

}  // namespace

TEST(Reference, EveryAcceptedSceneKeyIsDocumentedAndEveryDocumentedKeyIsAccepted) {
    ASSERT_TRUE(fs::is_regular_file(kReference)) << kReference;
    const Keys doc = documented_scene_keys();
    const Keys schema = schema_keys();
    ASSERT_GE(doc.size(), 10u) << "no scene tables found in " << kReference;
    for (const auto& [path, keys] : schema) {
        const auto d = doc.find(path);
        if (d == doc.end()) {
            ADD_FAILURE() << show(path) << " has no table in docs/REFERENCE.md §2 (a heading \"### `[[" << path
                          << "]]`\" or \"### `[" << path << "]`\")";
            continue;
        }
        for (const std::string& k : keys)
            EXPECT_TRUE(d->second.count(k))
                << show(path) << " key '" << k << "' is accepted by the loader but not documented in docs/REFERENCE.md";
    }
    for (const auto& [path, keys] : doc) {
        const auto s = schema.find(path);
        if (s == schema.end()) {
            ADD_FAILURE() << "docs/REFERENCE.md documents a table " << show(path) << " the loader does not read";
            continue;
        }
        for (const std::string& k : keys)
            EXPECT_TRUE(s->second.count(k))
                << show(path) << " key '" << k << "' is documented but not in src/scene/scene_schema.cpp";
    }
}

// The schema could list a key the loader never reads; these scenes use every listed key
// and must load, so each listed key is one a user can really give.
TEST(Reference, ScenesThatUseEverySchemaKeyLoad) {
    Keys used;
    for (const fs::path& f : {kData / "scenes" / "every_key.toml", kData / "reference" / "more_keys.toml",
                              kData / "reference" / "daylight_keys.toml", kData / "reference" / "annual_keys.toml"}) {
        EXPECT_NO_THROW(luxtrace::load_scene(f)) << f;
        collect(toml::parse_file(f.string()), "", used);
    }
    for (const auto& [path, keys] : schema_keys())
        for (const std::string& k : keys)
            EXPECT_TRUE(used[path].count(k))
                << show(path) << " key '" << k << "' is used by no reference scene (tests/data/reference/)";
}

TEST(Reference, UnknownAndMisplacedKeysAreRefusedWithTheirNames) {
    const fs::path dir = fs::temp_directory_path() / ("luxtrace_reference_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string base = "[[material]]\nname = \"m\"\nreflectance = 0.5\n"
                             "[[shape]]\ntype = \"rectangle\"\nsize = [1, 1]\nmaterial = \"m\"\n";
    const std::string lamp = "[[light]]\ntype = \"point\"\nposition = [0, 0, 1]\nflux_lm = 10\n";
    auto message = [&](const std::string& text) -> std::string {
        std::ofstream(dir / "s.toml") << text;
        try {
            luxtrace::load_scene(dir / "s.toml");
        } catch (const luxtrace::InputError& e) {
            return e.what();
        }
        return "(loaded)";
    };
    // Not in the schema: unknown, with the keys the table does take.
    const std::string unknown = message(base + lamp +
                                        "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1, 1]\n"
                                        "diameter = 2\n");
    EXPECT_NE(unknown.find("unknown key 'diameter'"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("half_angle_deg"), std::string::npos) << unknown;
    // In the schema but not for this type: a rectangle has no radius, nor an illuminance
    // detector (only cylindrical and semicylindrical ones have).
    const std::string misplaced = message(base + "radius = 1\n" + lamp);
    EXPECT_NE(misplaced.find("key 'radius' does not apply"), std::string::npos) << misplaced;
    EXPECT_NE(misplaced.find("s.toml:"), std::string::npos) << misplaced;
    const std::string not_cylinder = message(base + lamp +
                                             "[[detector]]\nname = \"d\"\ncenter = [0, 0, 0]\nsize = [1, 1]\n"
                                             "radius = 2\n");
    EXPECT_NE(not_cylinder.find("key 'radius' does not apply"), std::string::npos) << not_cylinder;
    fs::remove_all(dir);
}

TEST(Reference, CommandLineBlockIsWhatTheProgramPrints) {
    const auto o = luxtrace::test_support::run_luxtrace("reference cli");
    ASSERT_EQ(o.code, 0) << o.out;
    std::string block;
    bool inside = false, closed = false;
    for (const std::string& line : lines_of(kReference)) {
        if (line == "<!-- BEGIN luxtrace reference cli -->") {
            inside = true;
        } else if (line == "<!-- END luxtrace reference cli -->") {
            closed = inside;
            inside = false;
        } else if (inside) {
            block += line + "\n";
        }
    }
    ASSERT_TRUE(closed) << "docs/REFERENCE.md has no luxtrace reference cli block";
    EXPECT_EQ(block, o.out) << "docs/REFERENCE.md §1.2 differs from the program's options: run "
                               "scripts/update_reference.sh and review the difference";
    // Every visible subcommand has its table.
    for (const char* sub : {"run", "check", "info", "render", "photometry", "export-xdmf"})
        EXPECT_NE(block.find(std::string("### `luxtrace ") + sub + "`"), std::string::npos) << sub;
    EXPECT_EQ(block.find("luxtrace reference"), std::string::npos) << "the hidden subcommand is not documented";
}
