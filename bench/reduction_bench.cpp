// The size and time of a reduction of annual daylight-coefficient tallies over the ranks
// (docs/PERFORMANCE.md, "Reductions of annual tallies"): the message of the whole flat
// array (every detector word) against the message without the 8-word blocks no rank has
// written (tally/message_packing.hpp).
//
// No tracing: each rank fills a TallyLayout of P sky patches + ground + S suns with direct
// counts the way a side-lit room's sensors fill (below), then both messages are reduced to
// rank 0 the way RunLoop does it (mask, OR over the ranks, pack, ireduce, unpack), and the
// unpacked sums are compared word for word.
//
//   mpirun -n 2 reduction_bench --cells 1000 --mf 1 [--suns 3925] [--repeats 3]
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/tally/message_packing.hpp"
#include "luxtrace/tally/tally.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

using namespace luxtrace;

namespace {

struct Fill {
    double patch_cells = 0.9;   // cells a patch in front of the window reaches (by reflection)
    double patch_direct = 0.1;  // cells that see a front patch straight through the window
    double sun_cells = 0.1;     // cells a front sun's reflected light reaches
    double sun_direct = 0.02;   // cells in a front sun's beam patch
};

// A cheap reproducible stream (splitmix64): the fill is not the subject.
struct Stream {
    std::uint64_t s;
    double next() {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }
};

// Half the sky patches face the window (patches behind it emit nothing through it), and 6
// of every 10 suns (an hour's sun is in front of a south window for most of the day); the
// ground reaches every cell. Each rank traces other photons: its own stream.
void fill(const TallyLayout& L, std::size_t cells, std::size_t patches, const Fill& f, int rank,
          std::vector<std::uint64_t>& m) {
    Stream r{0x5EEDull + static_cast<std::uint64_t>(rank) * 0x1000193ull};
    const std::size_t G = L.groups();
    m[TallyLayout::kEscaped] = 1000;
    for (std::size_t c = 0; c < cells; ++c)
        for (std::size_t g = 0; g < G; ++g) {
            const bool patch = g < patches, ground = g == patches,
                       front = patch ? g % 2 == 0 : ground || (g - patches) % 10 < 6;
            if (!front) continue;
            const double reach = patch ? f.patch_cells : ground ? 1.0 : f.sun_cells;
            const double direct = patch ? f.patch_direct : ground ? 0.0 : f.sun_direct;
            if (r.next() < reach) {
                m[L.detector_n(0, c, 0, g)] = 1 + static_cast<std::uint64_t>(r.next() * 50);
                m[L.detector_q(0, c, 0, g)] = 1 + static_cast<std::uint64_t>(r.next() * 5000);
            }
            if (r.next() < direct) m[L.detector_direct(0, c, g)] = 1 + static_cast<std::uint64_t>(r.next() * 20);
        }
    for (std::size_t g = 0; g < G; ++g) m[L.detector_received(0, g)] = 1 + g;
}

struct Timing {
    double mask_s = 0, pack_s = 0, reduce_s = 0, unpack_s = 0;
    std::size_t words = 0;
    double total() const { return mask_s + pack_s + reduce_s + unpack_s; }
};

// One reduction as RunLoop::start_reduce / finish_reduce do it; `all_blocks` keeps every
// block after the surface map (the message before blocks were left out); its mask's bits
// past the last block are set too, which packing ignores.
Timing reduce_once(const Communicator& comm, const TallyLayout& L, const std::vector<std::uint64_t>& message,
                   bool all_blocks, std::vector<std::uint64_t>& packed, std::vector<std::uint64_t>& packed_sum,
                   std::vector<std::uint64_t>& reduced) {
    Timing t;
    comm.allreduce_max(0.0);  // start together
    double t0 = comm.wtime();
    // The whole detector part: no scan for its blocks (the layout has no triangles, so no
    // sides to mark either), as the reductions before message_packing.hpp.
    std::vector<std::uint64_t> mask(mask_words(L, message.size()), ~std::uint64_t{0});
    if (!all_blocks) mask = message_mask(L, message);
    comm.allreduce_or(mask);
    double t1 = comm.wtime();
    t.mask_s = t1 - t0;
    pack_message(L, mask, message, packed);
    t.words = packed.size();
    t0 = comm.wtime();
    t.pack_s = t0 - t1;
    comm.ireduce_sum_to_root(packed, packed_sum).wait();
    t1 = comm.wtime();
    t.reduce_s = t1 - t0;
    if (comm.is_root()) {
        reduced.resize(message.size());
        unpack_message(L, mask, packed_sum, reduced);
    }
    t.unpack_s = comm.wtime() - t1;
    // Every rank's figures: the slowest counts.
    t.mask_s = comm.allreduce_max(t.mask_s);
    t.pack_s = comm.allreduce_max(t.pack_s);
    t.reduce_s = comm.allreduce_max(t.reduce_s);
    t.unpack_s = comm.allreduce_max(t.unpack_s);
    return t;
}

std::uint64_t hash(const std::vector<std::uint64_t>& words) {
    std::uint64_t h = 0xCBF29CE484222325ull;  // FNV-1a over the words
    for (const std::uint64_t w : words) h = (h ^ w) * 0x100000001B3ull;
    return h;
}

Timing fastest(const std::vector<Timing>& runs) {
    return *std::min_element(runs.begin(), runs.end(),
                             [](const Timing& a, const Timing& b) { return a.total() < b.total(); });
}

}  // namespace

