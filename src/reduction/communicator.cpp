#include "luxtrace/reduction/communicator.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <thread>

namespace luxtrace {

namespace {
// Waits for `requests` without spinning: a rank's main thread waits for rank 0's decision
// while its tracing threads keep every core busy, and Open MPI's blocking calls poll
// (measured: two ranks over shared memory took a quarter more CPU time than one rank;
// docs/SCALING.md). The first test is immediate; then one every 100 µs.
void wait_politely(std::vector<MPI_Request>& requests) {
    if (requests.empty()) return;
    for (int done = 0;;) {
        MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
        if (done != 0) break;
        std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    requests.clear();
}

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
    if (size_ > 1) {
        // The ranks that share this one's memory (a node): the first of them leads it.
        MPI_Comm node;
        MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
        int node_rank = 0;
        MPI_Comm_rank(node, &node_rank);
        MPI_Comm_free(&node);
        const int leads = node_rank == 0 ? 1 : 0;
        int before = 0;
        MPI_Exscan(&leads, &before, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        MPI_Allreduce(&leads, &nodes_, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        node_index_ = leads != 0 ? (rank_ == 0 ? 0 : before) : -1;
    }
}

Communicator::~Communicator() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (finalized == 0) MPI_Finalize();
}

struct PendingReduce::Impl {
    std::vector<MPI_Request> requests;
    std::vector<std::vector<unsigned char>> round_buffers;  // a reduce-scatter's rounds' send pieces
};

PendingReduce::PendingReduce(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PendingReduce PendingReduce::completed() { return PendingReduce(std::make_unique<Impl>()); }
PendingReduce PendingReduce::both(PendingReduce a, PendingReduce b) {
    auto impl = std::move(a.impl_);
    for (MPI_Request r : b.impl_->requests) impl->requests.push_back(r);
    for (auto& buf : b.impl_->round_buffers) impl->round_buffers.push_back(std::move(buf));
    b.impl_->requests.clear();
    return PendingReduce(std::move(impl));
}
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

void PendingReduce::wait() { wait_politely(impl_->requests); }

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

namespace {
template <class Word>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<std::uint32_t>() {
    return MPI_UINT32_T;
}
template <>
MPI_Datatype mpi_type<std::uint64_t>() {
    return MPI_UINT64_T;
}
template <>
MPI_Datatype mpi_type<double>() {
    return MPI_DOUBLE;
}
template <>
MPI_Datatype mpi_type<float>() {
    return MPI_FLOAT;
}
}  // namespace

template <class Word>
PendingReduce Communicator::ireduce_scatter_sum(const std::vector<Word>& send, const std::vector<std::size_t>& counts,
                                                std::vector<Word>& recv) const {
    auto impl = std::make_unique<PendingReduce::Impl>();
    const std::size_t R = static_cast<std::size_t>(size_);
    std::vector<std::size_t> offset(R + 1, 0);
    for (std::size_t r = 0; r < R; ++r) offset[r + 1] = offset[r] + counts.at(r);
    recv.resize(counts[static_cast<std::size_t>(rank_)]);
    if (recv.capacity() == 0) recv.reserve(1);  // a valid address for a part of no words
    if (size_ == 1) {
        std::copy(send.begin(), send.end(), recv.begin());
        return PendingReduce(std::move(impl));
    }
    // Round k carries words [k p, (k + 1) p) of every rank's part: at most R p <= max per call.
    const std::size_t p = std::max<std::size_t>(1, std::min(max_per_call_, static_cast<std::size_t>(INT_MAX)) / R);
    std::size_t rounds = 1;
    for (std::size_t r = 0; r < R; ++r) rounds = std::max(rounds, (counts[r] + p - 1) / p);
    for (std::size_t k = 0; k < rounds; ++k) {
        std::vector<int> recvcounts(R);
        for (std::size_t r = 0; r < R; ++r)
            recvcounts[r] = static_cast<int>(std::min(p, counts[r] - std::min(counts[r], k * p)));
        const Word* from = send.data();
        if (rounds > 1) {
            std::vector<unsigned char>& buf = impl->round_buffers.emplace_back();
            std::size_t total = 0;
            for (int c : recvcounts) total += static_cast<std::size_t>(c);
            buf.resize(std::max<std::size_t>(1, total) * sizeof(Word));
            Word* out = reinterpret_cast<Word*>(buf.data());
            for (std::size_t r = 0; r < R; ++r) {
                out = std::copy_n(send.data() + offset[r] + std::min(counts[r], k * p), recvcounts[r], out);
            }
            from = reinterpret_cast<const Word*>(buf.data());
        }
        Word* to = recv.data() + std::min(recv.size(), k * p);
        MPI_Request req;
        MPI_Ireduce_scatter(from, to, recvcounts.data(), mpi_type<Word>(), MPI_SUM, MPI_COMM_WORLD, &req);
        impl->requests.push_back(req);
    }
    return PendingReduce(std::move(impl));
}

template PendingReduce Communicator::ireduce_scatter_sum(const std::vector<std::uint32_t>&,
                                                         const std::vector<std::size_t>&,
                                                         std::vector<std::uint32_t>&) const;
template PendingReduce Communicator::ireduce_scatter_sum(const std::vector<std::uint64_t>&,
                                                         const std::vector<std::size_t>&,
                                                         std::vector<std::uint64_t>&) const;

namespace {
// `op` over the ranks, element-wise and in place, in pieces of at most `max_per_call`.
void allreduce_in_place(std::vector<std::uint64_t>& values, MPI_Op op, std::size_t max_per_call) {
    std::vector<MPI_Request> requests;
    for (const auto& [off, n] : Communicator::pieces(values.size(), max_per_call)) {
        MPI_Request r;
        MPI_Iallreduce(MPI_IN_PLACE, values.data() + off, n, MPI_UINT64_T, op, MPI_COMM_WORLD, &r);
        requests.push_back(r);
    }
    wait_politely(requests);
}
}  // namespace

void Communicator::allreduce_sum(std::vector<std::uint64_t>& values) const {
    if (size_ == 1 || values.empty()) return;
    allreduce_in_place(values, MPI_SUM, max_per_call_);
}

template <class Post>
void Communicator::root_pieces(const std::vector<std::size_t>& counts, Post post) const {
    std::vector<MPI_Request> requests;
    auto post_pieces = [&](int peer, std::size_t first, std::size_t n) {
        for (const auto& [off, m] : pieces(n, max_per_call_)) {
            MPI_Request req;
            post(peer, first + off, m, &req);
            requests.push_back(req);
        }
    };
    if (rank_ == 0) {
        std::size_t at = counts[0];
        for (int r = 1; r < size_; ++r) {
            post_pieces(r, at, counts[static_cast<std::size_t>(r)]);
            at += counts[static_cast<std::size_t>(r)];
        }
    } else {
        post_pieces(0, 0, counts[static_cast<std::size_t>(rank_)]);
    }
    wait_politely(requests);
}

template <class Word>
void Communicator::gather_to_root(std::span<const Word> send, const std::vector<std::size_t>& counts,
                                  std::vector<Word>& recv) const {
    if (send.size() != counts.at(static_cast<std::size_t>(rank_)))
        throw std::logic_error("gather_to_root: this rank's words do not match its count");
    if (rank_ == 0) {
        std::size_t total = 0;
        for (std::size_t c : counts) total += c;
        recv.resize(total);
        std::copy(send.begin(), send.end(), recv.begin());
    }
    constexpr int kTag = 26;
    root_pieces(counts, [&](int peer, std::size_t at, int m, MPI_Request* req) {
        if (rank_ == 0) MPI_Irecv(recv.data() + at, m, mpi_type<Word>(), peer, kTag, MPI_COMM_WORLD, req);
        else MPI_Isend(send.data() + at, m, mpi_type<Word>(), 0, kTag, MPI_COMM_WORLD, req);
    });
}

template void Communicator::gather_to_root(std::span<const std::uint64_t>, const std::vector<std::size_t>&,
                                           std::vector<std::uint64_t>&) const;
template void Communicator::gather_to_root(std::span<const double>, const std::vector<std::size_t>&,
                                           std::vector<double>&) const;
template void Communicator::gather_to_root(std::span<const float>, const std::vector<std::size_t>&,
                                           std::vector<float>&) const;

template <class Word>
void Communicator::scatter_from_root(std::span<const Word> send, const std::vector<std::size_t>& counts,
                                     std::vector<Word>& recv) const {
    recv.resize(counts.at(static_cast<std::size_t>(rank_)));
    if (rank_ == 0) {
        std::size_t total = 0;
        for (std::size_t c : counts) total += c;
        if (send.size() != total) throw std::logic_error("scatter_from_root: the words do not match the counts");
        std::copy_n(send.begin(), counts[0], recv.begin());
    }
    constexpr int kTag = 27;
    root_pieces(counts, [&](int peer, std::size_t at, int m, MPI_Request* req) {
        if (rank_ == 0) MPI_Isend(send.data() + at, m, mpi_type<Word>(), peer, kTag, MPI_COMM_WORLD, req);
        else MPI_Irecv(recv.data() + at, m, mpi_type<Word>(), 0, kTag, MPI_COMM_WORLD, req);
    });
}

template void Communicator::scatter_from_root(std::span<const std::uint64_t>, const std::vector<std::size_t>&,
                                              std::vector<std::uint64_t>&) const;
template void Communicator::scatter_from_root(std::span<const double>, const std::vector<std::size_t>&,
                                              std::vector<double>&) const;
template void Communicator::scatter_from_root(std::span<const float>, const std::vector<std::size_t>&,
                                              std::vector<float>&) const;

void Communicator::broadcast(std::vector<double>& values) const {
    if (size_ == 1) return;
    std::vector<MPI_Request> requests;
    for (const auto& [off, n] : pieces(values.size(), max_per_call_)) {
        MPI_Request r;
        MPI_Ibcast(values.data() + off, n, MPI_DOUBLE, 0, MPI_COMM_WORLD, &r);
        requests.push_back(r);
    }
    wait_politely(requests);
}

void Communicator::allgather_parts(std::vector<double>& values, const std::vector<std::size_t>& offsets) const {
    if (size_ == 1) return;
    if (offsets.size() != static_cast<std::size_t>(size_) + 1 || offsets.back() > values.size() ||
        offsets.back() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw std::logic_error("allgather_parts: one part per rank, within the values and an int's range");
    std::vector<int> counts, displs;
    for (int r = 0; r < size_; ++r) {
        displs.push_back(static_cast<int>(offsets[static_cast<std::size_t>(r)]));
        counts.push_back(
            static_cast<int>(offsets[static_cast<std::size_t>(r) + 1] - offsets[static_cast<std::size_t>(r)]));
    }
    MPI_Request r;
    MPI_Iallgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, values.data(), counts.data(), displs.data(), MPI_DOUBLE,
                    MPI_COMM_WORLD, &r);
    std::vector<MPI_Request> requests{r};
    wait_politely(requests);
}

std::uint64_t Communicator::allreduce_max(std::uint64_t v) const {
    std::uint64_t out = v;
    MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

void Communicator::allreduce_or(std::vector<std::uint64_t>& bits) const {
    if (size_ == 1 || bits.empty()) return;
    allreduce_in_place(bits, MPI_BOR, max_per_call_);
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
