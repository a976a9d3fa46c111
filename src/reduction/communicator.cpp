#include "luxtrace/reduction/communicator.hpp"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstdlib>

namespace luxtrace {

namespace {
// A plain `./luxtrace` is an MPI singleton: one rank, no peers, so no network transport
// is needed, yet Open MPI probes UCX and libfabric first, which takes about 0.2 s of a
// 0.45 s start here (README, "Running on a cluster"). Without any launcher's variables in
// the environment, default the transports to the in-process ones; a user's own OMPI_MCA_*
// settings win, and a rank started by mpirun, srun or another PMI launcher is left alone.
bool launched_by_a_launcher() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "PMI_FD", "SLURM_STEP_NUM_TASKS",
                          "MPI_LOCALNRANKS", "HYDRA_CONTROL_FD"})
        if (std::getenv(v) != nullptr) return true;
    return false;
}
}  // namespace

Communicator::Communicator(int* argc, char*** argv) {
    if (!launched_by_a_launcher()) {
        setenv("OMPI_MCA_pml", "ob1", 0);
        setenv("OMPI_MCA_btl", "self", 0);
        setenv("OMPI_MCA_mtl", "^ofi", 0);
        // Nor the orted that Open MPI 4.1 forks to serve a singleton: a PMIx event from it
        // can reach the progress thread after MPI_Finalize has unloaded mca_pmix_ext3x.so,
        // whose handler it then calls (SIGSEGV on exit, seen after an early exit 2 on a
        // loaded machine). An isolated singleton's session directory is always jf.0, which
        // concurrent ones create and remove under each other; with one rank and btl=self
        // nothing needs it.
        setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
        setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
    }
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

struct PendingReduce::Impl {
    std::vector<MPI_Request> requests;
};

PendingReduce::PendingReduce(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PendingReduce PendingReduce::completed() { return PendingReduce(std::make_unique<Impl>()); }
PendingReduce::~PendingReduce() {
    if (impl_) wait();
}
PendingReduce::PendingReduce(PendingReduce&&) noexcept = default;
PendingReduce& PendingReduce::operator=(PendingReduce&&) noexcept = default;

bool PendingReduce::test() {
    if (impl_->requests.empty()) return true;
    int done = 0;
    MPI_Testall(static_cast<int>(impl_->requests.size()), impl_->requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done != 0) impl_->requests.clear();
    return done != 0;
}

void PendingReduce::wait() {
    if (impl_->requests.empty()) return;
    MPI_Waitall(static_cast<int>(impl_->requests.size()), impl_->requests.data(), MPI_STATUSES_IGNORE);
    impl_->requests.clear();
}

std::vector<std::pair<std::size_t, int>> Communicator::pieces(std::size_t n, std::size_t max_per_call) {
    const std::size_t step = std::clamp<std::size_t>(max_per_call, 1, static_cast<std::size_t>(INT_MAX));
    std::vector<std::pair<std::size_t, int>> out;
    for (std::size_t off = 0; off < n; off += step) out.emplace_back(off, static_cast<int>(std::min(step, n - off)));
    return out;
}

PendingReduce Communicator::ireduce_sum_to_root(const std::vector<std::uint64_t>& send,
                                                std::vector<std::uint64_t>& recv) const {
    auto impl = std::make_unique<PendingReduce::Impl>();
    if (rank_ == 0) recv.assign(send.size(), 0);
    if (size_ == 1) {
        recv = send;
        return PendingReduce(std::move(impl));
    }
    for (const auto& [off, n] : pieces(send.size(), max_per_call_)) {
        MPI_Request r;
        MPI_Ireduce(send.data() + off, rank_ == 0 ? recv.data() + off : nullptr, n, MPI_UINT64_T, MPI_SUM, 0,
                    MPI_COMM_WORLD, &r);
        impl->requests.push_back(r);
    }
    return PendingReduce(std::move(impl));
}

void Communicator::broadcast(std::vector<double>& values) const {
    if (size_ == 1) return;
    for (const auto& [off, n] : pieces(values.size(), max_per_call_))
        MPI_Bcast(values.data() + off, n, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

std::uint64_t Communicator::allreduce_max(std::uint64_t v) const {
    std::uint64_t out = v;
    MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

void Communicator::allreduce_or(std::vector<std::uint64_t>& bits) const {
    if (size_ == 1 || bits.empty()) return;
    for (const auto& [off, n] : pieces(bits.size(), max_per_call_))
        MPI_Allreduce(MPI_IN_PLACE, bits.data() + off, n, MPI_UINT64_T, MPI_BOR, MPI_COMM_WORLD);
}

double Communicator::allreduce_max(double v) const {
    double out = v;
    MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

double Communicator::wtime() const { return MPI_Wtime(); }

void Communicator::abort(int code) const {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::exit(code);
}

}  // namespace luxtrace
