#include "luxtrace/tally/message_packing.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace luxtrace {

namespace {

bool bit(std::span<const std::uint64_t> mask, std::size_t i) { return ((mask[i / 64] >> (i % 64)) & 1u) != 0; }
void set_bit(std::span<std::uint64_t> mask, std::size_t i) { mask[i / 64] |= std::uint64_t{1} << (i % 64); }

// The OR of `count` words from `words`: zero exactly when they all are.
std::uint64_t or_of(const std::uint64_t* words, std::size_t count) {
    std::uint64_t any = 0;
    for (std::size_t k = 0; k < count; ++k) any |= words[k];
    return any;
}

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
std::size_t run_begin(const TallyLayout& L, int run, std::size_t side) {
    return run == 0 ? L.counts_begin(side) : run == 1 ? L.repeats_begin(side) : L.replicas_begin(side);
}

// Calls `f(side)` for every side of `part`'s chunks, in chunk order.
template <class F>
void for_each_side(const TallyLayout& L, const MessagePart& part, F&& f) {
    for (const ChunkRange& r : {part.fronts, part.backs})
        if (r.size() > 0) {
            const std::size_t begin = chunk_sides(L, r.begin).first, end = chunk_sides(L, r.end - 1).second;
            for (std::size_t i = begin; i < end; ++i) f(i);
        }
}

// Hands `part` of the message to `visit(begin, count, kept)` as ranges: the head, each
// run of the part's sides (counts, repeats, replicate arrivals), then the blocks after
// the surface map; adjacent ranges of the same kind merged.
template <class Visit>
void for_each_range(const TallyLayout& L, std::span<const std::uint64_t> mask, std::size_t message_words,
                    const MessagePart& part, Visit&& visit) {
    const std::size_t C = chunk_count(L);
    if (message_words < L.surface_end() || mask.size() != mask_words(L, message_words) || part.fronts.end > C ||
        part.backs.end > C || part.fronts.begin > part.fronts.end || part.backs.begin > part.backs.end)
        throw std::logic_error("message packing: the message, its mask or the part does not fit the layout");
    std::size_t begin = 0, end = 0;
    bool kept = true;
    auto add = [&](std::size_t at, std::size_t count, bool keep) {
        if (count == 0) return;
        if (end > begin && (keep != kept || at != end)) {
            visit(begin, end - begin, kept);
            begin = end = at;
        }
        if (end == begin) begin = end = at;
        kept = keep;
        end += count;
    };
    if (part.head_and_tail) add(0, L.counts_begin(0), true);
    for (int run = 0; run < kRuns; ++run) {
        const std::size_t n = run_length(L, run);
        for_each_side(L, part, [&](std::size_t i) { add(run_begin(L, run, i), n, bit(mask, i)); });
    }
    if (part.head_and_tail) {
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
                const std::size_t at = L.surface_end() + b * kMessageBlockWords;
                add(at, std::min(run * kMessageBlockWords, message_words - at), keep);
                b += run;
                rest = run < 64 ? rest >> run : 0;
            }
        }
    }
    if (end > begin) visit(begin, end - begin, kept);
}

}  // namespace

namespace {
std::size_t half_chunks(const TallyLayout& L) { return (L.triangles() + kSidesPerChunk - 1) / kSidesPerChunk; }
}  // namespace

std::size_t chunk_count(const TallyLayout& L) { return 2 * half_chunks(L); }

std::pair<std::size_t, std::size_t> chunk_sides(const TallyLayout& L, std::size_t c) {
    const std::size_t H = half_chunks(L), T = L.triangles();
    const std::size_t side = c < H ? 0 : 1, k = c < H ? c : c - H;
    return {side * T + std::min(T, k * kSidesPerChunk), side * T + std::min(T, (k + 1) * kSidesPerChunk)};
}

MessagePart MessagePart::whole(const TallyLayout& L) {
    const std::size_t H = half_chunks(L);
    return {{0, H}, {H, 2 * H}, true};
}

