#pragma once
// Luminaires written by Radiance's ies2rad, read back as the photometry they came from
// (issue 25 §1; docs/RADIANCE.md "Luminaires from ies2rad"). ies2rad turns an IES file into
// a `brightdata` pattern over a `.dat` table of candela / 179 (source.cal's corr, flatcorr,
// boxcorr or cylcorr with src_phi*/src_theta), a `light` (or `illum`) it modifies and the
// emitting surfaces of that light. The intensity Radiance renders toward a direction d is
// then 179 * Y(light colour) * A1 * dat(d) * G(d), with A1 the pattern's first real (1 if
// none) and G the correction's geometry: the front area of the surfaces toward d (flatcorr),
// their projected area (corr), or that over the box's or cylinder's projected area (boxcorr,
// cylcorr). Reading that back gives a type C Photometry in the pattern's frame: nadir its
// -z, C0 its +x, C90 its +y, all moved by the pattern's own transform arguments and the
// !xform lines around its definition.
#include "luxtrace/core/math.hpp"
#include "luxtrace/light/photometry.hpp"
#include "luxtrace/scene/radiance_reader.hpp"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace luxtrace {

struct RadianceLuminaireOptions {
    // Folders searched for the `.dat` after the folder of the file defining the brightdata,
    // in order (Radiance's RAYPATH: library files name paths like "source/x/y.dat").
    std::vector<std::filesystem::path> search_path;
};

struct RadianceLuminaire {
    std::string name;                   // the brightdata modifier's name
    std::string data_file;              // the `.dat` read ("" when the photometry came from an IES file)
    Photometry photometry;              // type C, candela, in `frame`
    Vec3 position_m{0.0};               // centre of the emitting surfaces (their bounds in the frame)
    Frame frame;                        // scene directions of C0 (t), C90 (b) and the nadir (n); b = t x n
    std::vector<std::size_t> surfaces;  // the emitting surfaces, indices into RadianceModel::surfaces
    std::vector<std::string> notes;     // "file:line: ..." things a user should know
};

// The brightdata modifiers of `model` that feed an emitting material (light, illum,
// spotlight or glow) which some surface uses: the ies2rad luminaires in it, in file order.
std::vector<std::size_t> radiance_luminaire_modifiers(const RadianceModel& model);

// The luminaire of brightdata modifier `brightdata`, read from its `.dat`. Throws InputError
// naming the file and line: a brightdata that is not ies2rad's (function, .cal file or
// coordinates), a missing or malformed `.dat`, no emitting surface.
RadianceLuminaire radiance_luminaire(const RadianceModel& model, std::size_t brightdata,
                                     const RadianceLuminaireOptions& options = {});

// The same luminaire with the photometry of the IES (or EULUMDAT) file it came from, which
// the scene names instead: the file's table, flux, opening and tilt are taken as they are,
// placed at the model's position and frame; the `.dat` is not read. A named file takes
// precedence over the `.dat` (which holds the same table rounded to 6 digits, after
// ies2rad's -m multiplier and the lamp colour, and without the luminous opening or tilt).
RadianceLuminaire radiance_luminaire_named(const RadianceModel& model, std::size_t brightdata,
                                           const Photometry& photometry);

}  // namespace luxtrace
