#include "luxtrace/run/reduction_message.hpp"

#include <stdexcept>

namespace luxtrace {

std::size_t ReductionMessage::word_count(int ranks, std::size_t replicates) {
    return 2 * static_cast<std::size_t>(ranks) + RankFlags::kWords + replicates;
}

void ReductionMessage::encode(std::vector<std::uint64_t>& words) const {
    words.resize(word_count(static_cast<int>(progress.size()), replicate_photons.size()));
    std::uint64_t* w = words.data();
    for (const RankProgress& p : progress) {
        *w++ = p.items_done;
        *w++ = p.prefix;
    }
    *w++ = flags.signalled;
    *w++ = flags.idle;
    *w++ = flags.input_fault;
    *w++ = flags.internal_fault;
    *w++ = flags.wide;
    for (const std::uint64_t n : replicate_photons) *w++ = n;
}

ReductionMessage ReductionMessage::decode(std::span<const std::uint64_t> words, int ranks, std::size_t replicates) {
    if (words.size() != word_count(ranks, replicates))
        throw std::logic_error("ReductionMessage::decode: the words do not fit the rank and replicate counts");
    ReductionMessage m;
    const std::uint64_t* w = words.data();
    m.progress.resize(static_cast<std::size_t>(ranks));
    for (RankProgress& p : m.progress) {
        p.items_done = *w++;
        p.prefix = *w++;
    }
    m.flags.signalled = *w++;
    m.flags.idle = *w++;
    m.flags.input_fault = *w++;
    m.flags.internal_fault = *w++;
    m.flags.wide = *w++;
    m.replicate_photons.assign(w, w + replicates);
    return m;
}

}  // namespace luxtrace
