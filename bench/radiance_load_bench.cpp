// Loading speed of the Radiance reader against the mesh loader (assimp) on the same
// geometry (issue 25: "no slower than the mesh loaders per triangle"; docs/PERFORMANCE.md
// "Loading Radiance scenes"). bench/radiance_load.sh writes the files; this times each
// loader on them, alternating, and prints seconds per million triangles and their ratio.
// Usage: radiance_load_bench MODEL.rad MESH.obj [MESH.ply ...] [--repeats N]
#include "luxtrace/core/error.hpp"
#include "luxtrace/scene/mesh_loader.hpp"
#include "luxtrace/scene/radiance_reader.hpp"
#include "timing.hpp"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace {

using namespace luxtrace;
using bench::Clock;

struct Loader {
    std::string label;
    std::function<TriangleMesh()> load;
    std::vector<double> wall_s, cpu_s;
    std::size_t triangles = 0;
    double area_m2 = 0.0;  // of the last load: the files must hold the same geometry
};

double total_area(const TriangleMesh& mesh) {
    double a = 0.0;
    for (const glm::uvec3& t : mesh.triangles)
        a += 0.5 *
             glm::length(glm::cross(mesh.vertices[t.y] - mesh.vertices[t.x], mesh.vertices[t.z] - mesh.vertices[t.x]));
    return a;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Seconds per million triangles: read_radiance against load_mesh on the same geometry"};
    std::string rad;
    std::vector<std::string> meshes;
    int repeats = 3;
    app.add_option("model", rad, "the .rad file")->required()->check(CLI::ExistingFile);
    app.add_option("meshes", meshes, "the same geometry as mesh files (.obj, .ply)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--repeats", repeats, "loads of each file (the median is reported)")->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);

    std::vector<Loader> loaders;
    loaders.push_back({"read_radiance " + rad, [&] { return read_radiance(rad).mesh; }, {}, {}, 0, 0.0});
    for (const std::string& m : meshes)
        loaders.push_back({"load_mesh " + m, [m] { return load_mesh(m, Transform{}, "bench"); }, {}, {}, 0, 0.0});

    for (int r = 0; r < repeats; ++r) {
        for (Loader& l : loaders) {  // alternating, so that a busy spell of the machine hits both
            const auto t0 = Clock::now();
            const double c0 = bench::process_cpu_seconds();
            TriangleMesh mesh;
            try {
                mesh = l.load();
            } catch (const InputError& e) {
                std::fprintf(stderr, "radiance_load_bench: %s\n", e.what());
                return 2;
            }
            l.wall_s.push_back(bench::seconds_since(t0));
            l.cpu_s.push_back(bench::process_cpu_seconds() - c0);
            l.triangles = mesh.triangles.size();
            l.area_m2 = total_area(mesh);
        }
    }
    for (const Loader& l : loaders)
        if (l.triangles != loaders[0].triangles ||
            std::abs(l.area_m2 - loaders[0].area_m2) > 1e-6 * loaders[0].area_m2) {
            std::fprintf(stderr,
                         "radiance_load_bench: %s gave %zu triangles of %.9g m2, %s %zu of %.9g m2: not the same "
                         "geometry\n",
                         l.label.c_str(), l.triangles, l.area_m2, loaders[0].label.c_str(), loaders[0].triangles,
                         loaders[0].area_m2);
            return 1;
        }
    const double per_rad = bench::median(loaders[0].wall_s) / (loaders[0].triangles * 1e-6);
    std::printf("%-60s %10s %8s %8s %12s %8s\n", "loader", "triangles", "wall_s", "cpu_s", "s_per_Mtri", "ratio");
    for (const Loader& l : loaders) {
        const double per = bench::median(l.wall_s) / (l.triangles * 1e-6);
        std::printf("%-60s %10zu %8.3f %8.3f %12.3f %8.2f\n", l.label.c_str(), l.triangles, bench::median(l.wall_s),
                    bench::median(l.cpu_s), per, per / per_rad);
    }
    std::printf("(median of %d loads each; ratio = the loader's seconds per triangle / read_radiance's)\n", repeats);
    return 0;
}
