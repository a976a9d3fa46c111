#include "toml_reader.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace luxtrace::detail {
using luxtrace::parse_count;

TableReader::TableReader(const toml::table& table, std::string file, std::string context, std::string_view schema_path)
    : table_(table), schema_(scene_table_schema(schema_path)), file_(std::move(file)), context_(std::move(context)) {}

void TableReader::check_schema(const std::string& key) const {
    // A key the loader reads must be listed, or the reference would not document it.
    if (!schema_.accepts(key))
        throw std::logic_error("scene_schema.cpp: table '" + std::string(schema_.path) + "' does not list key '" + key +
                               "' that the loader reads");
}

bool TableReader::has(const std::string& key) const {
    check_schema(key);
    return table_.contains(key);
}

int TableReader::line(const std::string& key) const {
    if (const toml::node* n = table_.get(key)) return static_cast<int>(n->source().begin.line);
    return static_cast<int>(table_.source().begin.line);
}

std::string TableReader::where() const {
    return file_ + ":" + std::to_string(table_.source().begin.line) + ": " + context_;
}

void TableReader::fail(const std::string& key, const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(line(key)) + ": " + context_ + ": key '" + key + "': " + what);
}

void TableReader::fail_entry(const std::string& what) const { throw InputError(where() + ": " + what); }

void TableReader::fail_nested(const std::string& key, const toml::node& node, const std::string& what) const {
    throw InputError(file_ + ":" + std::to_string(node.source().begin.line) + ": " + context_ + ": key '" + key +
                     "': " + what);
}

const toml::node* TableReader::get(const std::string& key) {
    check_schema(key);
    const toml::node* n = table_.get(key);
    if (n != nullptr) used_.insert(key);
    return n;
}

std::optional<std::string> TableReader::string(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) fail(key, "expected a string");
    return std::string(n->as_string()->get());
}

std::optional<double> TableReader::number(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    const std::optional<double> v = n->value<double>();
    if (!v || !std::isfinite(*v)) fail(key, "expected a finite number");
    return v;
}

std::optional<bool> TableReader::boolean(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_boolean()) fail(key, "expected true or false");
    return n->as_boolean()->get();
}

std::optional<std::int64_t> TableReader::integer(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_integer()) fail(key, "expected an integer");
    return n->as_integer()->get();
}

std::optional<std::uint64_t> TableReader::count(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    std::optional<std::uint64_t> v;
    if (n->is_integer()) {
        if (n->as_integer()->get() >= 0) v = static_cast<std::uint64_t>(n->as_integer()->get());
    } else if (n->is_floating_point()) {
        const double d = n->as_floating_point()->get();
        if (d >= 0.0 && d < 1.8e19 && d == std::floor(d)) v = static_cast<std::uint64_t>(d);
    } else if (n->is_string()) {
        v = parse_count(std::string(n->as_string()->get()));
    }
    if (!v) fail(key, "expected a non-negative whole count such as 1000000, 1e6 or \"1M\"");
    return v;
}

std::optional<std::vector<double>> TableReader::numbers(const std::string& key, std::size_t n) {
    const toml::node* node = get(key);
    if (node == nullptr) return std::nullopt;
    const toml::array* a = node->as_array();
    if (a == nullptr || a->size() != n) fail(key, "expected an array of " + std::to_string(n) + " numbers");
    std::vector<double> out;
    for (const toml::node& e : *a) {
        const std::optional<double> v = e.value<double>();
        if (!v || !std::isfinite(*v)) fail(key, "expected an array of " + std::to_string(n) + " numbers");
        out.push_back(*v);
    }
    return out;
}

std::optional<Vec3> TableReader::vec3(const std::string& key) {
    const auto v = numbers(key, 3);
    if (!v) return std::nullopt;
    return Vec3((*v)[0], (*v)[1], (*v)[2]);
}

std::optional<std::vector<std::string>> TableReader::strings(const std::string& key) {
    const toml::node* node = get(key);
    if (node == nullptr) return std::nullopt;
    const toml::array* a = node->as_array();
    if (a == nullptr) fail(key, "expected an array of strings");
    std::vector<std::string> out;
    for (const toml::node& e : *a) {
        if (!e.is_string()) fail(key, "expected an array of strings");
        out.emplace_back(e.as_string()->get());
    }
    return out;
}

std::optional<std::vector<double>> TableReader::per_band(const std::string& key, std::size_t bands) {
    const toml::node* node = get(key);
    if (node == nullptr) return std::nullopt;
    std::vector<double> out;
    if (const toml::array* a = node->as_array()) {
        if (a->size() != bands)
            fail(key, "expected one value per band (" + std::to_string(bands) + "), got " + std::to_string(a->size()));
        for (const toml::node& e : *a) {
            const std::optional<double> v = e.value<double>();
            if (!v) fail(key, "expected numbers");
            out.push_back(*v);
        }
    } else if (const std::optional<double> v = node->value<double>()) {
        out.assign(bands, *v);
    } else {
        fail(key, "expected a number or one number per band");
    }
    for (double v : out)
        if (!(v >= 0.0 && v <= 1.0)) fail(key, "values must lie in [0, 1], got " + std::to_string(v));
    return out;
}

const toml::table* TableReader::table(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(key, "expected a table");
    return n->as_table();
}

const toml::array* TableReader::array(const std::string& key) {
    const toml::node* n = get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_array()) fail(key, "expected an array");
    return n->as_array();
}

void TableReader::finish() const {
    for (const auto& [k, v] : table_) {
        const std::string key(k.str());
        if (used_.count(key) != 0) continue;
        const std::string where = file_ + ":" + std::to_string(v.source().begin.line) + ": " + context_;
        if (schema_.accepts(key))
            throw InputError(where + ": key '" + key + "' does not apply here (with this type or these other keys)");
        std::string known;
        for (std::string_view s : schema_.keys) known += (known.empty() ? "" : ", ") + std::string(s);
        throw InputError(where + ": unknown key '" + key + "' (this table takes " + known + ")");
    }
}

}  // namespace luxtrace::detail
