// Tallies: layout indices are disjoint, and write-combining buffers flushed from many
// threads give exactly the serial sums (integers: order cannot matter).
#include "luxtrace/tally/tally.hpp"
#include "luxtrace/tally/photon_tally.hpp"

#include <gtest/gtest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <random>
#include <set>
#include <string>
#include <thread>

using namespace luxtrace;

TEST(TallyLayout, EveryIndexIsDistinctAndInRange) {
    // Every combination of the dimensions: replicates (random: 0, sobol: 4), light groups,
    // and the surface map per group or for all groups together (group_maps = false).
    struct Case {
        std::size_t groups, map_groups, replicates;
    };
    for (const Case k : {Case{1, 1, 0}, Case{1, 1, 4}, Case{3, 3, 0}, Case{3, 1, 4}, Case{2, 2, 2}}) {
        const std::size_t B = 3;
        const TallyLayout L(7, TallyDims{B, k.groups, k.map_groups, k.replicates, false, {}, {}, 0}, {4, 9});
        const std::string what = "groups " + std::to_string(k.groups) + ", map groups " + std::to_string(k.map_groups) +
                                 ", R " + std::to_string(k.replicates);
        std::set<std::size_t> seen;
        auto take = [&](std::size_t i) {
            EXPECT_LT(i, L.size()) << what;
            EXPECT_TRUE(seen.insert(i).second) << "index " << i << " used twice (" << what << ")";
        };
        for (std::size_t c = 0; c < TallyLayout::kCounters; ++c) take(c);
        for (std::size_t t = 0; t < 7; ++t)
            for (std::size_t side = 0; side < TallyLayout::kSides; ++side)
                for (std::size_t b = 0; b < B; ++b)
                    for (std::size_t g = 0; g < k.map_groups; ++g) {
                        const std::size_t n = L.side_index(t, side);
                        EXPECT_EQ(L.triangle_of(n), t);
                        const std::size_t col = L.map_column(b, g);
                        for (auto s : {TallyLayout::kCountOdd, TallyLayout::kCountEven, TallyLayout::kDirectOdd,
                                       TallyLayout::kDirectEven, TallyLayout::kRepeats}) {
                            const std::size_t i = L.surface(t, side, b, s, g);
                            take(i);
                            // Each side's counts are one run, its repeats another, its
                            // replicate arrivals a third (what the reduction packs); the
                            // counts of a side and column share a 32-byte aligned block.
                            const bool repeats = s == TallyLayout::kRepeats;
                            const std::size_t first = repeats ? L.repeats_begin(n) : L.counts_begin(n);
                            EXPECT_GE(i, first);
                            EXPECT_LT(i, first + L.map_columns() * (repeats ? 1 : TallyLayout::kCountSlots));
                            EXPECT_LT(i, L.surface_end());
                            if (!repeats) {
                                EXPECT_EQ((i - s) % 4, 0u) << "counts block not 32-byte aligned";
                            }
                        }
                        for (std::size_t r = 0; r < k.replicates; ++r) {
                            const std::size_t i = L.map_replicate(n, col, r);
                            take(i);
                            EXPECT_GE(i, L.replicas_begin(n));
                            EXPECT_LT(i, L.replicas_begin(n) + L.map_columns() * k.replicates);
                        }
                    }
        EXPECT_EQ(L.side_slots(), L.map_columns() * (TallyLayout::kSurfaceSlots + k.replicates));
        const int cells[] = {4, 9};
        for (std::size_t d = 0; d < 2; ++d) {
            for (std::size_t g = 0; g < k.groups; ++g) {
                for (int c = 0; c < cells[d]; ++c)
                    for (std::size_t b = 0; b < B; ++b) {
                        take(L.detector_n(d, c, b, g));
                        take(L.detector_q(d, c, b, g));
                        EXPECT_EQ(L.detector_cell(d, c, L.detector_column(b, g)), L.detector_n(d, c, b, g));
                        for (std::size_t r = 0; r < k.replicates; ++r) {
                            take(L.detector_replicate_n(d, r, c, b, g));
                            EXPECT_EQ(L.detector_replicate_of(d, L.detector_n(d, c, b, g), r),
                                      L.detector_replicate_n(d, r, c, b, g));
                        }
                    }
                take(L.detector_received(d, g));
                take(L.detector_total_n(d, g));
                take(L.detector_total_q(d, g));
                for (std::size_t r = 0; r < k.replicates; ++r) take(L.detector_replicate_total_n(d, r, g));
            }
        }
        for (std::size_t r = 0; r < k.replicates; ++r) take(L.replicate_photons(r));
        EXPECT_EQ(seen.size(), L.size()) << "the layout has unused slots (" << what << ")";
    }
}