int main(int argc, char** argv) {
    Communicator comm(&argc, &argv);
    CLI::App app{"luxtrace reduction bench: annual daylight-coefficient tallies over MPI ranks"};
    std::size_t cells = 1000, suns = 3925;
    int mf = 1, repeats = 3;
    Fill f;
    app.add_option("--cells", cells, "detector cells (sensors)");
    app.add_option("--mf", mf, "Reinhart sky subdivision: 1 (145 patches), 2 (577) or 4 (2305)")
        ->check(CLI::IsMember({1, 2, 4}));
    app.add_option("--suns", suns, "sun groups (the year's sun-up hours)");
    app.add_option("--repeats", repeats, "reductions timed of each kind (the fastest is reported)");
    app.add_option("--patch-cells", f.patch_cells);
    app.add_option("--patch-direct", f.patch_direct);
    app.add_option("--sun-cells", f.sun_cells);
    app.add_option("--sun-direct", f.sun_direct);
    CLI11_PARSE(app, argc, argv);

    const std::size_t patches = 144 * static_cast<std::size_t>(mf * mf) + 1;
    const std::size_t groups = patches + 1 + suns;
    const TallyLayout L(0, TallyDims{1, groups, 1, 0, true, {}, {}, 0}, {static_cast<int>(cells)});
    const std::size_t words = L.size() + 2 * static_cast<std::size_t>(comm.size()) + 4;  // + progress, flags
    std::vector<std::uint64_t> message(words, 0), packed, packed_sum, reduced;
    fill(L, cells, patches, f, comm.rank(), message);
    message[L.size() + 2 * static_cast<std::size_t>(comm.rank())] = 1;  // this rank's progress

    std::vector<Timing> sparse, flat;
    // The two sums compared by a hash of every word (a copy of 10,000 sensors' sums would
    // not fit beside the buffers).
    std::uint64_t sparse_hash = 0;
    bool same = true;
    for (int i = 0; i < repeats; ++i) {
        sparse.push_back(reduce_once(comm, L, message, false, packed, packed_sum, reduced));
        if (comm.is_root()) sparse_hash = hash(reduced);
        flat.push_back(reduce_once(comm, L, message, true, packed, packed_sum, reduced));
        same = same && (!comm.is_root() || hash(reduced) == sparse_hash);
    }
    if (comm.is_root()) {
        const Timing a = fastest(flat), b = fastest(sparse);
        const double MB = 8.0 / 1e6;
        std::printf("ranks %d, cells %zu, MF %d: %zu groups (%zu patches, ground, %zu suns), direct counts\n",
                    comm.size(), cells, mf, groups, patches, suns);
        std::printf("tally words per rank: %zu (%.1f MB)\n", L.size(), static_cast<double>(L.size()) * MB);
        std::printf("%-18s %14s %10s %9s %9s %9s %9s %9s\n", "message", "words", "MB", "mask s", "pack s", "reduce s",
                    "unpack s", "total s");
        for (const auto& [name, t] : {std::pair{"whole detector", a}, std::pair{"written blocks", b}})
            std::printf("%-18s %14zu %10.1f %9.3f %9.3f %9.3f %9.3f %9.3f\n", name, t.words,
                        static_cast<double>(t.words) * MB, t.mask_s, t.pack_s, t.reduce_s, t.unpack_s, t.total());
        std::printf("sums identical: %s\n", same ? "yes" : "NO");
        // What RunLoop holds: the store and its snapshot on every rank, the packed message,
        // and on rank 0 the packed sum and the unpacked sum.
        const double copy = static_cast<double>(words) * MB, sent = static_cast<double>(b.words) * MB;
        std::printf(
            "memory per rank (RunLoop): %.0f MB (store, snapshot, packed message), rank 0 %.0f MB (+ sum, packed "
            "sum)\n",
            2 * copy + sent, 3 * copy + 2 * sent);
    }
    return same ? 0 : 1;
}
