// A reduction's local work per rank, timed piece by piece on one process (issue 26 §3):
// the measured per-side and per-word costs the reduction cost model takes
// (bench/reduction_model.py, docs/SCALING.md). A layout of T triangles, one band, a closed
// room's share of its sides lit (the fronts: every other side), counts on each lit side
// as a reduction period leaves them; then, as RunLoop does it on R ranks:
//   mark     message_mask over the rank's counts (every side's count words read)
//   take     every owner's part packed as 32-bit words (the reduce-scatter's send buffer)
//            and the rank's counts zeroed, in one pass (take_part)
//   add      the owner adds its summed part into its totals (its 1/R of the sides)
//   chunks   the owner's chunk sums for the global estimate (its lit sides only)
//   one rank add_and_clear: the one-rank reduction (counts into totals, cleared)
// Each is the best of --repeats, in ns per side of the layout (mark, one rank), per lit
// word (take, add) and per lit side (chunks).
//   build/bench/reduction_costs --triangles 1e6 --ranks 4
#include "luxtrace/core/count.hpp"
#include "luxtrace/core/word_array.hpp"
#include "luxtrace/stats/global_sums.hpp"
#include "luxtrace/tally/message_packing.hpp"
#include "luxtrace/tally/tally.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace luxtrace;

namespace {

using Clock = std::chrono::steady_clock;

template <class F>
double best_of(int repeats, F&& f) {
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = Clock::now();
        f();
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return best;
}

// A closed room's counts after a period: the front sides lit, a few arrivals each.
void fill(const TallyLayout& L, std::span<std::uint64_t> words, std::uint64_t seed) {
    std::mt19937_64 g(seed);
    for (std::size_t t = 0; t < L.triangles(); ++t) {
        const std::size_t i = L.side_index(t, 0);
        words[L.map_slot(i, 0, TallyLayout::kCountOdd)] = 1 + g() % 4;
        words[L.map_slot(i, 0, TallyLayout::kCountEven)] = 1 + g() % 4;
        words[L.map_slot(i, 0, TallyLayout::kDirectOdd)] = g() % 2;
        words[L.map_slot(i, 0, TallyLayout::kRepeats)] = 2 * (g() % 2);
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"luxtrace reduction costs: a reduction's local work per rank, piece by piece"};
    std::string triangles_text = "1e6";
    int ranks = 1, repeats = 3;
    app.add_option("--triangles", triangles_text, "triangles of the layout")->capture_default_str();
    app.add_option("--ranks", ranks, "R: the owner's share is 1/R of the sides")->capture_default_str();
    app.add_option("--repeats", repeats, "best of this many")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    const std::optional<std::uint64_t> parsed = parse_count(triangles_text);
    if (!parsed) {
        std::fprintf(stderr, "reduction_costs: --triangles %s is not a count\n", triangles_text.c_str());
        return 2;
    }
    const std::size_t T = *parsed;
    const TallyLayout L(T, 1, {});
    WordArray counts(L.size()), totals(L.size());
    fill(L, counts.span(), 1);
    std::vector<std::uint64_t> mask;
    const double mark = best_of(repeats, [&] { mask = message_mask(L, counts.span(), MessagePart::whole(L)); });
    std::size_t lit_words = 0, lit_sides = 0;
    for (int r = 0; r < ranks; ++r) lit_words += packed_size(L, mask, L.size(), owned_sides(L, r, ranks));
    for (std::size_t w = 0; w < mask_side_words(L); ++w)
        lit_sides += static_cast<std::size_t>(__builtin_popcountll(mask[w]));
    std::vector<std::uint32_t> send(lit_words);
    // Taking and the one-rank pass clear the counts: each repeat refills them first (the
    // refill is not timed).
    double take = 1e300;
    for (int r = 0; r < repeats; ++r) {
        fill(L, counts.span(), 1);
        take = std::min(take, best_of(1, [&] {
                            std::uint32_t* out = send.data();
                            for (int o = 0; o < ranks; ++o)
                                out = take_part(L, mask, counts.span(), owned_sides(L, o, ranks), out);
                        }));
    }
    const MessagePart own = owned_sides(L, 0, ranks);
    const std::size_t own_words = packed_size(L, mask, L.size(), own);
    fill(L, counts.span(), 1);
    const std::vector<std::uint32_t> part(send.begin(), send.begin() + static_cast<std::ptrdiff_t>(own_words));
    const double add = best_of(repeats, [&] { add_packed_part<std::uint32_t>(L, mask, own, part, totals.span()); });
    const WeightedTallies w(L, totals.span());
    const std::vector<double> area(T, 0.01);
    std::size_t own_lit = 0;
    for (const ChunkRange& range : {own.fronts, own.backs})
        for (std::size_t c = range.begin; c < range.end; ++c)
            for (std::size_t i = chunk_sides(L, c).first; i < chunk_sides(L, c).second; ++i)
                own_lit += (mask[i / 64] >> (i % 64)) & 1u;
    const double chunks = best_of(repeats, [&] {
        for (const ChunkRange& range : {own.fronts, own.backs})
            if (chunk_sums(w, area, 1e-3, 1000000, range, mask).size() != range.size()) std::puts("chunks missing");
    });
    double one_rank = 1e300;
    std::vector<std::uint64_t> lit(mask_side_words(L));
    for (int r = 0; r < repeats; ++r) {
        fill(L, counts.span(), 1);
        one_rank = std::min(one_rank, best_of(1, [&] { add_and_clear(L, counts.span(), totals.span(), lit); }));
    }
    const double ns = 1e9;
    std::printf(
        "triangles %zu  sides %zu  lit sides %zu  lit words %zu  ranks %d (owner 0: %zu words, %zu lit sides)\n", T,
        L.sides(), lit_sides, lit_words, ranks, own_words, own_lit);
    std::printf("mark    %8.3f ms  %6.2f ns per side\n", 1e3 * mark, ns * mark / static_cast<double>(L.sides()));
    std::printf("take    %8.3f ms  %6.2f ns per lit word\n", 1e3 * take, ns * take / static_cast<double>(lit_words));
    std::printf("add     %8.3f ms  %6.2f ns per owned word\n", 1e3 * add,
                ns * add / static_cast<double>(std::max<std::size_t>(1, own_words)));
    std::printf("chunks  %8.3f ms  %6.2f ns per owned lit side\n", 1e3 * chunks,
                ns * chunks / static_cast<double>(std::max<std::size_t>(1, own_lit)));
    std::printf("1 rank  %8.3f ms  %6.2f ns per side (add_and_clear)\n", 1e3 * one_rank,
                ns * one_rank / static_cast<double>(L.sides()));
    return 0;
}
