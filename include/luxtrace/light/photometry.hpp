#pragma once
// A luminaire's goniometric photometry, as read from an IES LM-63 or EULUMDAT file: an
// intensity table over two angles, the file's statement of its flux, its luminous
// opening and its lamp-tilt multipliers. docs/PHOTOMETRY.md has the conventions, with a
// figure; in short, in the luminaire frame (orientation.hpp places it in the scene):
//  - local +z is the photometric axis: the nadir for type C, the beam axis (H = V = 0)
//    for types B and A;
//  - type C: gamma from +z, C0 along local +x and C90 along local +y:
//    direction = (sin g cos c, sin g sin c, cos g). The frame has C90 = C0 x nadir, so
//    C angles turn counter-clockwise seen from above a downlight (LM-63-2002 type C,
//    CIE/EN C-planes, Radiance's source.cal since 2008);
//  - type B: polar axis local +x (the luminaire's lateral axis, +H to the right looking
//    along the beam), V about it toward local +y (up): direction = (sin H, cos H sin V,
//    cos H cos V);
//  - type A: polar axis local +y (the luminaire's vertical axis), H about it toward +x,
//    V toward +y: direction = (cos V sin H, sin V, cos V cos H).
#include "luxtrace/core/math.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {

enum class PhotometricType { C = 1, B = 2, A = 3 };

// How a type C file's C-planes cover the full circle (LM-63 rules, keyed on the first and
// last horizontal angle; EULUMDAT's Isym maps onto the same cases).
enum class CPlaneSymmetry {
    Rotational,   // a single plane (0): the same in every C-plane
    Quadrant,     // 0..90: mirrored about the 0-180 and the 90-270 planes
    Bilateral,    // 0..180: mirrored about the 0-180 plane
    Bilateral90,  // 90..270 (LM-63-1995): mirrored about the 90-270 plane
    Full,         // 0..360: no symmetry, plane 360 is plane 0
};

// The symmetry a type C file's horizontal angles declare (the LM-63 rules above), or
// nullopt if they fit none.
std::optional<CPlaneSymmetry> c_plane_symmetry(const std::vector<double>& horizontal_deg);

// Shape of the luminous opening in the luminaire frame (the LM-63-2002/2019 table of
// luminous shapes by the signs of width, length and height; EULUMDAT's luminous area). Sizes in metres: `length_m`
// along the C0-C180 axis (local x), `width_m` along C90-C270 (local y), `height_m` along the photometric axis (local
// z). The photometric centre is the shape's centre.
struct LuminousOpening {
    enum class Shape {
        point,                  // no size given: all light from the photometric centre
        rectangle,              // length x width, flat, facing +-z
        ellipse,                // a disk when length = width
        box,                    // length x width x height, luminous top, bottom and sides
        vertical_cylinder,      // elliptic cross-section length x width, axis along z, height
        cylinder_along_length,  // horizontal cylinder, axis along x (length), diameter width = height
        cylinder_along_width,   // horizontal cylinder, axis along y (width), diameter length = height
        ellipsoid,              // a sphere when all three are equal
    };
    Shape shape = Shape::point;
    double length_m = 0.0, width_m = 0.0, height_m = 0.0;
};
const char* shape_name(LuminousOpening::Shape s);

// Lamp output against the luminaire's tilt (LM-63 TILT=INCLUDE / TILT=<file>).
struct TiltTable {
    int lamp_geometry = 0;          // 1 vertical lamp, 2 horizontal lamp that stays so, 3 tilts with it
    std::vector<double> angle_deg;  // increasing, tilt from the measured position
    std::vector<double> multiplier;
    bool empty() const { return angle_deg.empty(); }
    // Linear between the table's angles; held at the end values beyond them.
    double at(double tilt_deg) const;
};

struct Photometry {
    std::string format;  // "IES LM-63-2002", "EULUMDAT", ... (for reports)
    PhotometricType type = PhotometricType::C;
    std::vector<double> vertical_deg;                           // gamma (C) or V (B, A) angles
    std::vector<double> horizontal_deg;                         // C (C) or H (B, A) angles as in the file (B, A:
                                                                // mirrored to -90 when the file gives 0-90)
    std::vector<std::vector<double>> candela_cd;                // [horizontal][vertical] in cd, with every
                                                                // factor of the file applied
    std::vector<std::pair<std::string, std::string>> keywords;  // "[TEST] x" -> {"TEST", "x"}
    std::string luminaire;                                      // the file's name for it, for reports
    int num_lamps = 1;
    // Rated lamp flux of all lamps (lm); < 0 for absolute photometry (no lamp rating).
    double lamp_flux_lm = -1.0;
    // The luminaire flux the file itself states (EULUMDAT: lamp flux x LORL); < 0 if the
    // file states none (IES LM-63 does not).
    double stated_flux_lm = -1.0;
    double input_watts = 0.0;
    LuminousOpening opening;
    TiltTable tilt;
    std::vector<std::string> notes;  // things a user should know (become scene warnings)

    // Symmetry of a type C table; throws std::logic_error for other types or if the
    // angles fit no rule (the readers never return such data).
    CPlaneSymmetry symmetry() const;

    // Type C: intensity in cd toward (gamma, c) in radians, bilinear in the file's angles,
    // unfolded by its symmetry, zero outside the vertical range.
    double intensity_cd(double gamma_rad, double c_rad) const;
    // Any type: intensity toward a unit direction of the luminaire frame.
    double intensity_cd(const Vec3& local) const;
    // Any type: the table (bilinear, unfolded, zero outside) at the file's own angles.
    double table_cd(double horizontal_deg, double vertical_deg) const;

    // Luminous flux in lm: the integral of the intensity over the sphere, exact for the
    // bilinear interpolant.
    double flux_lm() const;
};

// The file's angles of a local direction: {horizontal, vertical} in degrees (C and gamma
// for type C, with C in [0, 360)).
std::pair<double, double> photometric_angles_deg(PhotometricType type, const Vec3& local);
// The inverse: a unit local direction.
Vec3 photometric_direction(PhotometricType type, double horizontal_deg, double vertical_deg);

}  // namespace luxtrace
