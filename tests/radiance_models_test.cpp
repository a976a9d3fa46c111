// Radiance models nobody here wrote (issue 25 §4): Honeybee's sample model folder and test
// model (tests/data/radiance/SOURCES.md) read as they are, every modifier mapped, and the
// geometry checked against what the files say of the rooms: each room closed (its oriented
// area vector sums to zero), its volume and floor area those of its dimensions, each glass
// the pane transmittance Honeybee made it from, each sensor over its room's floor.
#include "luxtrace/detector/pts_file.hpp"
#include "luxtrace/scene/radiance_materials.hpp"
#include "luxtrace/scene/radiance_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

const fs::path kHoneybee = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "honeybee";
const std::vector<std::string> kY{"Y"};

// The closed-surface integrals of a set of surfaces: vector area and enclosed volume
// (divergence theorem, V = 1/3 sum over triangles of x . n dA with x any vertex).
struct Enclosure {
    Vec3 area_vector{0.0};
    double volume_m3 = 0.0;
};

template <class Belongs>
Enclosure enclosure(const RadianceModel& m, const Belongs& belongs) {
    Enclosure e;
    for (const RadianceSurface& s : m.surfaces) {
        if (!belongs(s.name)) continue;
        for (std::size_t t = s.first_triangle; t < s.first_triangle + s.triangle_count; ++t) {
            const glm::uvec3 k = m.mesh.triangles[t];
            const Vec3 &a = m.mesh.vertices[k.x], &b = m.mesh.vertices[k.y], &c = m.mesh.vertices[k.z];
            const Vec3 n2 = glm::cross(b - a, c - a);  // twice the vector area
            e.area_vector += 0.5 * n2;
            e.volume_m3 += glm::dot(a, n2) / 6.0;
        }
    }
    return e;
}

double area_of_modifier(const RadianceModel& m, const std::string& modifier) {
    double a = 0.0;
    for (const RadianceSurface& s : m.surfaces) {
        if (m.modifiers[s.modifier].name != modifier) continue;
        for (std::size_t t = s.first_triangle; t < s.first_triangle + s.triangle_count; ++t) {
            const glm::uvec3 k = m.mesh.triangles[t];
            const Vec3 &a0 = m.mesh.vertices[k.x], &b = m.mesh.vertices[k.y], &c = m.mesh.vertices[k.z];
            a += 0.5 * glm::length(glm::cross(b - a0, c - a0));
        }
    }
    return a;
}

// Objects of one Radiance type in a file, counted by a plain scan of its header lines
// ("modifier type name"), independently of the reader.
int count_objects(const fs::path& file, const std::string& type) {
    std::ifstream in(file);
    std::string a, b, c;
    int n = 0;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        if ((words >> a >> b >> c) && b == type && !(words >> a)) ++n;
    }
    return n;
}

// Maps every modifier and returns the mappings by name (the last definition of a name).
std::map<std::string, RadianceMapping> map_all(const RadianceModel& m) {
    std::map<std::string, RadianceMapping> out;
    for (std::size_t i = 0; i < m.modifiers.size(); ++i) {
        RadianceMapping r = map_radiance_modifier(m, i, kY);
        std::cout << "[radiance] " << r.describe() << "\n";
        out[m.modifiers[i].name] = std::move(r);
    }
    return out;
}

// Honeybee writes a glass of visible transmittance T as Radiance's transmissivity of a
// 1.52 pane (honeybee-radiance Glass.from_single_transmittance, the Radiance manual's
// formula); the mapping must give the pane's T back. The manual's constants are rounded
// to 10 digits, hence the tolerance.
void expect_pane(const std::map<std::string, RadianceMapping>& maps, const std::string& name, double t) {
    const RadianceMapping& r = maps.at(name);
    EXPECT_EQ(r.role, RadianceRole::surface) << name;
    ASSERT_EQ(r.material.type, MaterialType::glazing) << name;
    ASSERT_EQ(r.material.transmittance.size(), 1u);
    EXPECT_NEAR(r.material.transmittance[0], t, 1e-6) << name;
}

