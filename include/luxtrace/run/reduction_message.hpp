#pragma once
// What every rank adds to a reduction besides its tallies' counts, with names. On the wire
// it is one short array of words, summed element-wise over the ranks onto every rank
// (Communicator::allreduce_sum):
//
//   [ items_done, prefix of rank 0 .. R-1 | flags | photons of replicate 0 .. Q-1 ]
//
// A rank writes its progress into its own two words and zeros into the others', so the sum
// holds every rank's progress; each flag is 0 or 1 per rank, so the sum counts the ranks
// that raised it; the replicate photons (sobol) are the rank's own since the run began,
// so the sum is the run's. Every rank needs these to sum its share of the map
// (RunLoop::reduce): the photons N and each replicate's. The counts themselves travel apart
// (message_packing.hpp). To add a field: a member here, its words in word_count, encode and
// decode, and a case in tests/run_control_test.cpp.
#include "luxtrace/run/work_plan.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

struct RankFlags {
    std::uint64_t signalled = 0;       // SIGTERM / SIGUSR1 seen: checkpoint and stop
    std::uint64_t idle = 0;            // out of work: its share of the budget is traced
    std::uint64_t input_fault = 0;     // a tracing thread threw an InputError
    std::uint64_t internal_fault = 0;  // a tracing thread threw anything else
    // The rank's counts since the previous reduction did not all fit 32 bits with room for
    // the sum over the ranks: the map travels as 64-bit words this time.
    std::uint64_t wide = 0;
    static constexpr std::size_t kWords = 5;
};

struct ReductionMessage {
    std::vector<RankProgress> progress;  // one per rank (a rank's own message: the others zero)
    RankFlags flags;
    std::vector<std::uint64_t> replicate_photons;  // one per replicate (sobol), since the run began

    static std::size_t word_count(int ranks, std::size_t replicates);
    // Writes the words (resizing `words` to word_count).
    void encode(std::vector<std::uint64_t>& words) const;
    // The fields of `words` as encode wrote them (or their sum over ranks).
    static ReductionMessage decode(std::span<const std::uint64_t> words, int ranks, std::size_t replicates);
};

}  // namespace luxtrace