MessagePart owned_sides(const TallyLayout& L, int rank, int ranks) {
    const std::size_t H = half_chunks(L), R = static_cast<std::size_t>(ranks), r = static_cast<std::size_t>(rank);
    const std::size_t c0 = r * H / R, c1 = (r + 1) * H / R;
    return {{c0, c1}, {H + c0, H + c1}, false};
}

std::size_t mask_side_words(const TallyLayout& L) { return (L.sides() + 63) / 64; }

std::size_t mask_words(const TallyLayout& L, std::size_t message_words) {
    return mask_side_words(L) + (tail_blocks(L, message_words) + 63) / 64;
}

std::vector<std::uint64_t> message_mask(const TallyLayout& L, std::span<const std::uint64_t> message) {
    return message_mask(L, message, MessagePart::whole(L));
}

std::vector<std::uint64_t> message_mask(const TallyLayout& L, std::span<const std::uint64_t> message,
                                        const MessagePart& part, std::uint64_t* map_bits) {
    std::vector<std::uint64_t> mask(mask_words(L, message.size()), 0);
    // A side with repeats or replicate arrivals has counts: its counts alone tell.
    const std::size_t n = run_length(L, 0);
    std::uint64_t bits = 0;
    for_each_side(L, part, [&](std::size_t i) {
        const std::uint64_t any = or_of(message.data() + L.counts_begin(i), n);
        if (any == 0) return;
        set_bit(mask, i);
        if (map_bits == nullptr) return;
        bits |= any;
        for (int run = 1; run < kRuns; ++run) bits |= or_of(message.data() + run_begin(L, run, i), run_length(L, run));
    });
    if (map_bits != nullptr) *map_bits = bits;
    if (!part.head_and_tail) return mask;
    const std::span<std::uint64_t> blocks = std::span(mask).subspan(mask_side_words(L));
    const std::size_t tail = L.surface_end();
    for (std::size_t b = 0; b < tail_blocks(L, message.size()); ++b) {
        const std::size_t from = tail + b * kMessageBlockWords;
        if (or_of(message.data() + from, std::min(message.size() - from, kMessageBlockWords)) != 0) set_bit(blocks, b);
    }
    return mask;
}

std::size_t packed_size(const TallyLayout& L, std::span<const std::uint64_t> mask, std::size_t message_words,
                        const MessagePart& part) {
    std::size_t size = 0;
    for_each_range(L, mask, message_words, part,
                   [&](std::size_t, std::size_t count, bool kept) { size += kept ? count : 0; });
    return size;
}

template <class Word>
Word* pack_part(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> message,
                const MessagePart& part, Word* out) {
    for_each_range(L, mask, message.size(), part, [&](std::size_t begin, std::size_t count, bool kept) {
        if (!kept) return;
        if constexpr (sizeof(Word) == sizeof(std::uint64_t)) {
            std::memcpy(out, message.data() + begin, count * sizeof(std::uint64_t));
            out += count;
        } else {
            for (std::size_t k = 0; k < count; ++k) *out++ = static_cast<Word>(message[begin + k]);
        }
    });
    return out;
}

template <class Word>
Word* take_part(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<std::uint64_t> message,
                const MessagePart& part, Word* out) {
    for_each_range(L, mask, message.size(), part, [&](std::size_t begin, std::size_t count, bool kept) {
        if (!kept) return;
        std::uint64_t* w = message.data() + begin;
        for (std::size_t k = 0; k < count; ++k) {
            *out++ = static_cast<Word>(w[k]);
            if (w[k] != 0) w[k] = 0;
        }
    });
    return out;
}

