// The typed reader (include/luxtrace/io/result_data.hpp) against the raw one: on a format-1
// file of luxtrace 0.2 and on a format-2 result and checkpoint written by a short run, what
// ResultFile returns is what ResultReader reads by path, and its maps obey the tallies'
// definitions (E = E0 (n_odd + n_even) / A per side and band; a floor lit from above has
// an unlit back).
#include "luxtrace/io/result_data.hpp"
#include "luxtrace/core/error.hpp"
#include "luxtrace/io/result_file.hpp"
#include "luxtrace/io/result_reader.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;
using namespace luxtrace;

namespace {

const fs::path kFormat1 = fs::path(LUXTRACE_TEST_DATA_DIR) / "results" / "format1_result_rgb.h5";

// Element by element, NaN (a cell that got nothing) equal to NaN.
bool same(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
    return true;
}

// Root attributes and the mesh, as both readers see them.
void expect_header_agrees(const ResultFile& f, const ResultReader& r) {
    EXPECT_EQ(f.format_version(), r.attr_u64("/", "format_version"));
    EXPECT_EQ(f.is_checkpoint(), r.attr_str("/", "format") == "luxtrace-checkpoint");
    const RunInfo& i = f.run_info();
    EXPECT_EQ(i.seed, r.attr_u64("/", "seed"));
    EXPECT_EQ(i.photons, r.attr_u64("/", "photons"));
    EXPECT_EQ(i.flux_per_photon_lm, r.attr_f64("/", "flux_per_photon_lm"));
    EXPECT_EQ(i.sampler, r.attr_str("/", "sampler"));
    EXPECT_EQ(i.stop_reason, r.attr_str("/", "stop_reason"));
    EXPECT_EQ(i.scene_file, r.attr_str("/", "scene_file"));
    EXPECT_EQ(static_cast<std::uint64_t>(i.ranks), r.attr_u64("/", "ranks"));
    EXPECT_EQ(i.reductions, r.attr_u64("/", "reductions"));
    // Setup times (files from before they were written have none): the BVH is built within
    // the run's time, the scene loaded before it.
    if (r.has_attr("/", "bvh_build_s")) {
        EXPECT_EQ(i.load_s, r.attr_f64("/", "load_s"));
        EXPECT_EQ(i.bvh_build_s, r.attr_f64("/", "bvh_build_s"));
        EXPECT_GT(i.bvh_build_s, 0.0);
        EXPECT_LE(i.bvh_build_s, i.elapsed_s);
    }
    EXPECT_EQ(f.scene_name(), r.attr_str("/", "scene_name"));
    EXPECT_EQ(f.bands(), r.attr_strs("/", "bands"));
    std::vector<std::size_t> vshape, tshape;
    EXPECT_EQ(f.vertices(), r.f64("/mesh/vertices", &vshape));
    r.f64("/mesh/area", &tshape);
    EXPECT_EQ(f.mesh_shape().vertices, vshape[0]);
    EXPECT_EQ(f.mesh_shape().triangles, tshape[0]);
    ASSERT_TRUE(f.material_names());
    EXPECT_EQ(*f.material_names(), r.attr_strs("/mesh", "material_names"));
}

// The surface maps and detectors: the raw arrays, and E = E0 (n_odd + n_even) / A_t.
void expect_maps_agree(const ResultFile& f, const ResultReader& r) {
    const SurfaceIlluminance e = f.surface_illuminance();
    const SurfaceCounts n = f.surface_counts();
    EXPECT_TRUE(same(e.total_lx, r.f64("/global/illuminance")));
    EXPECT_TRUE(same(e.direct_lx, r.f64("/global/illuminance_direct")));
    EXPECT_EQ(n.count_odd, r.u64("/global/count_odd"));
    EXPECT_EQ(n.count_even, r.u64("/global/count_even"));
    EXPECT_EQ(n.direct_odd, r.u64("/global/direct_odd"));
    EXPECT_EQ(n.direct_even, r.u64("/global/direct_even"));
    const SurfaceShape& s = e.shape;
    EXPECT_EQ(s.sides, f.surface_sides());
    EXPECT_EQ(s.triangles, f.mesh_shape().triangles);
    EXPECT_EQ(s.bands, f.bands().size());
    EXPECT_EQ(s.size(), e.total_lx.size());
    const std::vector<double> area = r.f64("/mesh/area");
    const double e0 = f.run_info().flux_per_photon_lm;
    double lit = 0.0;
    for (std::size_t t = 0; t < s.triangles; ++t)
        for (std::size_t side = 0; side < 2; ++side)
            for (std::size_t b = 0; b < s.bands; ++b) {
                const std::size_t i = s.index(t, side, b);
                const double expected = e0 * static_cast<double>(n.count_odd[i] + n.count_even[i]) / area[t];
                EXPECT_NEAR(e.total_lx[i], expected, 1e-12 * expected);
                EXPECT_LE(e.direct_lx[i], e.total_lx[i]);
                lit += e.total_lx[i];
            }
    EXPECT_GT(lit, 0.0);
    const std::vector<std::string> names = f.detector_names();
    EXPECT_EQ(names, r.children("/detectors"));
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names) {
        const std::string g = "/detectors/" + name;
        const DetectorData d = f.detector(name);
        std::vector<std::size_t> shape;
        EXPECT_EQ(d.count, r.u64(g + "/count", &shape));
        EXPECT_EQ(d.sumsq, r.u64(g + "/sumsq"));
        EXPECT_TRUE(same(d.value, r.f64(g + "/value")));
        EXPECT_TRUE(same(d.sigma_rel, r.f64(g + "/sigma_rel")));
        EXPECT_EQ((std::vector<std::size_t>{d.ny, d.nx, d.bands}), shape);
        const std::vector<double> cells = r.f64_attr_array(g, "cells");
        EXPECT_EQ(d.nx, static_cast<std::size_t>(cells[0]));
        EXPECT_EQ(d.ny, static_cast<std::size_t>(cells[1]));
        EXPECT_EQ(d.type, r.attr_str(g, "type"));
        EXPECT_EQ(d.photons_received, r.attr_u64(g, "photons_received"));
        EXPECT_EQ(d.mean_value, r.attr_f64(g, "mean_value"));
    }
    EXPECT_THROW(f.detector("no such detector"), InputError);
}

}  // namespace

