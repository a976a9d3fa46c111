#include "luxtrace/reduction/communicator.hpp"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstdlib>

namespace luxtrace {

Communicator::Communicator(int* argc, char*** argv) {
    int provided = 0;
    // Only the main thread calls MPI; tracing threads never do.
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Communicator::~Communicator() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (finalized == 0) MPI_Finalize();
}

void Communicator::reduce_sum_to_root(std::vector<std::uint64_t>& data) const {
    if (size_ == 1) return;
    // MPI counts are int: reduce maps larger than 2^31 elements in pieces.
    constexpr std::size_t kPiece = std::size_t{1} << 28;
    for (std::size_t off = 0; off < data.size(); off += kPiece) {
        const int n = static_cast<int>(std::min(kPiece, data.size() - off));
        if (rank_ == 0)
            MPI_Reduce(MPI_IN_PLACE, data.data() + off, n, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
        else
            MPI_Reduce(data.data() + off, nullptr, n, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    }
}

std::uint64_t Communicator::allreduce_max(std::uint64_t v) const {
    std::uint64_t out = v;
    MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

double Communicator::allreduce_max(double v) const {
    double out = v;
    MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

int Communicator::broadcast(int v) const {
    MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v;
}

void Communicator::barrier() const { MPI_Barrier(MPI_COMM_WORLD); }

double Communicator::wtime() const { return MPI_Wtime(); }

void Communicator::abort(int code) const {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
}

}  // namespace luxtrace