template <class Word>
void add_packed_part(const TallyLayout& L, std::span<const std::uint64_t> mask, const MessagePart& part,
                     std::span<const Word> packed, std::span<std::uint64_t> message) {
    if (packed.size() != packed_size(L, mask, message.size(), part))
        throw std::logic_error("add_packed_part: the packed words do not fit the mask");
    const Word* in = packed.data();
    for_each_range(L, mask, message.size(), part, [&](std::size_t begin, std::size_t count, bool kept) {
        if (!kept) return;
        std::uint64_t* w = message.data() + begin;
        for (std::size_t k = 0; k < count; ++k) w[k] += in[k];
        in += count;
    });
}

template std::uint32_t* pack_part(const TallyLayout&, std::span<const std::uint64_t>, std::span<const std::uint64_t>,
                                  const MessagePart&, std::uint32_t*);
template std::uint64_t* pack_part(const TallyLayout&, std::span<const std::uint64_t>, std::span<const std::uint64_t>,
                                  const MessagePart&, std::uint64_t*);
template std::uint32_t* take_part(const TallyLayout&, std::span<const std::uint64_t>, std::span<std::uint64_t>,
                                  const MessagePart&, std::uint32_t*);
template std::uint64_t* take_part(const TallyLayout&, std::span<const std::uint64_t>, std::span<std::uint64_t>,
                                  const MessagePart&, std::uint64_t*);
template void add_packed_part(const TallyLayout&, std::span<const std::uint64_t>, const MessagePart&,
                              std::span<const std::uint32_t>, std::span<std::uint64_t>);
template void add_packed_part(const TallyLayout&, std::span<const std::uint64_t>, const MessagePart&,
                              std::span<const std::uint64_t>, std::span<std::uint64_t>);

void unpack_part(const TallyLayout& L, std::span<const std::uint64_t> mask, const MessagePart& part,
                 std::span<const std::uint64_t> packed, std::span<std::uint64_t> message) {
    if (packed.size() != packed_size(L, mask, message.size(), part))
        throw std::logic_error("unpack_part: the packed words do not fit the mask");
    const std::uint64_t* in = packed.data();
    for_each_range(L, mask, message.size(), part, [&](std::size_t begin, std::size_t count, bool kept) {
        if (kept) {
            std::memcpy(message.data() + begin, in, count * sizeof(std::uint64_t));
            in += count;
        } else std::fill_n(message.begin() + static_cast<std::ptrdiff_t>(begin), count, 0);
    });
}

void add_and_clear(const TallyLayout& L, std::span<std::uint64_t> from, std::span<std::uint64_t> to,
                   std::span<std::uint64_t> lit) {
    if (from.size() != to.size() || from.size() < L.surface_end() || lit.size() < mask_side_words(L))
        throw std::logic_error("add_and_clear: the arrays do not fit the layout");
    auto move = [&](std::size_t begin, std::size_t count) {
        for (std::size_t k = begin; k < begin + count; ++k) {
            to[k] += from[k];
            from[k] = 0;
        }
    };
    move(0, L.counts_begin(0));
    const std::size_t n = run_length(L, 0);
    for_each_side(L, MessagePart::whole(L), [&](std::size_t i) {
        if (or_of(from.data() + L.counts_begin(i), n) == 0) return;
        set_bit(lit, i);
        for (int run = 0; run < kRuns; ++run) move(run_begin(L, run, i), run_length(L, run));
    });
    for (std::size_t b = L.surface_end(); b < from.size(); b += kMessageBlockWords) {
        const std::size_t count = std::min(from.size() - b, kMessageBlockWords);
        if (or_of(from.data() + b, count) != 0) move(b, count);
    }
}

std::size_t packed_size(const TallyLayout& L, std::span<const std::uint64_t> mask, std::size_t message_words) {
    return packed_size(L, mask, message_words, MessagePart::whole(L));
}

void pack_message(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> message,
                  std::vector<std::uint64_t>& packed) {
    packed.resize(packed_size(L, mask, message.size()));
    pack_part(L, mask, message, MessagePart::whole(L), packed.data());
}

void unpack_message(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> packed,
                    std::span<std::uint64_t> message) {
    unpack_part(L, mask, MessagePart::whole(L), packed, message);
}

}  // namespace luxtrace
