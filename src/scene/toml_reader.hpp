#pragma once
// Internal to the scene loader: reads one TOML table with strict key checking and
// error messages of the form "FILE:LINE: CONTEXT: key 'K': WHAT". Each reader knows its
// table's schema (scene_schema.hpp): the keys it may read and the user may give.
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/core/math.hpp"
#include "luxtrace/scene/scene_schema.hpp"

#include <toml++/toml.h>

#include <optional>
#include <set>
#include <string>
#include <vector>

namespace luxtrace::detail {

class TableReader {
public:
    // schema_path: the table's path in scene_schema(), e.g. "light" or "light.grid".
    TableReader(const toml::table& table, std::string file, std::string context, std::string_view schema_path);

    const std::string& context() const { return context_; }
    bool has(const std::string& key) const;
    int line(const std::string& key) const;  // line of the key's value, or of the table
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
    [[noreturn]] void fail_entry(const std::string& what) const;
    // For a key of a table inside this one whose keys the user chooses (e.g. the group names
    // of `dimming`): `key` is its dotted name ("dimming.desk"), `node` its value.
    [[noreturn]] void fail_nested(const std::string& key, const toml::node& node, const std::string& what) const;

    std::optional<std::string> string(const std::string& key);
    std::optional<double> number(const std::string& key);
    std::optional<bool> boolean(const std::string& key);
    std::optional<std::int64_t> integer(const std::string& key);
    // Counts such as photons: an integer, a float like 1e8, or a string like "100M".
    std::optional<std::uint64_t> count(const std::string& key);
    std::optional<Vec3> vec3(const std::string& key);
    std::optional<std::vector<double>> numbers(const std::string& key, std::size_t n);
    std::optional<std::vector<std::string>> strings(const std::string& key);
    // A scalar or one value per band, each in [0, 1].
    std::optional<std::vector<double>> per_band(const std::string& key, std::size_t bands);
    const toml::table* table(const std::string& key);
    const toml::array* array(const std::string& key);

    // Every key of the table must have been read: a key the schema does not list is an
    // unknown key, a listed one that was not read does not apply to this entry.
    void finish() const;

private:
    // "FILE:LINE: CONTEXT" for messages about the whole entry.
    std::string where() const;
    const toml::node* get(const std::string& key);
    void check_schema(const std::string& key) const;  // std::logic_error: the loader reads an unlisted key
    const toml::table& table_;
    const SceneTableSchema& schema_;
    std::string file_;
    std::string context_;
    std::set<std::string> used_;
};

}  // namespace luxtrace::detail