// The rooms' own faces and apertures (not the apertures' exterior reveals, "..._OutBorderK").
bool in_class_room(const std::string& n) {
    if (n.find("_OutBorder") != std::string::npos) return false;
    return n.rfind("class_room_", 0) == 0 || n.rfind("skylight_", 0) == 0 || n.rfind("north_window", 0) == 0 ||
           n.rfind("east_window_classroom", 0) == 0;
}
bool in_office(const std::string& n) {
    if (n.find("_OutBorder") != std::string::npos) return false;
    return n.rfind("office_", 0) == 0 || n.rfind("EC_Aperture", 0) == 0 || n.rfind("east_window_office", 0) == 0;
}
bool in_tiny_house(const std::string& n) {
    return (n.rfind("TinyHouseZone_", 0) == 0 && n.find("Overhang") == std::string::npos) || n == "FrontDoor" ||
           n == "FrontAperture";
}

TEST(RadianceModels, HoneybeeModelFolderReadsAsTheRoomsItDescribes) {
    // honeybee-radiance-folder's static model: a class room 6 m x 12 m (floor at z = 0, a
    // roof from 7 m down to 3.6 m over y = 3..12 m, two skylights) beside an office
    // 6 m x 9 m x 4 m, windows in both; a 1 m sensor grid over each floor at 0.8 m.
    const fs::path model = kHoneybee / "model";
    const RadianceModel m = read_radiance(kHoneybee / "static_model.rad");
    int polygons = 0;
    for (const char* f : {"scene/envelope.rad", "scene/shades.rad", "aperture/aperture.rad"})
        polygons += count_objects(model / f, "polygon");
    EXPECT_EQ(m.surfaces.size(), static_cast<std::size_t>(polygons));
    EXPECT_EQ(m.sources.size(), 2u);  // the sky and ground hemispheres
    ASSERT_EQ(m.sky_commands.size(), 1u);
    EXPECT_EQ(m.sky_commands[0].program, "gensky");

    const std::map<std::string, RadianceMapping> maps = map_all(m);
    EXPECT_EQ(maps.at("sky_glow").role, RadianceRole::light);
    for (const auto& [name, refl] : std::map<std::string, double>{{"generic_wall_0.50", 0.5},
                                                                  {"generic_ceiling_0.80", 0.8},
                                                                  {"generic_floor_0.20", 0.2}}) {
        const Material& w = maps.at(name).material;  // grey plastic: Lambertian of its colour
        ASSERT_EQ(w.diffuse_reflectance.size(), 1u);
        EXPECT_NEAR(w.diffuse_reflectance[0], refl, 1e-9) << name;
        EXPECT_EQ(w.specular_reflectance[0], 0.0) << name;
    }
    expect_pane(maps, "custom_glass", 0.65);
    expect_pane(maps, "Tint_0", 0.40);
    expect_pane(maps, "Tint_1", 0.12);
    for (const RadianceSurface& s : m.surfaces)  // every surface on a modifier that maps
        EXPECT_TRUE(maps.count(m.modifiers[s.modifier].name)) << s.name;

    // Each room, walls with their windows, is closed and outward-facing: its vector area
    // vanishes and the divergence theorem gives its volume (the class room a prism 6 m
    // wide over the section (0,0) (12,0) (12,3.6) (4,5) (3,7) (0,7) of 61.4 m^2).
    const Enclosure cls = enclosure(m, in_class_room), off = enclosure(m, in_office);
    EXPECT_LT(glm::length(cls.area_vector), 1e-9);
    EXPECT_LT(glm::length(off.area_vector), 1e-9);
    EXPECT_NEAR(cls.volume_m3, 6.0 * 61.4, 1e-9);
    EXPECT_NEAR(off.volume_m3, 6.0 * 9.0 * 4.0, 1e-9);
    EXPECT_NEAR(area_of_modifier(m, "generic_floor_0.20"), 6.0 * 12.0 + 6.0 * 9.0, 1e-9);

    // The grids: one sensor per square metre of floor, over the floor, 0.8 m up, facing up.
    struct Grid {
        const char* file;
        double y0, y1;
    };
    for (const Grid& g : {Grid{"grid/class_room.pts", 0.0, 12.0}, Grid{"grid/office.pts", -9.0, 0.0}}) {
        const SensorPointList pts = read_pts((model / g.file).string());
        EXPECT_EQ(pts.positions.size(), static_cast<std::size_t>(std::lround(6.0 * (g.y1 - g.y0)))) << g.file;
        for (std::size_t i = 0; i < pts.positions.size(); ++i) {
            const Vec3 p = pts.positions[i];
            EXPECT_TRUE(p.x > -3.0 && p.x < 3.0 && p.y > g.y0 && p.y < g.y1) << g.file << " sensor " << i;
            EXPECT_NEAR(p.z, 0.8, 1e-6) << g.file << " sensor " << i;
            EXPECT_EQ(pts.directions[i], Vec3(0.0, 0.0, 1.0));
        }
    }
}