TEST(ResultData, FormatOneFileReadsAsOneMapForBothSides) {
    const ResultFile f(kFormat1);
    const ResultReader r(kFormat1);
    EXPECT_EQ(f.format_version(), 1u);
    EXPECT_EQ(f.surface_sides(), 1u);
    expect_header_agrees(f, r);
    expect_maps_agree(f, r);
    // Format 1's one map serves both sides, and has no second moments.
    const SurfaceIlluminance e = f.surface_illuminance();
    for (std::size_t t = 0; t < e.shape.triangles; ++t)
        for (std::size_t b = 0; b < e.shape.bands; ++b) {
            EXPECT_EQ(e.shape.index(t, 0, b), e.shape.index(t, 1, b));
            EXPECT_EQ(e.shape.index(t, 0, b), t * e.shape.bands + b);
        }
    EXPECT_TRUE(f.surface_counts().sumsq.empty());
    EXPECT_FALSE(f.is_checkpoint());
    EXPECT_THROW(f.checkpoint_budget(), InputError);
}

TEST(ResultData, FormatTwoResultAndCheckpointOfARun) {
    const luxtrace::test_support::ScratchDir dir("result_data");
    const fs::path scene = fs::path(LUXTRACE_TEST_DATA_DIR) / "validation" / "point_floor.toml";
    const fs::path out = dir.path() / "r.h5", ck = dir.path() / "ck.h5";
    const auto run = luxtrace::test_support::run_luxtrace(
        "run " + scene.string() + " --photons 20k --seed 3 --threads 1 --report-every-photons 10k --quiet" +
        " --checkpoint-every 0.000001 --checkpoint " + ck.string() + " --output " + out.string());
    ASSERT_EQ(run.code, 0) << run.out;
    ASSERT_TRUE(fs::exists(ck)) << run.out;
    for (const fs::path& p : {out, ck}) {
        SCOPED_TRACE(p.string());
        const ResultFile f(p);
        const ResultReader r(p);
        EXPECT_EQ(f.format_version(), kResultFormatVersion);
        EXPECT_EQ(f.surface_sides(), 2u);
        expect_header_agrees(f, r);
        expect_maps_agree(f, r);
        EXPECT_EQ(f.surface_counts().sumsq, r.u64("/global/sumsq"));
    }
    const ResultFile f(out);
    EXPECT_EQ(f.run_info().photons, 20000u);
    EXPECT_EQ(f.run_info().seed, 3u);
    // The floor faces the light above it: its back side receives nothing.
    const SurfaceIlluminance e = f.surface_illuminance();
    double front = 0.0, back = 0.0;
    for (std::size_t t = 0; t < e.shape.triangles; ++t)
        for (std::size_t b = 0; b < e.shape.bands; ++b) {
            front += e.total_lx[e.shape.index(t, 0, b)];
            back += e.total_lx[e.shape.index(t, 1, b)];
        }
    EXPECT_GT(front, 0.0);
    EXPECT_EQ(back, 0.0);
    const ResultFile c(ck);
    EXPECT_TRUE(c.is_checkpoint());
    EXPECT_EQ(c.checkpoint_budget(), ResultReader(ck).attr_u64("/checkpoint", "budget"));
}

TEST(ResultData, RefusesWhatIsNotAResult) {
    const luxtrace::test_support::ScratchDir dir("result_data_bad");
    EXPECT_THROW(ResultFile(dir.path() / "missing.h5"), InputError);
    const fs::path text = dir.path() / "text.h5";
    std::ofstream(text) << "not HDF5\n";
    EXPECT_THROW(ResultFile{text}, InputError);
}
