// The MPI door's collectives in pieces (issue 26: Open MPI 4.1 has no large-count
// collectives, so arrays longer than an int's count travel in pieces). Run under mpirun
// with several ranks (ctest communicator_mpi): the piece bookkeeping for counts above
// 2^31, then every collective with a piece size of 7 elements on arrays of 0 to 1000
// elements, each rank's data distinct, against the sums, maxima and ORs worked out here;
// the distributed reduction's collectives (reduce-scatter in 32- and 64-bit words, parts
// of unequal and zero lengths, in rounds; the sum onto every rank; the gather to rank 0).
// Exit 0 when all agree; the first disagreement is printed and fails the run.
#include "luxtrace/reduction/communicator.hpp"

#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

using luxtrace::Communicator;

namespace {

int failures = 0;

void expect(bool ok, const char* what, std::size_t n, std::size_t i) {
    if (ok) return;
    if (++failures <= 5) std::fprintf(stderr, "communicator_mpi_test: %s (n %zu, element %zu)\n", what, n, i);
}

// Rank r's element i: distinct per rank and element, large enough to use all 64 bits.
std::uint64_t value(int rank, std::size_t i) { return (std::uint64_t{1} << 40) * (rank + 1) + i * 2654435761u; }

void check_pieces() {
    // 2^31 + 5 elements in pieces of the default size: whole, in order, each an int count.
    const std::size_t n = (std::size_t{1} << 31) + 5;
    const auto p = Communicator::pieces(n, Communicator::kMaxElementsPerCall);
    std::size_t next = 0;
    for (const auto& [off, count] : p) {
        expect(off == next && count > 0 && static_cast<std::size_t>(count) <= Communicator::kMaxElementsPerCall,
               "pieces cover the array in order", n, off);
        next = off + static_cast<std::size_t>(count);
    }
    expect(next == n && p.size() == 9, "2^31 + 5 elements are 8 full pieces and one of 5", n, p.size());
    // A limit above an int's range is held to INT_MAX.
    const auto big = Communicator::pieces(std::size_t{5} << 30, std::size_t{1} << 40);
    expect(big.size() == 3 && big[0].second == INT_MAX, "pieces never exceed INT_MAX elements", big.size(), 0);
    expect(Communicator::pieces(0, 7).empty(), "no piece for an empty array", 0, 0);
}

// Rank `owner`'s part has this many words out of n: unequal, and rank 1's empty.
std::size_t part_length(std::size_t n, int owner) { return owner == 1 ? 0 : n / (2 + static_cast<std::size_t>(owner)); }

template <class Word>
void check_reduce_scatter(const Communicator& comm, std::size_t n) {
    const int R = comm.size();
    std::vector<std::size_t> counts(static_cast<std::size_t>(R));
    std::size_t total = 0;
    for (int r = 0; r < R; ++r) total += counts[static_cast<std::size_t>(r)] = part_length(n, r);
    // Element i of the whole message: small enough that the sum over the ranks fits a Word.
    auto element = [](int rank, std::size_t i) { return static_cast<Word>((rank + 1) * 1000003u + i * 7u); };
    std::vector<Word> send(total), recv;
    for (std::size_t i = 0; i < total; ++i) send[i] = element(comm.rank(), i);
    comm.ireduce_scatter_sum(send, counts, recv).wait();
    std::size_t first = 0;
    for (int r = 0; r < comm.rank(); ++r) first += counts[static_cast<std::size_t>(r)];
    expect(recv.size() == counts[static_cast<std::size_t>(comm.rank())], "reduce-scatter: the rank's part length", n,
           recv.size());
    for (std::size_t k = 0; k < recv.size(); ++k) {
        Word sum = 0;
        for (int r = 0; r < R; ++r) sum += element(r, first + k);
        expect(recv[k] == sum,
               sizeof(Word) == 4 ? "reduce-scatter sums the rank's part (32-bit)"
                                 : "reduce-scatter sums the rank's part (64-bit)",
               n, k);
    }
}

void check_distributed(const Communicator& comm, std::size_t n) {
    const int R = comm.size();
    check_reduce_scatter<std::uint32_t>(comm, n);
    check_reduce_scatter<std::uint64_t>(comm, n);
    std::vector<std::uint64_t> sum(n);
    for (std::size_t i = 0; i < n; ++i) sum[i] = value(comm.rank(), i);
    comm.allreduce_sum(sum);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t want = 0;
        for (int r = 0; r < R; ++r) want += value(r, i);
        expect(sum[i] == want, "allreduce_sum on every rank", n, i);
    }
    std::vector<std::size_t> counts(static_cast<std::size_t>(R));
    for (int r = 0; r < R; ++r) counts[static_cast<std::size_t>(r)] = part_length(n, r);
    std::vector<double> mine(counts[static_cast<std::size_t>(comm.rank())]), all;
    for (std::size_t k = 0; k < mine.size(); ++k) mine[k] = comm.rank() + 0.25 * static_cast<double>(k);
    comm.gather_to_root(std::span<const double>(mine), counts, all);
    if (!comm.is_root()) return;
    std::size_t at = 0;
    for (int r = 0; r < R; ++r)
        for (std::size_t k = 0; k < counts[static_cast<std::size_t>(r)]; ++k, ++at)
            expect(at < all.size() && all[at] == r + 0.25 * static_cast<double>(k), "gather_to_root in rank order", n,
                   at);
    expect(at == all.size(), "gather_to_root: every part and nothing else", n, all.size());
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);
    comm.set_max_elements_per_call(7);
    const int R = comm.size();
    if (comm.is_root()) check_pieces();
    for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{8}, std::size_t{1000}}) {
        std::vector<std::uint64_t> send(n), recv;
        for (std::size_t i = 0; i < n; ++i) send[i] = value(comm.rank(), i);
        comm.ireduce_sum_to_root(send, recv).wait();
        if (comm.is_root()) {
            expect(recv.size() == n, "the reduced array has the sent length", n, recv.size());
            for (std::size_t i = 0; i < n && i < recv.size(); ++i) {
                std::uint64_t sum = 0;
                for (int r = 0; r < R; ++r) sum += value(r, i);
                expect(recv[i] == sum, "ireduce_sum_to_root sums every rank's element", n, i);
            }
        }
        check_distributed(comm, n);
        std::vector<double> b(n);
        for (std::size_t i = 0; i < n; ++i) b[i] = comm.is_root() ? 0.5 * static_cast<double>(i) : -1.0;
        comm.broadcast(b);
        for (std::size_t i = 0; i < n; ++i) expect(b[i] == 0.5 * static_cast<double>(i), "broadcast", n, i);
        std::vector<std::uint64_t> bits(n);
        for (std::size_t i = 0; i < n; ++i)
            bits[i] = std::uint64_t{1} << ((i + static_cast<std::size_t>(comm.rank())) % 64);
        comm.allreduce_or(bits);
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t want = 0;
            for (int r = 0; r < R; ++r) want |= std::uint64_t{1} << ((i + static_cast<std::size_t>(r)) % 64);
            expect(bits[i] == want, "allreduce_or", n, i);
        }
    }
    const std::uint64_t worst = comm.allreduce_max(static_cast<std::uint64_t>(failures));
    if (comm.is_root()) std::printf("communicator_mpi_test: %d ranks, %s\n", R, worst == 0 ? "all agree" : "FAILED");
    return worst == 0 ? 0 : 1;
}