TEST(RadianceModels, HoneybeeTestModelReadsAsTheHouseItDescribes) {
    // honeybee-radiance's test model: a 5 m x 10 m x 3 m house with a door, two windows,
    // light shelves, a table and a tree canopy, modifiers and geometry in one file.
    const fs::path file = kHoneybee / "test_model.rad";
    const RadianceModel m = read_radiance(file);
    EXPECT_EQ(m.surfaces.size(), static_cast<std::size_t>(count_objects(file, "polygon")));
    EXPECT_EQ(m.modifiers.size(),
              static_cast<std::size_t>(count_objects(file, "plastic") + count_objects(file, "glass")));

    const std::map<std::string, RadianceMapping> maps = map_all(m);
    for (const auto& [name, r] : maps) EXPECT_EQ(r.role, RadianceRole::surface) << name;
    expect_pane(maps, "generic_exterior_window_vis_0.64", 0.64);
    expect_pane(maps, "generic_interior_window_vis_0.88", 0.88);
    expect_pane(maps, "custom_triple_pane_0.3", 0.30);
    // Honeybee's air boundary is a glass of transmissivity 1: still a pane reflecting
    // 2 r0 / (1 + r0) of normal light, r0 = ((n-1)/(n+1))^2 (glazing.hpp), not a hole.
    const double r0 = std::pow(0.52 / 2.52, 2);
    expect_pane(maps, "air_boundary", 1.0 - 2.0 * r0 / (1.0 + r0));

    const Enclosure house = enclosure(m, in_tiny_house);
    EXPECT_LT(glm::length(house.area_vector), 1e-9);
    EXPECT_NEAR(house.volume_m3, 5.0 * 10.0 * 3.0, 1e-9);
    EXPECT_NEAR(area_of_modifier(m, "DarkFloor"), 5.0 * 10.0, 1e-9);
}