TEST(TallyLayout, GatheredSlotsAreTheirOwnAndColumnByColumn) {
    const std::size_t groups = 5;
    const TallyLayout L(3, TallyDims{1, groups, 1, 0, true, {1, 1}, {1, 0}, 0}, {4, 6});
    const TallyLayout plain(3, TallyDims{1, groups, 1, 0, true, {1, 1}, {}, 0}, {4, 6});
    EXPECT_TRUE(L.gathered(0));
    EXPECT_FALSE(L.gathered(1));
    constexpr std::size_t W = TallyLayout::kGatherWords, T = TallyLayout::kGatherTotalWords;
    EXPECT_EQ(W, 2 + TallyLayout::kGatherRegions);  // Y, Y^2 and Y T_r per region
    EXPECT_EQ(L.size(), plain.size() + (4 * W + T) * groups);
    std::set<std::size_t> seen;
    for (std::size_t d = 0; d < 2; ++d)
        for (std::size_t c = 0; c < (d == 0 ? 4u : 6u); ++c)
            for (std::size_t g = 0; g < groups; ++g) {
                seen.insert({L.detector_n(d, c, 0, g), L.detector_q(d, c, 0, g), L.detector_direct(d, c, g)});
                if (d == 0) {
                    for (std::size_t w = 0; w < W; ++w)
                        EXPECT_TRUE(seen.insert(L.detector_gathered(d, c, g) + w).second);
                    if (c == 0) {
                        for (std::size_t w = 0; w < T; ++w)
                            EXPECT_TRUE(seen.insert(L.detector_gathered_total(d, g) + w).second);
                        EXPECT_LT(L.detector_gathered_total(d, g) + T - 1, L.size());
                    }
                    EXPECT_LT(L.detector_gathered(d, c, g) + W - 1, L.size());
                    // A column's cells lie together.
                    EXPECT_EQ(L.detector_gathered(d, c, g), L.detector_gathered(d, 0, g) + W * c);
                    if (g + 1 < groups) {
                        EXPECT_EQ(L.detector_gathered(d, c, g) + L.gathered_column_stride(d),
                                  L.detector_gathered(d, c, g + 1));
                    }
                }
            }
    // The regions' pairs fill the upper triangle once each, row by row.
    std::set<std::size_t> pairs;
    for (std::size_t r = 0; r < TallyLayout::kGatherRegions; ++r)
        for (std::size_t q = r; q < TallyLayout::kGatherRegions; ++q) {
            EXPECT_TRUE(pairs.insert(TallyLayout::gather_pair(r, q)).second);
            EXPECT_LT(TallyLayout::gather_pair(r, q), TallyLayout::kGatherPairs);
        }
    EXPECT_EQ(pairs.size(), TallyLayout::kGatherPairs);
}

