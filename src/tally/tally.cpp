#include "luxtrace/tally/tally.hpp"

#include "luxtrace/scene/scene.hpp"

namespace luxtrace {

TallyLayout::TallyLayout(std::size_t triangles, std::size_t bands, const std::vector<int>& detector_cells)
    : triangles_(triangles), bands_(bands) {
    size_ = kCounters + triangles * bands * kSurfaceSlots;
    for (int cells : detector_cells) {
        det_offset_.push_back(size_);
        det_cells_.push_back(static_cast<std::size_t>(cells));
        size_ += static_cast<std::size_t>(cells) * bands * 2 + 3;
    }
}

namespace {
std::vector<int> cells_of(const Scene& scene) {
    std::vector<int> cells;
    for (const Detector& d : scene.detectors) cells.push_back(d.cells());
    return cells;
}
}  // namespace

TallyLayout::TallyLayout(const Scene& scene)
    : TallyLayout(scene.triangle_count(), scene.bands.size(), cells_of(scene)) {}

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
