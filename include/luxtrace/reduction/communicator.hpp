#pragma once
// The only door to MPI. Everything here moves plain arrays; no physics type appears.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace luxtrace {

// A sum-reduction in flight (MPI requests); the buffers must outlive it.
class PendingReduce {
public:
    struct Impl;
    explicit PendingReduce(std::unique_ptr<Impl> impl);
    // A reduction that needed no message (one rank).
    static PendingReduce completed();
    // Both in flight as one: complete when both are.
    static PendingReduce both(PendingReduce a, PendingReduce b);
    ~PendingReduce();
    PendingReduce(PendingReduce&&) noexcept;
    PendingReduce& operator=(PendingReduce&&) noexcept;
    // True once complete (then the root's receive buffer holds the sums).
    bool test();
    void wait();

private:
    std::unique_ptr<Impl> impl_;
};

class Communicator {
public:
    // Elements per MPI call: Open MPI 4.1 takes counts as int (no large-count collectives),
    // so longer arrays travel in pieces of at most this many elements.
    static constexpr std::size_t kMaxElementsPerCall = std::size_t{1} << 28;
    // The pieces [offset, offset + count) an array of n elements travels in.
    static std::vector<std::pair<std::size_t, int>> pieces(std::size_t n, std::size_t max_per_call);

    // Initialises MPI (a plain process without mpirun is a 1-rank world).
    Communicator(int* argc, char*** argv);
    ~Communicator();
    Communicator(const Communicator&) = delete;
    Communicator& operator=(const Communicator&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool is_root() const { return rank_ == 0; }
    // The nodes (sets of ranks sharing memory) of the run, and this rank's node's index when
    // it leads its node (the node's first rank), else -1. Rank 0 leads node 0.
    int nodes() const { return nodes_; }
    int node_index() const { return node_index_; }

    // Non-blocking: `recv` (rank 0 only, resized there) receives the element-wise sum of
    // every rank's `send`, which must stay untouched until the reduction completes.
    PendingReduce ireduce_sum_to_root(const std::vector<std::uint64_t>& send, std::vector<std::uint64_t>& recv) const;
    // Non-blocking reduce-scatter (MPI_Ireduce_scatter): `send` holds every rank's part in
    // rank order, counts[r] words for rank r (the same counts everywhere); `recv` (resized
    // to counts[rank]) receives the element-wise sum of this rank's part over the ranks.
    // Word: std::uint32_t or std::uint64_t. With more than max elements per call in all,
    // the parts travel in rounds, each from a copy of its pieces.
    template <class Word>
    PendingReduce ireduce_scatter_sum(const std::vector<Word>& send, const std::vector<std::size_t>& counts,
                                      std::vector<Word>& recv) const;
    // Element-wise sum over the ranks, in place (same length everywhere).
    void allreduce_sum(std::vector<std::uint64_t>& values) const;
    // Every rank's `send` (counts[r] words from rank r, the same counts everywhere) to
    // rank 0's `recv`, in rank order (resized there). Point to point, in pieces.
    template <class Word>
    void gather_to_root(std::span<const Word> send, const std::vector<std::size_t>& counts,
                        std::vector<Word>& recv) const;
    // The mirror of gather_to_root: rank 0's `send` holds every rank's part in rank order
    // (counts[r] words for rank r, the same counts everywhere); each rank's `recv` (resized
    // to counts[rank]) gets its part. Point to point, in pieces.
    template <class Word>
    void scatter_from_root(std::span<const Word> send, const std::vector<std::size_t>& counts,
                           std::vector<Word>& recv) const;
    // Rank 0's values to every rank (same length everywhere).
    void broadcast(std::vector<double>& values) const;
    // Every rank holds its part of `values`, [offsets[rank], offsets[rank + 1]); afterwards
    // every rank holds every part (an all-gather in place).
    void allgather_parts(std::vector<double>& values, const std::vector<std::size_t>& offsets) const;
    std::uint64_t allreduce_max(std::uint64_t v) const;
    // Element-wise bitwise OR over the ranks, in place (same length everywhere).
    void allreduce_or(std::vector<std::uint64_t>& bits) const;
    double allreduce_max(double v) const;
    double wtime() const;
    // Ends every rank at once (after an error that only this rank saw).
    [[noreturn]] void abort(int code) const;
    // Tests: a smaller piece size, so that the pieces' bookkeeping is exercised on small arrays.
    void set_max_elements_per_call(std::size_t n) { max_per_call_ = n; }

private:
    // The point-to-point messages of gather_to_root and scatter_from_root, in pieces: on rank
    // 0 one exchange with each other rank r, at its part's place in rank 0's array (after
    // the earlier ranks' counts); on rank r one with rank 0, from its own words' start.
    // post(peer, at, count, request) posts a piece (a send or a receive); returns once all
    // are done.
    template <class Post>
    void root_pieces(const std::vector<std::size_t>& counts, Post post) const;

    int rank_ = 0;
    int size_ = 1;
    int nodes_ = 1;
    int node_index_ = 0;
    std::size_t max_per_call_ = kMaxElementsPerCall;
};

}  // namespace luxtrace