TEST(PhotonTally, GatheredSumsAndSquaresPerPhotonAndNoDiscCountAfterADiffuseReflection) {
    const TallyLayout L(3, TallyDims{1, 2, 1, 0, true, {1}, {1}, 0}, {3});
    TallyStore store(L);
    const std::size_t total = L.detector_gathered_total(0, 0);
    // Cells 0, 1 and 2 in regions 0, 3 and 1.
    const GatherSlot slots[3] = {{L.detector_gathered(0, 0, 0), L.gathered_column_stride(0), total, 0},
                                 {L.detector_gathered(0, 1, 0), L.gathered_column_stride(0), total, 3},
                                 {L.detector_gathered(0, 2, 0), L.gathered_column_stride(0), total, 1}};
    const std::uint64_t big = std::uint64_t{3} << 30;  // Y^2 beyond 64 bits before the shift
    constexpr std::uint32_t u = 1u << 12;              // u^2 = 2^24: the scaled products exact
    {
        TallyBuffer out(store);
        PhotonTally t;
        for (int photon = 0; photon < 2; ++photon) {
            t.begin(L.bin(0, 1, 0, photon == 1));
            const GatherEntry first[2] = {{0, 3 * u}, {2, 7 * u}}, second[1] = {{0, 5 * u}};
            t.gather(first, slots);
            t.gather(second, slots);
            t.registrations().push_back({0, 1, false, true});   // after a diffuse reflection: the gather's
            t.registrations().push_back({0, 1, false, false});  // after a mirror: the cell's
            t.end(L, TallyLayout::kAbsorbed, out);
        }
        t.begin(L.bin(0, 0, 0, false));
        const GatherEntry huge[1] = {{1, static_cast<std::uint32_t>(big >> 8)}};
        for (int i = 0; i < 256; ++i) t.gather(huge, slots);
        t.end(L, TallyLayout::kAbsorbed, out);
    }
    const std::uint64_t s = TallyLayout::kGatherSquareShift;
    auto square = [&](std::uint64_t y) {
        return static_cast<std::uint64_t>((static_cast<long double>(y) * y) / (1 << s) + 0.5L);
    };
    EXPECT_EQ(store[L.detector_gathered(0, 0, 1)], 2u * 8u * u);  // two photons, 3 + 5 each
    EXPECT_EQ(store[L.detector_gathered(0, 0, 1) + 1], 2u * 64u);
    EXPECT_EQ(store[L.detector_gathered(0, 2, 1)], 14u * u);
    // Y T_r: cell 0's 8 (region 0) and cell 2's 7 (region 1) against each region's total.
    EXPECT_EQ(store[L.detector_gathered(0, 0, 1) + 2], 2u * 64u);
    EXPECT_EQ(store[L.detector_gathered(0, 0, 1) + 3], 2u * 56u);
    EXPECT_EQ(store[L.detector_gathered(0, 2, 1) + 2], 2u * 56u);
    EXPECT_EQ(store[L.detector_gathered(0, 2, 1) + 3], 2u * 49u);
    EXPECT_EQ(store[L.detector_gathered(0, 1, 0) + 2 + 3], square(big));  // its own region's
    EXPECT_EQ(store[L.detector_gathered(0, 1, 0) + 2], 0u);
    EXPECT_EQ(store[L.detector_gathered(0, 1, 1)], 0u);
    EXPECT_EQ(store[L.detector_gathered(0, 1, 0)], big);
    EXPECT_EQ(store[L.detector_gathered(0, 1, 0) + 1], square(big));
    // The regions' totals per photon: 8 and 7 for each of the two, the huge one alone in 3.
    const std::size_t R = TallyLayout::kGatherRegions;
    EXPECT_EQ(store[L.detector_gathered_total(0, 1)], 16u * u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 1) + 1], 14u * u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 1) + 3], 0u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 1) + R + TallyLayout::gather_pair(0, 0)], 2u * 64u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 1) + R + TallyLayout::gather_pair(0, 1)], 2u * 56u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 1) + R + TallyLayout::gather_pair(1, 1)], 2u * 49u);
    EXPECT_EQ(store[L.detector_gathered_total(0, 0) + 3], big);
    EXPECT_EQ(store[L.detector_gathered_total(0, 0) + R + TallyLayout::gather_pair(3, 3)], square(big));
    EXPECT_EQ(store[L.detector_gathered_total(0, 0) + R + TallyLayout::gather_pair(0, 3)], 0u);
    EXPECT_EQ(store[L.detector_n(0, 1, 0, 1)], 2u);  // the mirror's registrations only
    EXPECT_EQ(store[L.detector_q(0, 1, 0, 1)], 2u);
}

