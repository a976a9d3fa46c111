// Reduction messages without the words zero on every rank: the sum of the packed messages
// of several ranks unpacks to the sum of their full messages, word for word, and only the
// sides and blocks some rank has written are sent.
#include "luxtrace/tally/message_packing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace luxtrace;

namespace {

std::vector<std::uint64_t> or_of(std::vector<std::vector<std::uint64_t>> masks) {
    std::vector<std::uint64_t> all = masks.front();
    for (const auto& m : masks)
        for (std::size_t w = 0; w < all.size(); ++w) all[w] |= m[w];
    return all;
}

// What rank 0 holds after the reduction of `messages` packed under their OR-ed masks.
std::vector<std::uint64_t> reduce_packed(const TallyLayout& L, const std::vector<std::vector<std::uint64_t>>& messages,
                                         std::vector<std::uint64_t>& mask, std::size_t& packed_words) {
    std::vector<std::vector<std::uint64_t>> masks;
    for (const auto& m : messages) masks.push_back(message_mask(L, m));
    mask = or_of(masks);
    std::vector<std::uint64_t> sum, packed;
    for (const auto& m : messages) {
        pack_message(L, mask, m, packed);
        if (sum.empty()) sum.assign(packed.size(), 0);
        EXPECT_EQ(packed.size(), sum.size()) << "every rank packs alike";
        for (std::size_t i = 0; i < sum.size() && i < packed.size(); ++i) sum[i] += packed[i];
    }
    packed_words = sum.size();
    std::vector<std::uint64_t> out(messages.front().size(), 12345);  // overwritten everywhere
    unpack_message(L, mask, sum, out);
    return out;
}

}  // namespace

TEST(MessagePacking, LeavesOutUnlitSidesAndRestoresTheMessageExactly) {
    // 50 triangles, 2 bands, a detector, 3 trailing words (progress and flags of the run's
    // message). Some sides are lit on "rank" a, others on b; the OR of their masks packs
    // both messages alike, the sum of the packed messages unpacks to the sum of the full ones.
    const TallyLayout L(50, 2, {6});
    std::mt19937_64 g(7);
    auto message = [&](int lit_every) {
        std::vector<std::uint64_t> m(L.size() + 3, 0);
        for (std::size_t c = 0; c < TallyLayout::kCounters; ++c) m[c] = g() % 100;
        for (std::size_t i = 0; i < L.sides(); i += static_cast<std::size_t>(lit_every))
            m[L.counts_begin(i) + g() % (L.bands() * TallyLayout::kCountSlots)] = 1 + g() % 1000;
        for (std::size_t i = 0; i < L.sides(); i += static_cast<std::size_t>(2 * lit_every))
            m[L.repeats_begin(i) + g() % L.bands()] = 2 * (1 + g() % 100);  // some lit sides have repeats
        for (std::size_t i = L.surface_end(); i < m.size(); ++i) m[i] = g() % 50;
        return m;
    };
    const std::vector<std::uint64_t> a = message(3), b = message(5);
    const std::vector<std::uint64_t> mask_a = message_mask(L, a), mask_b = message_mask(L, b);
    std::size_t lit = 0;
    for (std::size_t i = 0; i < L.sides(); ++i) {
        const bool in_a = i % 3 == 0, in_b = i % 5 == 0;
        EXPECT_EQ((mask_a[i / 64] >> (i % 64)) & 1u, in_a ? 1u : 0u) << "side " << i;
        EXPECT_EQ((mask_b[i / 64] >> (i % 64)) & 1u, in_b ? 1u : 0u) << "side " << i;
        lit += in_a || in_b;
    }
    std::vector<std::uint64_t> mask;
    std::size_t packed_words = 0;
    const std::vector<std::uint64_t> out = reduce_packed(L, {a, b}, mask, packed_words);
    // Every block after the surface map holds a nonzero word (8 words below 50: 1 in 4e13).
    EXPECT_EQ(packed_words, a.size() - (L.sides() - lit) * L.side_slots());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(out[i], a[i] + b[i]) << "word " << i;
}

