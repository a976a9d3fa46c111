// The distributed reduction's two ways of sending the map (issue 26), under mpirun with
// several ranks (ctest reduction_mpi): the same run with the map's counts as 32-bit words
// (the default while they fit) and with every reduction forced to 64-bit words
// (RunOptions::narrow_word_bound = 1) gives the same tallies word for word, and the
// history's global estimates with the same bits (reductions at photon counts: the same
// photons in each); the result's reduction_message_bytes says which way each run took.
// Exit 0 when all agree; the first disagreement is printed and fails the run.
#include "luxtrace/io/result_reader.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/run/simulation.hpp"
#include "luxtrace/scene/scene.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace luxtrace;

namespace {

int failures = 0;

void expect(bool ok, const std::string& what) {
    if (ok) return;
    if (++failures <= 5) std::fprintf(stderr, "reduction_mpi_test: %s\n", what.c_str());
}

RunSummary run(const Communicator& comm, const std::filesystem::path& output, std::uint64_t narrow_word_bound) {
    Scene scene = load_scene(std::string(LUXTRACE_TEST_DATA_DIR) + "/run/room.toml");
    scene.run.photons = 200000;
    scene.run.report_every_photons = 40000;
    scene.run.seed = 11;
    scene.run.output = output.string();
    RunOptions opt;
    opt.threads = 1;
    opt.quiet = true;
    opt.narrow_word_bound = narrow_word_bound;
    std::ostringstream out;
    return run_simulation(scene, comm, opt, out);
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("luxtrace_reduction_mpi_" +
                                       std::to_string(comm.allreduce_max(static_cast<std::uint64_t>(::getpid()))));
    if (comm.is_root()) std::filesystem::create_directories(dir);
    comm.allreduce_max(std::uint64_t{0});  // the directory exists before any rank writes
    const RunSummary narrow = run(comm, dir / "narrow.h5", 0);
    const RunSummary wide = run(comm, dir / "wide.h5", 1);
    expect(narrow.exit_code == 0 && wide.exit_code == 0, "both runs finish");
    if (comm.is_root() && failures == 0) {
        const ResultReader a((dir / "narrow.h5").string()), b((dir / "wide.h5").string());
        for (const char* d : {"/global/count_odd", "/global/count_even", "/global/direct_odd", "/global/direct_even",
                              "/global/sumsq", "/detectors/table/count", "/detectors/table/sumsq"})
            expect(a.u64(d) == b.u64(d), std::string(d) + " the same with 32- and 64-bit words");
        const std::uint64_t words_a = a.attr_u64("/", "reduction_message_words");
        const std::uint64_t bytes_a = a.attr_u64("/", "reduction_message_bytes");
        const std::uint64_t words_b = b.attr_u64("/", "reduction_message_words");
        const std::uint64_t bytes_b = b.attr_u64("/", "reduction_message_bytes");
        expect(words_a > 0 && bytes_a < 8 * words_a, "the default run sent 32-bit words");
        expect(words_b > 0 && bytes_b == 8 * words_b, "the forced run sent 64-bit words");
        const std::vector<double> ha = a.f64("/history/sigma_rel_global"), hb = b.f64("/history/sigma_rel_global");
        expect(ha.size() >= 5 && ha == hb, "the history's global errors have the same bits");
        std::printf("reduction_mpi_test: %d ranks, %zu reductions, longest message %llu words: %llu bytes (32-bit), "
                    "%llu bytes (64-bit)\n",
                    comm.size(), ha.size(), static_cast<unsigned long long>(words_a),
                    static_cast<unsigned long long>(bytes_a), static_cast<unsigned long long>(bytes_b));
        std::filesystem::remove_all(dir);
    }
    const std::uint64_t worst = comm.allreduce_max(static_cast<std::uint64_t>(failures));
    if (comm.is_root()) std::printf("reduction_mpi_test: %s\n", worst == 0 ? "all agree" : "FAILED");
    return worst == 0 ? 0 : 1;
}
