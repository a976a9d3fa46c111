#include "luxtrace/tally/tally.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

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
    for (std::size_t d = 0; d < det_cells_.size(); ++d) {
        gather_offset_.push_back(size_);
        if (gathered(d)) size_ += (det_cells_[d] * kGatherWords + kGatherTotalWords) * detector_columns();
    }
    gather_sites_begin_ = size_;
    size_ += dims_.gather_sites;
    size_ += dims_.replicates;  // photons per replicate
}

void TallyStore::assign(std::span<const std::uint64_t> words) {
    if (words.size() != layout_.size()) throw std::logic_error("TallyStore::assign: the words do not fit the layout");
    std::copy(words.begin(), words.end(), data_[active_].begin());
}

void TallyStore::exchange_taken(WordArray& other) {
    if (other.size() != layout_.size()) throw std::logic_error("TallyStore::exchange_taken: the array does not fit");
    std::swap(data_[1 - active_], other);
}

std::span<std::uint64_t> TallyStore::take() {
    // The second array is mapped at the first take: a run without reductions never has it.
    if (data_[1 - active_].size() != layout_.size()) data_[1 - active_] = WordArray(layout_.size());
    const int taken = active_;
    active_ = 1 - active_;
    words_ = data_[active_].data();
    return data_[taken].span();
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
