#include "luxtrace/tally/tally.hpp"

#include "luxtrace/scene/scene.hpp"

#include <algorithm>
#include <stdexcept>

namespace luxtrace {

TallyLayout::TallyLayout(std::size_t triangles, const TallyDims& dims, const std::vector<int>& detector_cells)
    : triangles_(triangles), dims_(dims) {
    // Counts, then repeats, then (sobol) replicate arrivals of every side.
    size_ = kCounters + triangles * kSides * map_columns() * (kSurfaceSlots + dims_.replicates);
    for (int cells : detector_cells) {
        det_offset_.push_back(size_);
        det_cells_.push_back(static_cast<std::size_t>(cells));
        size_ += static_cast<std::size_t>(cells) * detector_columns() * 2 + 3 * dims_.groups;
    }
    // The replicate slots after all others, so that a random run's layout is unchanged.
    for (std::size_t d = 0; d < det_cells_.size() && dims_.replicates > 0; ++d) {
        rep_offset_.push_back(size_);
        size_ += dims_.replicates * (det_cells_[d] * detector_columns() + dims_.groups);
    }
    for (std::size_t d = 0; d < det_cells_.size() && dims_.direct_scores; ++d) {
        direct_offset_.push_back(size_);
        size_ += det_cells_[d] * detector_columns();
    }
    size_ += dims_.replicates;  // photons per replicate
}

namespace {
std::vector<int> cells_of(const Scene& scene) {
    std::vector<int> cells;
    for (const Detector& d : scene.detectors) cells.push_back(d.cells());
    return cells;
}

TallyDims dims_of(const Scene& scene) {
    TallyDims d;
    d.bands = scene.bands.size();
    d.groups = scene.light_groups.size();
    d.map_groups = scene.run.group_maps ? d.groups : 1;
    d.replicates = scene.run.sampler == "sobol" ? scene.run.replicates : 0;
    d.direct_scores = scene.annual.has_value();
    return d;
}
}  // namespace

TallyLayout::TallyLayout(const Scene& scene) : TallyLayout(scene.triangle_count(), dims_of(scene), cells_of(scene)) {}

namespace {
bool bit(std::span<const std::uint64_t> mask, std::size_t i) { return ((mask[i / 64] >> (i % 64)) & 1u) != 0; }
}  // namespace

// A side's three runs of slots: its counts, its repeats and its replicate arrivals (tally.hpp).
constexpr int kRuns = 3;
struct SideRuns {
    std::size_t begin[kRuns], length[kRuns];
};
SideRuns runs_of(const TallyLayout& L, std::size_t i) {
    const std::size_t c = L.map_columns();
    return {{L.counts_begin(i), L.repeats_begin(i), L.replicas_begin(i)},
            {c * TallyLayout::kCountSlots, c, c * L.replicates()}};
}

std::vector<std::uint64_t> lit_side_mask(const TallyLayout& L, std::span<const std::uint64_t> message) {
    // A side with repeats or replicate arrivals has counts: its counts alone tell.
    std::vector<std::uint64_t> mask((L.sides() + 63) / 64, 0);
    const std::size_t n = L.map_columns() * TallyLayout::kCountSlots;
    for (std::size_t i = 0; i < L.sides(); ++i) {
        const std::uint64_t* s = message.data() + L.counts_begin(i);
        std::uint64_t any = 0;
        for (std::size_t k = 0; k < n; ++k) any |= s[k];
        if (any != 0) mask[i / 64] |= std::uint64_t{1} << (i % 64);
    }
    return mask;
}

void pack_lit_sides(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> message,
                    std::vector<std::uint64_t>& packed) {
    packed.clear();
    auto put = [&](std::size_t from, std::size_t count) {
        const auto s = message.begin() + static_cast<std::ptrdiff_t>(from);
        packed.insert(packed.end(), s, s + static_cast<std::ptrdiff_t>(count));
    };
    put(0, L.counts_begin(0));
    for (int run = 0; run < kRuns; ++run)
        for (std::size_t i = 0; i < L.sides(); ++i)
            if (bit(mask, i)) put(runs_of(L, i).begin[run], runs_of(L, i).length[run]);
    put(L.surface_end(), message.size() - L.surface_end());
}

void unpack_lit_sides(const TallyLayout& L, std::span<const std::uint64_t> mask, std::span<const std::uint64_t> packed,
                      std::span<std::uint64_t> message) {
    auto in = packed.begin();
    auto take = [&](std::size_t to, std::size_t count) {
        std::copy(in, in + static_cast<std::ptrdiff_t>(count), message.begin() + static_cast<std::ptrdiff_t>(to));
        in += static_cast<std::ptrdiff_t>(count);
    };
    take(0, L.counts_begin(0));
    for (int run = 0; run < kRuns; ++run)
        for (std::size_t i = 0; i < L.sides(); ++i) {
            const SideRuns r = runs_of(L, i);
            if (bit(mask, i)) take(r.begin[run], r.length[run]);
            else std::fill_n(message.begin() + static_cast<std::ptrdiff_t>(r.begin[run]), r.length[run], 0);
        }
    take(L.surface_end(), message.size() - L.surface_end());
}

void TallyStore::assign(std::span<const std::uint64_t> words) {
    if (words.size() != data_.size()) throw std::logic_error("TallyStore::assign: the words do not fit the layout");
    std::copy(words.begin(), words.end(), data_.begin());
}

TallyBuffer::TallyBuffer(TallyStore& store) : store_(store), slots_(kCapacity, Slot{kEmpty, 0}), used_(kMaxLoad) {}

void TallyBuffer::flush() {
    constexpr std::size_t kAhead = 8;  // store lines requested before their add
    for (std::size_t i = 0; i < used_count_; ++i) {
        if (i + kAhead < used_count_) __builtin_prefetch(store_.address(slots_[used_[i + kAhead]].index), 1);
        Slot& s = slots_[used_[i]];
        store_.add(s.index, s.value);
        s = {kEmpty, 0};
    }
    used_count_ = 0;
}

}  // namespace luxtrace
