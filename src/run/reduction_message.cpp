#include "luxtrace/run/reduction_message.hpp"

#include <algorithm>
#include <stdexcept>

namespace luxtrace {

std::size_t ReductionMessage::word_count(std::size_t tally_words, int ranks) {
    return tally_words + 2 * static_cast<std::size_t>(ranks) + RankFlags::kWords;
}

void ReductionMessage::encode(std::vector<std::uint64_t>& words) const {
    const std::size_t S = tallies.size();
    words.resize(word_count(S, static_cast<int>(progress.size())));
    std::copy(tallies.begin(), tallies.end(), words.begin());
    std::uint64_t* w = words.data() + S;
    for (const RankProgress& p : progress) {
        *w++ = p.items_done;
        *w++ = p.prefix;
    }
    *w++ = flags.signalled;
    *w++ = flags.idle;
    *w++ = flags.input_fault;
    *w++ = flags.internal_fault;
}

ReductionMessage ReductionMessage::decode(std::span<const std::uint64_t> words, std::size_t tally_words, int ranks) {
    if (words.size() != word_count(tally_words, ranks))
        throw std::logic_error("ReductionMessage::decode: the words do not fit the layout and rank count");
    ReductionMessage m;
    m.tallies = words.first(tally_words);
    const std::uint64_t* w = words.data() + tally_words;
    m.progress.resize(static_cast<std::size_t>(ranks));
    for (RankProgress& p : m.progress) {
        p.items_done = *w++;
        p.prefix = *w++;
    }
    m.flags.signalled = *w++;
    m.flags.idle = *w++;
    m.flags.input_fault = *w++;
    m.flags.internal_fault = *w++;
    return m;
}

}  // namespace luxtrace
