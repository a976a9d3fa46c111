// The year's light after an event at a sensor grid, gathered from a result's surface map
// through luxtrace's own sensor_gather (tracer/sensor_gather.hpp): for each cell,
// sum over the sides it sees of K rho E / pi, E the side's year of exposure in the result
// (/global/illuminance), rho its diffuse reflectance. Prints, per result file, the gathered
// values against the first file's disc values (the photons' count over each sensor's disc
// of what arrived after an event, [annual] direct = "shadow_rays") and against the first
// file's gathered values: the C++ side of bench/annual_gather_potential.py
// (docs/PERFORMANCE.md "A path to ten times").
//
//   build/bench/gather_year SCENE.toml REFERENCE.h5 [RUN.h5 ...] [--detector sensors] [--rays 4096]
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/embree_scene.hpp"
#include "luxtrace/tracer/sensor_gather.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace luxtrace;

namespace {

// Per cell, sum over its sides of K rho E / pi.
std::vector<double> gathered(const Scene& scene, const SensorGather& k, const std::vector<double>& side_lx) {
    std::vector<double> out(k.cells, 0.0);
    const std::size_t triangles = scene.triangle_count();
    for (std::size_t c = 0; c < k.cells; ++c)
        for (std::size_t i = k.offset[c]; i < k.offset[c + 1]; ++i) {
            const std::size_t side = k.site[i], tri = side % triangles, face = side / triangles;
            const Material& m = scene.materials[scene.triangle_material[tri]];
            const double rho = m.type == MaterialType::diffuse && !m.diffuse_reflectance.empty()
                                   ? m.diffuse_reflectance[0]
                                   : 0.0;
            out[c] += k.weight_sr[i] * rho * side_lx[tri * 2 + face] / kPi;
        }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app("gather_year: the year's light after an event gathered from a result's map");
    std::string scene_file, detector = "sensors";
    std::vector<std::string> results;
    int rays = 4096;
    std::vector<double> check;  // the reference's mean ratio must lie in [lo, hi]
    app.add_option("scene", scene_file, "the scene the results were run on")->required();
    app.add_option("results", results, "the reference result, then the runs to compare")->required();
    app.add_option("--detector", detector, "the points or illuminance grid");
    app.add_option("--rays", rays, "gather rays per cell");
    app.add_option("--check-ratio", check, "LO HI: exit 1 unless the reference's mean gathered / disc lies in [LO, HI]")
        ->expected(2);
    CLI11_PARSE(app, argc, argv);
    try {
        const Scene scene = load_scene(scene_file);
        const EmbreeScene embree(scene);
        std::size_t det = scene.detectors.size();
        for (std::size_t d = 0; d < scene.detectors.size(); ++d)
            if (scene.detectors[d].name == detector) det = d;
        if (det == scene.detectors.size()) throw std::runtime_error("no detector " + detector);
        const std::size_t cells = static_cast<std::size_t>(scene.detectors[det].cells());
        SensorGatherOptions o;
        o.rays = rays;
        const SensorGather k = sensor_gather(scene, embree, det, o, 0, cells);
        std::vector<double> ref_gathered, ref_disc;
        for (const std::string& file : results) {
            const ResultReader r(file);
            std::vector<std::size_t> shape;
            const std::vector<double> side_lx = r.f64("/global/illuminance", &shape);
            if (shape.empty() || shape[0] != scene.triangle_count() || side_lx.size() != 2 * scene.triangle_count())
                throw std::runtime_error(file + ": its map is not this scene's (one band, two sides a triangle)");
            const std::vector<double> disc = r.f64("/detectors/" + detector + "/value");
            const std::vector<double> g = gathered(scene, k, side_lx);
            if (ref_gathered.empty()) {
                ref_gathered = g;
                ref_disc = disc;
                double mean = 0.0, lo = 1e300, hi = 0.0;
                for (std::size_t c = 0; c < cells; ++c) {
                    const double x = g[c] / disc[c];
                    mean += x / static_cast<double>(cells);
                    lo = std::min(lo, x);
                    hi = std::max(hi, x);
                }
                std::printf("%s: gathered / disc values, mean %.4f, by cell %.3f-%.3f\n", file.c_str(), mean, lo, hi);
                if (check.size() == 2 && !(mean >= check[0] && mean <= check[1])) {
                    std::fprintf(stderr, "gather_year: the mean ratio %.4f lies outside [%g, %g]\n", mean, check[0],
                                 check[1]);
                    return 1;
                }
                continue;
            }
            double e_gather = 0.0, e_disc = 0.0;
            for (std::size_t c = 0; c < cells; ++c) {
                e_gather += std::pow(g[c] / ref_gathered[c] - 1.0, 2) / static_cast<double>(cells);
                e_disc += std::pow(disc[c] / ref_disc[c] - 1.0, 2) / static_cast<double>(cells);
            }
            std::printf("%s: RMS against the reference, gathered %.3f %%, disc %.3f %%\n", file.c_str(),
                        100.0 * std::sqrt(e_gather), 100.0 * std::sqrt(e_disc));
        }
    } catch (const std::exception& e) {
        std::cerr << "gather_year: " << e.what() << '\n';
        return 2;
    }
    return 0;
}
