// The collectives a reduction uses, timed as the OSU micro-benchmarks time them (issue 26 §3):
// for each message size, a few warm-up calls, then as many calls as fit in --seconds, the
// mean time per call taken as the slowest rank's (a collective ends for the run when its last
// rank is done), the best of --repeats such loops. Also the local summing rate of uint64
// arrays, the receiver's work in a sum-reduction. These are the measured inputs of the
// reduction cost model (docs/SCALING.md):
//   mpirun -n 4 --oversubscribe --bind-to none build/bench/mpi_collectives --max-bytes 256M
// Raw MPI on purpose: it measures MPI itself, and the collectives the redesign will use
// (MPI_Ireduce_scatter_block) before the MPI door (reduction/communicator) has them.
#include "luxtrace/core/count.hpp"

#include <mpi.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Options {
    std::string max_bytes = "64M";
    double seconds = 0.2;
    int repeats = 3;
};

// Seconds per call of `op` (the slowest rank's mean), best of `repeats` timed loops.
template <class Op>
double time_per_call(const Options& o, Op op) {
    for (int w = 0; w < 2; ++w) op();
    double best = 1e300;
    for (int r = 0; r < o.repeats; ++r) {
        // Every rank runs the same number of calls: rank 0's count for the time budget.
        MPI_Barrier(MPI_COMM_WORLD);
        double t0 = MPI_Wtime();
        op();
        double once = MPI_Wtime() - t0;
        MPI_Allreduce(MPI_IN_PLACE, &once, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        long calls = std::clamp(static_cast<long>(o.seconds / std::max(once, 1e-7)), 1L, 100000L);
        MPI_Barrier(MPI_COMM_WORLD);
        t0 = MPI_Wtime();
        for (long k = 0; k < calls; ++k) op();
        double t = (MPI_Wtime() - t0) / static_cast<double>(calls);
        MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        best = std::min(best, t);
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    Options o;
    CLI::App app{"MPI collectives of a reduction: latency, bandwidth, summing rate"};
    app.add_option("--max-bytes", o.max_bytes, "largest message per rank (e.g. 64M, 1G)");
    app.add_option("--seconds", o.seconds, "time per size and repeat");
    app.add_option("--repeats", o.repeats, "timed loops per size (the best is kept)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = rank == 0 ? app.exit(e) : 0;
        MPI_Finalize();
        return code;
    }
    const auto max_bytes = luxtrace::parse_count(o.max_bytes);
    if (!max_bytes || *max_bytes < 8) {
        if (rank == 0) std::fprintf(stderr, "mpi_collectives: --max-bytes: not a size of at least 8\n");
        MPI_Finalize();
        return 2;
    }
    if (rank == 0)
        std::printf(
            "# %d ranks; bytes per rank; time per call (us, slowest rank, best of %d); bandwidth = bytes / time "
            "(GB/s)\n%-26s %12s %12s %10s\n",
            ranks, o.repeats, "operation", "bytes", "time_us", "GB/s");
    // Message sizes 8 B, 64 B, ... up to max_bytes (each a multiple of 8 bytes and of the rank count).
    for (std::uint64_t bytes = 8; bytes <= *max_bytes; bytes *= 8) {
        const std::size_t n = std::max<std::size_t>(static_cast<std::size_t>(bytes / 8) / ranks * ranks, ranks);
        std::vector<std::uint64_t> send(n, 1), recv(n, 0), slice(n / ranks, 0);
        std::vector<double> words(n, 1.0);
        const double b = 8.0 * static_cast<double>(n);
        auto row = [&](const char* name, double t) {
            if (rank == 0) std::printf("%-26s %12.0f %12.2f %10.3f\n", name, b, t * 1e6, b / t * 1e-9);
        };
        row("Ireduce+Wait (sum)", time_per_call(o, [&] {
                MPI_Request r;
                MPI_Ireduce(send.data(), rank == 0 ? recv.data() : nullptr, static_cast<int>(n), MPI_UINT64_T, MPI_SUM,
                            0, MPI_COMM_WORLD, &r);
                MPI_Wait(&r, MPI_STATUS_IGNORE);
            }));
        row("Ireduce_scatter_block", time_per_call(o, [&] {
                MPI_Request r;
                MPI_Ireduce_scatter_block(send.data(), slice.data(), static_cast<int>(n / ranks), MPI_UINT64_T, MPI_SUM,
                                          MPI_COMM_WORLD, &r);
                MPI_Wait(&r, MPI_STATUS_IGNORE);
            }));
        row("Allreduce (bor)", time_per_call(o, [&] {
                MPI_Allreduce(send.data(), recv.data(), static_cast<int>(n), MPI_UINT64_T, MPI_BOR, MPI_COMM_WORLD);
            }));
        row("Bcast (double)",
            time_per_call(o, [&] { MPI_Bcast(words.data(), static_cast<int>(n), MPI_DOUBLE, 0, MPI_COMM_WORLD); }));
        row("Gather (slice to root)", time_per_call(o, [&] {
                MPI_Gather(slice.data(), static_cast<int>(n / ranks), MPI_UINT64_T, rank == 0 ? recv.data() : nullptr,
                           static_cast<int>(n / ranks), MPI_UINT64_T, 0, MPI_COMM_WORLD);
            }));
        // The receiver's work: adding one array of counts into another.
        row("local sum (uint64 +=)", time_per_call(o, [&] {
                for (std::size_t i = 0; i < n; ++i) recv[i] += send[i];
            }));
    }
    MPI_Finalize();
    return 0;
}
