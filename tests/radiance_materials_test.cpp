// Radiance materials mapped onto luxtrace's (issue 25 §2, docs/RADIANCE.md "Materials"):
// each type against the formulas of Radiance's reference manual, energy conserved, the
// units (179 lm/W), the glass transmissivity against Radiance's documented pair (tn 0.96 is
// a pane of normal transmittance 0.88), and every modifier of real Radiance scenes mapped.
#include "luxtrace/scene/radiance_materials.hpp"

#include "luxtrace/core/error.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace luxtrace {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kY{"Y"}, kRgb{"R", "G", "B"};

// Each test process writes its own files (ctest runs the cases as parallel processes).
RadianceModel model_of(const std::string& text) {
    static const test_support::ScratchDir dir("radiance_materials");
    static int n = 0;
    const fs::path p = dir.path() / ("model_" + std::to_string(++n) + ".rad");
    std::ofstream(p) << text;
    return read_radiance(p);
}

double y_of(double r, double g, double b) {
    return kRadianceLuminanceWeights[0] * r + kRadianceLuminanceWeights[1] * g + kRadianceLuminanceWeights[2] * b;
}

TEST(RadianceMaterials, PlasticAndMetalSplitTheirColourAsRadianceDoes) {
    const RadianceModel m = model_of("void plastic wall 0 0 5 0.6 0.5 0.4 0.05 0.1\n"
                                     "void metal chrome 0 0 5 0.8 0.7 0.6 0.9 0\n");
    const RadianceMapping wall = map_radiance_modifier(m, 0, kRgb);
    EXPECT_EQ(wall.material.type, MaterialType::general);
    EXPECT_NEAR(wall.material.diffuse_reflectance[1], 0.5 * 0.95, 1e-15);
    EXPECT_NEAR(wall.material.specular_reflectance[2], 0.05, 1e-15);  // white highlight
    EXPECT_DOUBLE_EQ(wall.material.roughness, 0.1);
    const RadianceMapping wall_y = map_radiance_modifier(m, 0, kY);
    EXPECT_NEAR(wall_y.material.diffuse_reflectance[0], 0.95 * y_of(0.6, 0.5, 0.4), 1e-15);
    const RadianceMapping chrome = map_radiance_modifier(m, 1, kRgb);
    EXPECT_NEAR(chrome.material.specular_reflectance[0], 0.8 * 0.9, 1e-15);  // coloured highlight
    EXPECT_NEAR(chrome.material.diffuse_reflectance[0], 0.8 * 0.1, 1e-15);
    EXPECT_EQ(chrome.material.roughness, 0.0);  // roughness 0: a mirror-like highlight
    EXPECT_NE(wall.describe().find("roughness 0.1"), std::string::npos) << wall.describe();
}

TEST(RadianceMaterials, TransConservesWhatItDoesNotAbsorb) {
    // Rd + Rs + Td + Ts = c (1 - s) + s for every band (Radiance's trans formulas).
    const RadianceModel m = model_of("void trans shade 0 0 7 0.7 0.6 0.5 0.04 0 0.4 0.25\n");
    const RadianceMapping t = map_radiance_modifier(m, 0, kRgb);
    const double c[3] = {0.7, 0.6, 0.5};
    for (int b = 0; b < 3; ++b) {
        const Material& x = t.material;
        EXPECT_NEAR(x.diffuse_reflectance[b] + x.specular_reflectance[b] + x.diffuse_transmittance[b] +
                        x.specular_transmittance[b],
                    c[b] * 0.96 + 0.04, 1e-15);
        EXPECT_NEAR(x.specular_transmittance[b], c[b] * 0.96 * 0.4 * 0.25, 1e-15);
        EXPECT_NEAR(x.diffuse_transmittance[b], c[b] * 0.96 * 0.4 * 0.75, 1e-15);
    }
}

TEST(RadianceMaterials, GlassTransmissivityIsTheRadianceManualsPane) {
    // Radiance's manual: a transmissivity of 0.96 is a pane of normal transmittance 0.88.
    const RadianceModel m = model_of("void glass pane 0 0 3 0.96 0.96 0.96\n");
    const RadianceMapping g = map_radiance_modifier(m, 0, kY);
    EXPECT_EQ(g.material.type, MaterialType::glazing);
    EXPECT_NEAR(g.material.transmittance[0], 0.88, 2e-3);
    ASSERT_TRUE(g.material.glazing);
    // The pane's curve at normal incidence gives the same transmittance back.
    EXPECT_NEAR(pane_optics(1.0, 1.52, pane_transmissivity(g.material.transmittance[0], 1.52)).transmittance,
                g.material.transmittance[0], 1e-9);
}

