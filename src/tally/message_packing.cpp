#include "luxtrace/tally/message_packing.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace luxtrace {

namespace {

bool bit(std::span<const std::uint64_t> mask, std::size_t i) { return ((mask[i / 64] >> (i % 64)) & 1u) != 0; }

std::size_t tail_blocks(const TallyLayout& L, std::size_t message_words) {
    return (message_words - L.surface_end() + kMessageBlockWords - 1) / kMessageBlockWords;
}

// A side's three runs of slots: its counts, its repeats and its replicate arrivals
// (TallyLayout::counts_begin and the next two).
constexpr int kRuns = 3;
std::size_t run_length(const TallyLayout& L, int run) {
    const std::size_t c = L.map_columns();
    return run == 0 ? c * TallyLayout::kCountSlots : run == 1 ? c : c * L.replicates();
}

// Hands the message to `visit(begin, count, kept)` as ranges in address order, adjacent
// ranges of the same kind merged: the counters, each side's three runs (the runs of all
// sides lie one after the other: counts, repeats, replicate arrivals), then the blocks
// after the surface map.
template <class Visit>
void for_each_range(const TallyLayout& L, std::span<const std::uint64_t> mask, std::size_t message_words,
                    Visit&& visit) {
    if (message_words < L.surface_end() || mask.size() != mask_words(L, message_words))
        throw std::logic_error("message packing: the message or its mask does not fit the layout");
    std::size_t begin = 0, end = 0;
    bool kept = true;
    auto add = [&](std::size_t count, bool keep) {
        if (count == 0) return;
        if (keep != kept && end > begin) {
            visit(begin, end - begin, kept);
            begin = end;
        }
        kept = keep;
        end += count;
    };
    add(L.counts_begin(0), true);
    for (int run = 0; run < kRuns; ++run)
        for (std::size_t i = 0; i < L.sides(); ++i) add(run_length(L, run), bit(mask, i));
    const std::span<const std::uint64_t> blocks = mask.subspan(mask_side_words(L));
    const std::size_t n = tail_blocks(L, message_words);
    for (std::size_t b = 0; b < n;) {
        const std::uint64_t w = blocks[b / 64];
        const std::size_t stop = std::min(n, b + 64 - b % 64);
        // b is a multiple of 64 here: step over each run of equal bits of w at once.
        for (std::uint64_t rest = w; b < stop;) {
            const bool keep = (rest & 1u) != 0;
            const std::size_t run = std::min<std::size_t>(stop - b,
                                                          static_cast<std::size_t>(keep ? std::countr_one(rest)
                                                                                        : std::countr_zero(rest)));
            add(run * kMessageBlockWords, keep);
            b += run;
            rest = run < 64 ? rest >> run : 0;
        }
    }
    end = std::min(end, message_words);  // the last block may be short
    if (end > begin) visit(begin, end - begin, kept);
}

}  // namespace

std::size_t mask_side_words(const TallyLayout& L) { return (L.sides() + 63) / 64; }

std::size_t mask_words(const TallyLayout& L, std::size_t message_words) {
    return mask_side_words(L) + (tail_blocks(L, message_words) + 63) / 64;
}

std::vector<std::uint64_t> message_mask(const TallyLayout& L, std::span<const std::uint64_t> message) {
    std::vector<std::uint64_t> mask(mask_words(L, message.size()), 0);
    // A side with repeats or replicate arrivals has counts: its counts alone tell.
    const std::size_t n = run_length(L, 0);
    for (std::size_t i = 0; i < L.sides(); ++i) {
        const std::uint64_t* s = message.data() + L.counts_begin(i);
        std::uint64_t any = 0;
        for (std::size_t k = 0; k < n; ++k) any |= s[k];
        if (any != 0) mask[i / 64] |= std::uint64_t{1} << (i % 64);
    }
    std::uint64_t* blocks = mask.data() + mask_side_words(L);
    const std::size_t tail = L.surface_end();
    for (std::size_t b = 0; b < tail_blocks(L, message.size()); ++b) {
        const std::size_t from = tail + b * kMessageBlockWords;
        const std::size_t to = std::min(message.size(), from + kMessageBlockWords);
        std::uint64_t any = 0;
        for (std::size_t k = from; k < to; ++k) any |= message[k];
        if (any != 0) blocks[b / 64] |= std::uint64_t{1} << (b % 64);
    }
    return mask;
}

std::size_t packed_size(const TallyLayout& L, std::span<const std::uint64_t> mask, std::size_t message_words) {
    std::size_t size = 0;
    for_each_range(L, mask, message_words,
                   [&](std::size_t, std::size_t count, bool kept) { size += kept ? count : 0; });
    return size;
}

void pack_message(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> message,
                  std::vector<std::uint64_t>& packed) {
    packed.resize(packed_size(L, mask, message.size()));
    std::uint64_t* out = packed.data();
    for_each_range(L, mask, message.size(), [&](std::size_t begin, std::size_t count, bool kept) {
        if (!kept) return;
        std::memcpy(out, message.data() + begin, count * sizeof(std::uint64_t));
        out += count;
    });
}

void unpack_message(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> packed,
                    std::span<std::uint64_t> message) {
    if (packed.size() != packed_size(L, mask, message.size()))
        throw std::logic_error("unpack_message: the packed words do not fit the mask");
    const std::uint64_t* in = packed.data();
    for_each_range(L, mask, message.size(), [&](std::size_t begin, std::size_t count, bool kept) {
        if (kept) {
            std::memcpy(message.data() + begin, in, count * sizeof(std::uint64_t));
            in += count;
        } else std::fill_n(message.begin() + static_cast<std::ptrdiff_t>(begin), count, 0);
    });
}

}  // namespace luxtrace
