#include "luxtrace/run/direct_pass.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/direct_daylight.hpp"

#include <algorithm>
#include <span>

namespace luxtrace {

namespace {

// The rows (entries and suns, values and variances) gathered to rank 0 at a time.
constexpr std::size_t kRowsPerGather = 256;

// Rank r's cells of n: [n r / R, n (r + 1) / R).
std::size_t first_cell(std::size_t n, int rank, int ranks) {
    return n * static_cast<std::size_t>(rank) / static_cast<std::size_t>(ranks);
}

}  // namespace

AnnualDirect annual_direct_pass(const Scene& scene, const EmbreeScene& embree, const Communicator& comm) {
    if (!scene.annual || !scene.annual->options.shadow_rays()) return {};
    const AnnualOptions& o = scene.annual->options;
    DirectDaylightOptions options;
    options.sky_rays = o.direct_sky_rays;
    options.sun_rays = o.direct_sun_rays;
    options.seed = scene.run.seed;
    const std::size_t entries = scene.annual->sky->sky_entries(), suns = scene.annual->sky->suns().size();
    const int ranks = comm.size(), rank = comm.rank();
    AnnualDirect out(comm.is_root() ? scene.detectors.size() : 0);
    for (std::size_t det = 0; det < scene.detectors.size(); ++det) {
        if (!annual_grid(scene.detectors[det])) continue;
        const std::size_t cells = static_cast<std::size_t>(scene.detectors[det].cells());
        const std::size_t first = first_cell(cells, rank, ranks), last = first_cell(cells, rank + 1, ranks);
        DirectCoefficients mine;  // this rank's cells alone
        mine.resize(ranks == 1 ? cells : last - first, entries, suns, ranks == 1 ? 0 : first);
        direct_daylight(scene, embree, det, options, first, last, mine);
        if (ranks == 1) {
            out[det] = std::move(mine);
            continue;
        }
        // Gathered a slab of rows at a time, so that rank 0 never holds the grid twice.
        if (comm.is_root()) out[det].resize(cells, entries, suns);
        const std::size_t rows = mine.rows();
        for (std::size_t r0 = 0; r0 < rows; r0 += kRowsPerGather) {
            const std::size_t r1 = std::min(rows, r0 + kRowsPerGather);
            std::vector<std::size_t> counts;
            for (int r = 0; r < ranks; ++r)
                counts.push_back(
                    mine.packed_words(first_cell(cells, r + 1, ranks) - first_cell(cells, r, ranks), r0, r1));
            std::vector<float> send, recv;
            mine.pack_cells(first, last, send, r0, r1);
            comm.gather_to_root<float>(send, counts, recv);
            if (!comm.is_root()) continue;
            std::size_t at = 0;
            for (int r = 0; r < ranks; ++r) {
                const std::size_t f = first_cell(cells, r, ranks), l = first_cell(cells, r + 1, ranks);
                const std::size_t n = counts[static_cast<std::size_t>(r)];
                out[det].unpack_cells(std::span<const float>(recv).subspan(at, n), f, l, r0, r1);
                at += n;
            }
        }
    }
    return out;
}

}  // namespace luxtrace