TEST(RadianceMaterials, RefractiveIndicesNoGlassCanHaveAreRefusedAndTheGlazingsRangeKept) {
    // A glass (pane) of index n <= 1 has no Fresnel reflectance at grazing incidence
    // (0 / 0): it is taken into the glazing's range [1.2, 3] with a note; an index that is
    // not positive belongs to no material, glass or dielectric, and is refused with its line.
    const RadianceModel m = model_of("void glass plain 0 0 4 0.9 0.9 0.9 1\nvoid glass dense 0 0 4 0.9 0.9 0.9 7\n"
                                     "void glass zero 0 0 4 0.9 0.9 0.9 0\nvoid dielectric neg 0 0 5 1 1 1 -1.5 0\n"
                                     "void dielectric bubble 0 0 5 1 1 1 0.75 0\n");
    const RadianceMapping plain = map_radiance_modifier(m, 0, kY);
    EXPECT_EQ(plain.material.ior, 1.2);
    ASSERT_FALSE(plain.notes.empty());
    for (const double cos_i : {0.0, 0.5, 1.0}) {
        const PaneOptics o = plain.material.glazing->front().at(cos_i);
        EXPECT_TRUE(o.reflectance >= 0.0 && o.transmittance >= 0.0 && o.reflectance + o.transmittance <= 1.0)
            << "cos " << cos_i << ": R " << o.reflectance << " T " << o.transmittance;
    }
    EXPECT_EQ(map_radiance_modifier(m, 1, kY).material.ior, 3.0);
    for (const std::size_t k : {2, 3}) {
        try {
            map_radiance_modifier(m, k, kY);
            ADD_FAILURE() << "modifier " << k << ": an index that is not positive must be refused";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(":" + std::to_string(k + 1) + ":"), std::string::npos) << e.what();
        }
    }
    // A dielectric below 1 is an interface into a thinner medium (an air bubble in water).
    EXPECT_EQ(map_radiance_modifier(m, 4, kY).material.ior, 0.75);
}

TEST(RadianceMaterials, LightsAreLuminanceAt179LumensPerWatt) {
    const RadianceModel m = model_of("void light lamp 0 0 3 10 10 10\nvoid glow dim 0 0 4 1 2 3 0\n"
                                     "void illum window 0 0 3 1 1 1\n");
    const RadianceMapping lamp = map_radiance_modifier(m, 0, kY);
    EXPECT_EQ(lamp.role, RadianceRole::light);
    EXPECT_NEAR(lamp.luminance_cd_m2[0], 1790.0, 1e-9);  // the weights sum to 1
    const RadianceMapping dim = map_radiance_modifier(m, 1, kRgb);
    // R, G, B bands share the luminance as Radiance weighs the channels: they sum to 179 x
    // its luminance, as the one band Y does.
    EXPECT_NEAR(dim.luminance_cd_m2[2], 3.0 * 179.0 * kRadianceLuminanceWeights[2], 1e-12);
    EXPECT_NEAR(dim.luminance_cd_m2[0] + dim.luminance_cd_m2[1] + dim.luminance_cd_m2[2],
                map_radiance_modifier(m, 1, kY).luminance_cd_m2[0], 1e-9);
    EXPECT_FALSE(dim.notes.empty());  // glow's radius is an approximation, and says so
    EXPECT_EQ(map_radiance_modifier(m, 2, kY).role, RadianceRole::portal);
}

TEST(RadianceMaterials, ApproximationsAreSaidAndBadValuesNamed) {
    const RadianceModel m = model_of(
        "void plastic hot 0 0 5 1.2 0.5 0.5 0 0\nvoid plastic neg 0 0 5 -0.1 0.5 0.5 0 0\n");
    const RadianceMapping hot = map_radiance_modifier(m, 0, kRgb);
    EXPECT_EQ(hot.material.diffuse_reflectance[0], 1.0);
    ASSERT_FALSE(hot.notes.empty());
    try {
        map_radiance_modifier(m, 1, kRgb);
        FAIL() << "a negative colour must be refused";
    } catch (const InputError& e) {
        const std::string w = e.what();
        EXPECT_NE(w.find(":2:"), std::string::npos) << w;  // its line
        EXPECT_NE(w.find("'neg'"), std::string::npos) << w;
    }
    EXPECT_THROW(map_radiance_modifier(m, 0, std::vector<std::string>{"A", "B"}), InputError);
    // check's line for a mirror names what it is.
    const RadianceMapping mirror = map_radiance_modifier(model_of("void mirror shiny 0 0 3 .9 .9 .9\n"), 0, kY);
    EXPECT_EQ(mirror.describe(), "shiny -> mirror, specular reflectance 0.9");
}

TEST(RadianceMaterials, EveryModifierOfRealScenesMaps) {
    // Public Radiance scenes (tests/data/radiance/SOURCES.md): each material maps, and the
    // surface materials keep every probability within [0, 1] and their sum at most 1.
    const fs::path dir = fs::path(LUXTRACE_TEST_DATA_DIR) / "radiance";
    int mapped = 0;
    for (const char* file : {"cornell.rad", "basic.mat"}) {
        const RadianceModel m = read_radiance(dir / file);
        for (std::size_t i = 0; i < m.modifiers.size(); ++i) {
            const RadianceMapping r = map_radiance_modifier(m, i, kRgb);
            std::cout << "[radiance] " << r.describe() << "\n";
            if (r.role != RadianceRole::surface || r.material.type != MaterialType::general) continue;
            for (int b = 0; b < 3; ++b) EXPECT_LE(albedo(r.material, b), 1.0 + 1e-12) << r.describe();
            ++mapped;
        }
    }
    EXPECT_GE(mapped, 5);
}

}  // namespace
}  // namespace luxtrace
