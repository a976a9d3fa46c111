#pragma once
// What every rank sends to rank 0's sum at a reduction, with names. On the wire it is one
// flat array of words, summed element-wise (Communicator::ireduce_sum_to_root):
//
//   [ tallies (TallyLayout order) | items_done, prefix of rank 0 .. R-1 | flags ]
//
// A rank writes its progress into its own two words and zeros into the others', so the sum
// holds every rank's progress; each flag is 0 or 1 per rank, so the sum counts the ranks
// that raised it. With several ranks the words go out without those zero on every rank
// (the sides no rank has lit, the detector blocks no rank has written: message_packing.hpp). To add a field: a member
// here, its words in word_count, encode and decode, and a case in tests/run_control_test.cpp.
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
    static constexpr std::size_t kWords = 4;
};

struct ReductionMessage {
    std::span<const std::uint64_t> tallies;  // the flat tally array
    std::vector<RankProgress> progress;      // one per rank (a rank's own message: the others zero)
    RankFlags flags;

    static std::size_t word_count(std::size_t tally_words, int ranks);
    // Writes the words (resizing `words` to word_count, without reallocating a buffer of
    // that size already).
    void encode(std::vector<std::uint64_t>& words) const;
    // The fields of `words` as encode wrote them (or their sum over ranks); `tallies` views
    // `words`, which must outlive the message.
    static ReductionMessage decode(std::span<const std::uint64_t> words, std::size_t tally_words, int ranks);
};

}  // namespace luxtrace