TEST(MessagePacking, AnnualDetectorsSendOnlyTheBlocksSomeRankWrote) {
    // An annual layout in small: 300 light groups (100 sky patches, 200 suns), direct
    // counts, two detectors, 3 trailing words (so the last block is short). Each rank has
    // written the sky patches' n_c and q_c in most cells, few suns' and few direct counts,
    // as a side-lit room's sensors would.
    const std::size_t G = 300, patches = 100;
    const TallyLayout L(4, TallyDims{1, G, 1, 0, true, {}, {}, 0}, {10, 3});
    const std::size_t words = L.size() + 3;
    ASSERT_NE((words - L.surface_end()) % kMessageBlockWords, 0u);
    auto message = [&](unsigned seed) {
        std::mt19937_64 g(seed);
        std::vector<std::uint64_t> m(words, 0);
        m[TallyLayout::kEscaped] = 1 + g() % 100;
        m[L.counts_begin(1)] = 3;
        for (std::size_t d = 0; d < L.detector_count(); ++d)
            for (std::size_t c = 0; c < (d == 0 ? 10u : 3u); ++c)
                for (std::size_t gr = 0; gr < G; ++gr) {
                    if (g() % 100 < (gr < patches ? 60u : 2u)) {
                        m[L.detector_n(d, c, 0, gr)] = 1 + g() % 9;
                        m[L.detector_q(d, c, 0, gr)] = 1 + g() % 99;
                    }
                    if (g() % 100 < 3) m[L.detector_direct(d, c, gr)] = 1;
                }
        for (std::size_t i = L.size(); i < words; ++i) m[i] = g() % 3;
        return m;
    };
    const std::vector<std::vector<std::uint64_t>> ranks = {message(1), message(2), message(3)};
    std::vector<std::uint64_t> mask;
    std::size_t packed_words = 0;
    const std::vector<std::uint64_t> out = reduce_packed(L, ranks, mask, packed_words);
    for (std::size_t i = 0; i < words; ++i) ASSERT_EQ(out[i], ranks[0][i] + ranks[1][i] + ranks[2][i]) << "word " << i;
    // Sent: the counters, the one lit side, and every block after the surface map some rank
    // wrote in.
    std::size_t want = L.counts_begin(0) + L.side_slots();
    for (std::size_t from = L.surface_end(); from < words; from += kMessageBlockWords) {
        bool any = false;
        for (std::size_t i = from; i < std::min(words, from + kMessageBlockWords); ++i)
            for (const auto& r : ranks) any = any || r[i] != 0;
        if (any) want += std::min(kMessageBlockWords, words - from);
    }
    EXPECT_EQ(packed_words, want);
    EXPECT_LT(packed_words, words / 2) << "the suns' and direct blocks are mostly left out";
    EXPECT_EQ(packed_size(L, mask, words), packed_words);
}

TEST(MessagePacking, NothingWrittenSendsTheCountersAndTheTrailingWordsOnly) {
    const TallyLayout L(6, TallyDims{2, 50, 1, 0, true, {}, {}, 0}, {20});
    std::vector<std::uint64_t> m(L.size() + 4, 0);
    m[TallyLayout::kAbsorbed] = 5;
    m[L.size() + 1] = 7;  // a rank's progress
    std::vector<std::uint64_t> mask;
    std::size_t packed_words = 0;
    const std::vector<std::uint64_t> out = reduce_packed(L, {m, m}, mask, packed_words);
    EXPECT_EQ(packed_words, L.counts_begin(0) + kMessageBlockWords);  // the block holding the progress
    for (std::size_t i = 0; i < m.size(); ++i) ASSERT_EQ(out[i], 2 * m[i]) << "word " << i;
}
