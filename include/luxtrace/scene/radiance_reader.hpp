#pragma once
// Radiance scene files (.rad) read into a neutral model: the modifiers as records (name,
// type, arguments; mapped to luxtrace materials by the caller), the surfaces as triangles
// (radiance_shapes.hpp), distant `source`s and the sky generators' command lines as
// records. Nothing is run: `!xform` lines are read (radiance_xform.hpp), `!gensky` and
// `!gendaylit` are kept, any other command is refused. docs/RADIANCE.md lists what is read,
// what is refused and the tolerances. To read a new primitive: add it to the type tables
// at the top of radiance_reader.cpp, read it there, list it in docs/RADIANCE.md.
#include "luxtrace/scene/shapes.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

struct RadianceOptions {
    double scale = 1.0;  // metres per model unit (0.3048 for feet, 0.001 for mm)
    // Curved surfaces: every point of a triangle within chord_tolerance * radius of the
    // true surface (areas then within a factor (1 - chord_tolerance)^2 of the exact ones).
    double chord_tolerance = 0.002;
};

struct RadianceLocation {
    int file = 0;  // index into RadianceModel::files
    int line = 0;  // 1-based
};

// A modifier: a material (plastic, metal, trans, glass, dielectric, mirror, light, glow,
// spotlight, illum), or one of the kept non-materials: `texfunc` (ignored, with a warning),
// `brightdata` (ies2rad's luminaire data, kept for the caller) and the `skyfunc` pattern
// that a `!gensky` / `!gendaylit` line defines. plastic2, metal2 and trans2 are read as
// plastic, metal and trans (the roughness sqrt(u v), which keeps the lobe's peak) with a
// warning; `type` is then the isotropic one and `read_as` the original.
struct RadianceModifier {
    std::string name;
    std::string type;
    std::string read_as;   // the type in the file when it differs from `type`, else ""
    int modifier = -1;     // index of this one's own modifier, -1 for void
    int sky_command = -1;  // for `skyfunc`: the RadianceModel::sky_commands entry defining it
    std::vector<std::string> strings;
    std::vector<double> reals;
    RadianceLocation at;
    // The !xform lines in force where it was defined (its file -> the top file's model
    // units): a pattern's coordinates move with the surfaces around it, as xform would
    // have appended the transform to the pattern's arguments.
    glm::dmat4 transform{1.0};
};

// One surface primitive of the file (a polygon, ring, sphere, ...) and its triangles
// [first_triangle, first_triangle + triangle_count) of the model's mesh.
struct RadianceSurface {
    std::string name;   // with xform -n prefixes
    std::string type;   // as read after any xform -I or negative radius: "sphere", "bubble", ...
    int modifier = -1;  // the surface's material (through ignored texfuncs)
    std::size_t first_triangle = 0;
    std::size_t triangle_count = 0;
    RadianceLocation at;
};

// `mod source id 0 0 4 dx dy dz angle`: a light at infinity.
struct RadianceSource {
    std::string name;
    int modifier = -1;
    Vec3 direction{0.0};     // unit, toward the source, in scene coordinates
    double angle_deg = 0.0;  // the full angle it subtends
    RadianceLocation at;
};

// `!gensky ...` or `!gendaylit ...`, not run: the caller maps the arguments to its sky and sun.
struct RadianceCommand {
    std::string program;  // "gensky" or "gendaylit"
    std::vector<std::string> arguments;
    glm::dmat4 transform{1.0};  // of the xforms that included the line (the sky is rotated with them)
    RadianceLocation at;
};

struct RadianceModel {
    std::vector<std::string> files;           // every file read, the first the one asked for
    std::vector<RadianceModifier> modifiers;  // in the order defined (a name defined again is a new entry)
    std::vector<RadianceSurface> surfaces;
    TriangleMesh mesh;                             // in metres; front side as shapes.hpp; material_names left empty
    std::vector<std::uint32_t> triangle_modifier;  // per triangle: index into `modifiers`
    std::vector<RadianceSource> sources;
    std::vector<RadianceCommand> sky_commands;
    std::vector<std::string> warnings;  // "file:line: ..." each

    std::string where(const RadianceLocation& at) const;  // "file:line"
};

// Reads the file and every file its `!xform` lines name. Throws InputError naming the file,
// the line and what is wrong (exit 2).
RadianceModel read_radiance(const std::filesystem::path& path, const RadianceOptions& options = {});
// Several files read in turn as one model, as oconv reads its arguments: a modifier defined
// in one (a .mat) is in force in the files after it.
RadianceModel read_radiance(const std::vector<std::filesystem::path>& paths, const RadianceOptions& options = {});

}  // namespace luxtrace