TEST(RadianceModels, Cie171RoofOpeningIsTheReportsRoom) {
    // tests/data/radiance/cie171 (written here, SOURCES.md): CIE 171:2006 §5.9/5.10's
    // 4 m x 4 m x 3 m room with a 1 m x 1 m roof opening, open and glazed, under gensky -c.
    const fs::path dir = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "cie171";
    auto all = [](const std::string&) { return true; };
    const RadianceModel open = read_radiance(dir / "roof_1x1_open.rad");
    const RadianceModel glazed = read_radiance(dir / "roof_1x1_glazed.rad");
    for (const RadianceModel* m : {&open, &glazed}) {
        ASSERT_EQ(m->sky_commands.size(), 1u);
        const std::vector<std::string>& a = m->sky_commands[0].arguments;
        EXPECT_NE(std::find(a.begin(), a.end(), "-c"), a.end());  // the CIE overcast sky
        const Material black = map_all(*m).at("black").material;
        EXPECT_EQ(black.diffuse_reflectance[0] + black.specular_reflectance[0], 0.0);
    }
    // Open, the outward area vector lacks the opening's 1 m^2 of roof; glazed, the room is closed.
    const Enclosure o = enclosure(open, all), g = enclosure(glazed, all);
    EXPECT_LT(glm::length(o.area_vector - Vec3(0.0, 0.0, -1.0)), 1e-12);
    EXPECT_LT(glm::length(g.area_vector), 1e-12);
    EXPECT_NEAR(g.volume_m3, 4.0 * 4.0 * 3.0, 1e-12);
    expect_pane(map_all(glazed), "clear_6mm", 0.88);

    // The report's points A-N: inside the room, 1 mm in front of the wall or floor they lie on.
    const SensorPointList pts = read_pts((dir / "points.pts").string());
    ASSERT_EQ(pts.positions.size(), 14u);
    for (std::size_t i = 0; i < pts.positions.size(); ++i) {
        const Vec3 p = pts.positions[i], d = pts.directions[i];
        EXPECT_TRUE(p.x > 0.0 && p.x < 4.0 && p.y > 0.0 && p.y < 4.0 && p.z > 0.0 && p.z < 3.0) << i;
        const double gap = i < 6 ? 4.0 - p.y : p.z;  // A-F on the north wall, G-N on the floor
        EXPECT_NEAR(gap, 0.001, 1e-12) << i;
        EXPECT_EQ(d, i < 6 ? Vec3(0.0, -1.0, 0.0) : Vec3(0.0, 0.0, 1.0)) << i;
    }
}

TEST(RadianceModels, Ward1990TestRoomIsThePublishedRoom) {
    // tests/data/radiance/ward1990 (written here from the published description, SOURCES.md):
    // a closed 10 x 6 x 3 room facing inward, a 0.5 x 0.5 fixture of 31.416 W/m^2 in the
    // ceiling, reflectances 70/50/30 %.
    const fs::path dir = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance" / "ward1990";
    const RadianceModel m = read_radiance(dir / "room.rad");
    const Enclosure e = enclosure(m, [](const std::string&) { return true; });
    EXPECT_LT(glm::length(e.area_vector), 1e-12);
    EXPECT_NEAR(e.volume_m3, -10.0 * 6.0 * 3.0, 1e-12);  // negative: the surfaces face inward
    EXPECT_NEAR(area_of_modifier(m, "ceiling_70"), 60.0 - 0.25, 1e-12);
    const std::map<std::string, RadianceMapping> maps = map_all(m);
    // Emittance M = pi L: 31.416 W/m^2 is a radiance of 10 W sr^-1 m^-2, 1790 cd/m^2 at 179 lm/W.
    const RadianceMapping& fixture = maps.at("fixture_10");
    ASSERT_EQ(fixture.role, RadianceRole::light);
    EXPECT_NEAR(kPi * fixture.luminance_cd_m2[0] / kRadianceEfficacy_lm_per_W, 31.416, 1e-3);
    for (const auto& [name, refl] :
         std::map<std::string, double>{{"ceiling_70", 0.7}, {"wall_50", 0.5}, {"floor_30", 0.3}})
        EXPECT_NEAR(maps.at(name).material.diffuse_reflectance[0], refl, 1e-12) << name;
    const SensorPointList pts = read_pts((dir / "ceiling.pts").string());
    ASSERT_EQ(pts.positions.size(), 20u);
    for (std::size_t i = 0; i < pts.positions.size(); ++i) {  // under the ceiling, facing down
        EXPECT_NEAR(pts.positions[i].z, 2.999, 1e-12);
        EXPECT_EQ(pts.directions[i], Vec3(0.0, 0.0, -1.0));
    }
}

}  // namespace
}  // namespace luxtrace
