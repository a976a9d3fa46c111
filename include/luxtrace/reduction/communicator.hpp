#pragma once
// The only door to MPI. Everything here moves plain arrays; no physics type appears.
#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

class Communicator {
public:
    // Initialises MPI (a plain process without mpirun is a 1-rank world).
    Communicator(int* argc, char*** argv);
    ~Communicator();
    Communicator(const Communicator&) = delete;
    Communicator& operator=(const Communicator&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool is_root() const { return rank_ == 0; }

    // Element-wise sum of `data` over all ranks into rank 0's `data` (exact: integers).
    void reduce_sum_to_root(std::vector<std::uint64_t>& data) const;
    std::uint64_t allreduce_max(std::uint64_t v) const;
    double allreduce_max(double v) const;
    int broadcast(int v) const;
    void barrier() const;
    double wtime() const;
    // Ends every rank at once (after an error that only this rank saw).
    [[noreturn]] void abort(int code) const;

private:
    int rank_ = 0;
    int size_ = 1;
};

}  // namespace luxtrace
