#pragma once
// A reduction message without the words that are zero on every rank.
//
// A message is the flat tally array (TallyLayout order), possibly followed by a few other
// words (progress, flags). Two kinds of words are mostly zero: the slots of triangle sides
// no photon has reached (the back of a closed room's walls), and, after the surface map,
// detector words (an annual run keeps three words per cell and light group, thousands of
// groups; the sun groups reach few cells, the direct counts of most patches are zero). A
// rank marks the sides it has lit and the 8-word blocks after the surface map it holds
// anything in; the marks are OR-ed over the ranks, and every rank sends only the marked
// words, in message order. A word unmarked on every rank is zero on every rank, so its sum
// is zero and unpacking restores the summed message exactly, whatever was left out.
#include "luxtrace/tally/tally.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

// Words after the surface map are kept or left out by blocks of this many (a cache line).
inline constexpr std::size_t kMessageBlockWords = 8;

// The mask of a message of `message_words` words: one bit per side (word i / 64, bit
// i % 64), then, from word mask_side_words(layout) on, one bit per block after the
// surface map. Its words are OR-ed over the ranks as they are.
std::size_t mask_side_words(const TallyLayout& layout);
std::size_t mask_words(const TallyLayout& layout, std::size_t message_words);
std::vector<std::uint64_t> message_mask(const TallyLayout& layout, std::span<const std::uint64_t> message);
// The length of a message packed under `mask`.
std::size_t packed_size(const TallyLayout& layout, std::span<const std::uint64_t> mask, std::size_t message_words);
// `packed` is resized to packed_size (without reallocating a buffer of that size already).
void pack_message(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                  std::span<const std::uint64_t> message, std::vector<std::uint64_t>& packed);
// `message` must have the full length; it is overwritten (the left-out words with zeros).
void unpack_message(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                    std::span<const std::uint64_t> packed, std::span<std::uint64_t> message);

}  // namespace luxtrace
