#include "luxtrace/run/direct_pass.hpp"

#include "luxtrace/annual/annual_grid.hpp"
#include "luxtrace/reduction/communicator.hpp"
#include "luxtrace/scene/scene.hpp"
#include "luxtrace/tracer/direct_daylight.hpp"

#include <span>

namespace luxtrace {

namespace {

// Rank r's cells of n: [n r / R, n (r + 1) / R).
std::size_t first_cell(std::size_t n, int rank, int ranks) {
    return n * static_cast<std::size_t>(rank) / static_cast<std::size_t>(ranks);
}

// The four arrays' values of cells [first, last), row by row (a row: an entry or a sun).
std::vector<double> pack(const DirectCoefficients& d, std::size_t first, std::size_t last) {
    std::vector<double> out;
    for (const std::vector<double>* a : {&d.sky_lx, &d.sky_var, &d.sun_lx, &d.sun_var}) {
        const std::size_t rows = a->size() / d.cells;
        for (std::size_t row = 0; row < rows; ++row)
            out.insert(out.end(), a->begin() + static_cast<std::ptrdiff_t>(row * d.cells + first),
                       a->begin() + static_cast<std::ptrdiff_t>(row * d.cells + last));
    }
    return out;
}

void unpack(std::span<const double> in, std::size_t first, std::size_t last, DirectCoefficients& d) {
    std::size_t at = 0;
    for (std::vector<double>* a : {&d.sky_lx, &d.sky_var, &d.sun_lx, &d.sun_var}) {
        const std::size_t rows = a->size() / d.cells;
        for (std::size_t row = 0; row < rows; ++row)
            for (std::size_t c = first; c < last; ++c) (*a)[row * d.cells + c] = in[at++];
    }
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
        DirectCoefficients mine;
        mine.resize(cells, entries, suns);
        direct_daylight(scene, embree, det, options, first, last, mine);
        if (ranks == 1) {
            out[det] = std::move(mine);
            continue;
        }
        std::vector<std::size_t> counts;
        for (int r = 0; r < ranks; ++r)
            counts.push_back((first_cell(cells, r + 1, ranks) - first_cell(cells, r, ranks)) * 2 * (entries + suns));
        const std::vector<double> send = pack(mine, first, last);
        std::vector<double> recv;
        comm.gather_to_root<double>(send, counts, recv);
        if (!comm.is_root()) continue;
        out[det].resize(cells, entries, suns);
        std::size_t at = 0;
        for (int r = 0; r < ranks; ++r) {
            const std::size_t f = first_cell(cells, r, ranks), l = first_cell(cells, r + 1, ranks);
            unpack(std::span<const double>(recv).subspan(at, counts[static_cast<std::size_t>(r)]), f, l, out[det]);
            at += counts[static_cast<std::size_t>(r)];
        }
    }
    return out;
}

}  // namespace luxtrace
