#pragma once
// A reduction message without the words that are zero on every rank, and the parts of it
// each rank owns in a distributed reduction.
//
// A message is the flat tally array (TallyLayout order), possibly followed by a few other
// words. Two kinds of words are mostly zero: the slots of triangle sides no photon has
// reached (the back of a closed room's walls), and, after the surface map, detector words
// (an annual run keeps three words per cell and light group, thousands of groups; the sun
// groups reach few cells, the direct counts of most patches are zero). A rank marks the
// sides it has lit and the 8-word blocks after the surface map it holds anything in; the
// marks are OR-ed over the ranks, and every rank sends only the marked words. A word
// unmarked on every rank is zero on every rank, so its sum is zero and unpacking restores
// the summed message exactly, whatever was left out.
//
// The sides are cut into chunks of kSidesPerChunk: H chunks of the front sides, then H of
// the back sides (H = ceil(T / kSidesPerChunk)). A MessagePart is two runs of chunks, one
// of fronts and one of backs (each side's counts, repeats and replicate arrivals, which lie
// in three separate runs of the layout), and optionally the head (the photon fates'
// counters) and the tail (everything after the surface map). In a distributed reduction
// (docs/RUN_CONTROL.md) rank r owns front chunks [r H / R, (r + 1) H / R) and the backs of
// the same triangles, so that a closed model's lit fronts are shared evenly; rank 0 also
// owns the head and the tail.
#include "luxtrace/tally/tally.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace luxtrace {

// Words after the surface map are kept or left out by blocks of this many (a cache line).
inline constexpr std::size_t kMessageBlockWords = 8;
// Sides per chunk: the unit a rank owns, and the unit of the global estimate's partial
// sums (stats/global_sums.hpp), whatever the rank count.
inline constexpr std::size_t kSidesPerChunk = 4096;

struct ChunkRange {
    std::size_t begin = 0, end = 0;  // chunks [begin, end)
    std::size_t size() const { return end - begin; }
};

std::size_t chunk_count(const TallyLayout& layout);  // 2 H
// The sides [first, second) of chunk c.
std::pair<std::size_t, std::size_t> chunk_sides(const TallyLayout& layout, std::size_t chunk);

struct MessagePart {
    ChunkRange fronts, backs;
    bool head_and_tail = false;
    std::size_t chunks() const { return fronts.size() + backs.size(); }
    // Every word of the message.
    static MessagePart whole(const TallyLayout& layout);
    static MessagePart head_and_tail_only() { return {{}, {}, true}; }
};
// The sides rank `rank` of `ranks` owns, without the head and tail.
MessagePart owned_sides(const TallyLayout& layout, int rank, int ranks);

// The mask of a message of `message_words` words: one bit per side (word i / 64, bit
// i % 64), then, from word mask_side_words(layout) on, one bit per block after the
// surface map. Its words are OR-ed over the ranks as they are. Only the bits of `part`
// are set; `map_bits`, when given, receives the OR of every word of the part's sides (a
// bound on the largest: below 2^k when it is).
std::size_t mask_side_words(const TallyLayout& layout);
std::size_t mask_words(const TallyLayout& layout, std::size_t message_words);
std::vector<std::uint64_t> message_mask(const TallyLayout& layout, std::span<const std::uint64_t> message);
std::vector<std::uint64_t> message_mask(const TallyLayout& layout, std::span<const std::uint64_t> message,
                                        const MessagePart& part, std::uint64_t* map_bits = nullptr);

// The length of `part` of a message packed under `mask`.
std::size_t packed_size(const TallyLayout& layout, std::span<const std::uint64_t> mask, std::size_t message_words,
                        const MessagePart& part);
// Writes the marked words of `part` to `out` (packed_size of them, as Word: uint32_t or
// uint64_t; a narrower Word must hold every value) and returns the end.
template <class Word>
Word* pack_part(const TallyLayout& layout, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> message,
                const MessagePart& part, Word* out);
// pack_part, zeroing each packed word of `message` that is not zero already (so that pages
// of words this rank never wrote stay unwritten): a rank's counts handed over and cleared
// in one pass.
template <class Word>
Word* take_part(const TallyLayout& layout, std::span<const std::uint64_t> mask, std::span<std::uint64_t> message,
                const MessagePart& part, Word* out);
// Adds the packed words of `part` to the words of `message` they came from.
template <class Word>
void add_packed_part(const TallyLayout& layout, std::span<const std::uint64_t> mask, const MessagePart& part,
                     std::span<const Word> packed, std::span<std::uint64_t> message);
// One rank's reduction (it owns every word): adds every word of `from` to `to` and zeroes
// it, in one pass that touches only the sides with counts and the blocks after the surface
// map that hold anything; the sides with counts are marked in `lit` (mask_side_words).
void add_and_clear(const TallyLayout& layout, std::span<std::uint64_t> from, std::span<std::uint64_t> to,
                   std::span<std::uint64_t> lit);
// Sets the words of `part` from its packed words, the left-out ones to zero.
void unpack_part(const TallyLayout& layout, std::span<const std::uint64_t> mask, const MessagePart& part,
                 std::span<const std::uint64_t> packed, std::span<std::uint64_t> message);

// The whole message: `packed` is resized to packed_size (without reallocating a buffer of
// that size already); `message` must have the full length and is overwritten.
std::size_t packed_size(const TallyLayout& layout, std::span<const std::uint64_t> mask, std::size_t message_words);
void pack_message(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                  std::span<const std::uint64_t> message, std::vector<std::uint64_t>& packed);
void unpack_message(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                    std::span<const std::uint64_t> packed, std::span<std::uint64_t> message);

}  // namespace luxtrace