TEST(TallyLayout, OneGroupWithoutReplicatesKeepsTheRandomLayout) {
    // The group dimension of one group adds no word: a scene without light groups has the
    // layout (and so the checkpoints) of before.
    const TallyLayout one(7, TallyDims{2, 1, 1, 0, false, {}, {}, 0}, {4});
    EXPECT_EQ(one.size(), TallyLayout::kCounters + 7 * 2 * 2 * TallyLayout::kSurfaceSlots + (4 * 2 * 2 + 3));
    // group_maps = false: the map has one column per band whatever the groups.
    const TallyLayout shared(7, TallyDims{2, 5, 1, 0, false, {}, {}, 0}, {4});
    EXPECT_EQ(shared.surface_end(), one.surface_end());
    EXPECT_EQ(shared.bin(1, 4, 0, true).map_column, 1u);
    EXPECT_EQ(shared.bin(1, 4, 0, true).detector_column, 1u * 5 + 4);
}

TEST(TallyBuffer, ThreadedBuffersGiveExactSerialSums) {
    // Skewed indices (many repeats of a few, plus a long tail) exercise both merging in
    // the buffer and flushing when it fills.
    const TallyLayout L(20000, 1, {});
    TallyStore store(L);
    std::vector<std::uint64_t> expected(L.size(), 0);
    constexpr int kThreads = 4;
    constexpr int kAdds = 200000;
    auto index_of = [&](std::mt19937_64& g) { return (g() % 4 == 0) ? g() % 8 : g() % L.size(); };
    for (int t = 0; t < kThreads; ++t) {
        std::mt19937_64 g(t);
        for (int i = 0; i < kAdds; ++i) {
            const std::size_t idx = index_of(g);
            expected[idx] += 1 + (g() & 3);
        }
    }
    std::vector<std::jthread> pool;
    for (int t = 0; t < kThreads; ++t)
        pool.emplace_back([&, t] {
            std::mt19937_64 g(t);
            TallyBuffer buf(store);
            for (int i = 0; i < kAdds; ++i) {
                const std::size_t idx = index_of(g);
                buf.add(idx, 1 + (g() & 3));
            }
        });
    pool.clear();  // joins; buffers flushed by their destructors
    EXPECT_EQ(std::vector<std::uint64_t>(store.data().begin(), store.data().end()), expected);
}

// The store's memory: zero without being written, cache-line aligned, and untouched pages
// not resident (a closed room's back sides cost no memory).
TEST(WordArray, ZeroAlignedAndResidentOnlyWhereWritten) {
    const long page = sysconf(_SC_PAGESIZE);
    const std::size_t words = std::size_t{8} << 20;  // 64 MiB
    WordArray a(words);
    ASSERT_EQ(a.size(), words);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % 64, 0u);
    a[12345] = 7;
    a[words - 1] = 9;
    const std::size_t pages = (words * 8 + page - 1) / page;
    std::vector<unsigned char> resident(pages);
    ASSERT_EQ(mincore(a.data(), pages * page, resident.data()), 0);
    std::size_t in_memory = 0;
    for (unsigned char r : resident) in_memory += r & 1u;
    EXPECT_LE(in_memory, 4u) << "of " << pages << " pages";
    std::uint64_t sum = 0;
    for (std::uint64_t w : a) sum += w;
    EXPECT_EQ(sum, 16u);

    WordArray copy(a);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), copy.begin(), copy.end()));
    copy[0] = 1;
    EXPECT_EQ(a[0], 0u);
    WordArray moved(std::move(copy));
    EXPECT_EQ(copy.size(), 0u);
    EXPECT_EQ(moved[0] + moved[12345], 8u);
    moved = WordArray(3);
    EXPECT_EQ(moved.size(), 3u);
    EXPECT_EQ(moved[0] + moved[1] + moved[2], 0u);
}
