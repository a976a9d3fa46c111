#pragma once
// The keys the scene loader accepts, table by table: the loader's own list. TableReader
// refuses a key that is not listed for its table, and a key the loader reads that is not
// listed is a programming error, so this list is the truth docs/REFERENCE.md is checked
// against (tests/reference_test.cpp, both directions).
//
// To add a key: list it here, read it in its table's loader (src/scene/*_loader.cpp, the steps
// in scene_loader.hpp), document it in docs/REFERENCE.md.
#include <string_view>
#include <vector>

namespace luxtrace {

struct SceneTableSchema {
    // Dotted TOML path of the table: "" is the top level, "light" every [[light]],
    // "light.grid" the grid table inside a [[light]], "run.target" every [[run.target]].
    std::string_view path;
    std::vector<std::string_view> keys;

    bool accepts(std::string_view key) const;
};

// Every table of a scene file, the top level first.
const std::vector<SceneTableSchema>& scene_schema();
// The schema of one table; std::logic_error if the path is not in scene_schema().
const SceneTableSchema& scene_table_schema(std::string_view path);

}  // namespace luxtrace
