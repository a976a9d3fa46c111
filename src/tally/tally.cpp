#include "luxtrace/tally/tally.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

TallyLayout::TallyLayout(std::size_t triangles, std::size_t bands, const std::vector<int>& detector_cells,
                         std::size_t replicates)
    : triangles_(triangles), bands_(bands), replicates_(replicates) {
    size_ = kCounters + triangles * bands * kSurfaceSlots;
    for (int cells : detector_cells) {
        det_offset_.push_back(size_);
        det_cells_.push_back(static_cast<std::size_t>(cells));
        size_ += static_cast<std::size_t>(cells) * bands * 2 + 3;
    }
    // The replicate slots after all others, so that a random run's layout is unchanged.
    for (std::size_t d = 0; d < det_cells_.size() && replicates_ > 0; ++d) {
        rep_offset_.push_back(size_);
        size_ += replicates_ * (det_cells_[d] * bands + 1);
    }
    size_ += replicates_;  // photons per replicate
}

namespace {
std::vector<int> cells_of(const Scene& scene) {
    std::vector<int> cells;
    for (const Detector& d : scene.detectors) cells.push_back(d.cells());
    return cells;
}
}  // namespace

TallyLayout::TallyLayout(const Scene& scene)
    : TallyLayout(scene.triangle_count(), scene.bands.size(), cells_of(scene),
                  scene.run.sampler == "sobol" ? scene.run.replicates : 0) {}

TallyBuffer::TallyBuffer(TallyStore& store)
    : store_(store), slots_(kCapacity, Slot{kEmpty, 0}), used_(kMaxLoad) {}

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
