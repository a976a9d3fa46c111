#include "luxtrace/run/work_plan.hpp"

#include <algorithm>

namespace luxtrace {

std::vector<PhotonRange> merge_ranges(std::vector<PhotonRange> r) {
    std::erase_if(r, [](const PhotonRange& x) { return x.empty(); });
    std::sort(r.begin(), r.end(), [](const PhotonRange& a, const PhotonRange& b) { return a.begin < b.begin; });
    std::vector<PhotonRange> out;
    for (const PhotonRange& x : r) {
        if (!out.empty() && x.begin <= out.back().end) out.back().end = std::max(out.back().end, x.end);
        else out.push_back(x);
    }
    return out;
}

std::uint64_t count_photons(const std::vector<PhotonRange>& ranges) {
    std::uint64_t n = 0;
    for (const PhotonRange& r : ranges) n += r.size();
    return n;
}

WorkPlan::WorkPlan(const std::vector<PhotonRange>& done, std::uint64_t budget, std::uint64_t block, int ranks)
    : done_(merge_ranges(done)), budget_(budget), block_(std::max<std::uint64_t>(1, block)),
      ranks_(std::max(1, ranks)) {
    std::uint64_t at = 0;
    for (const PhotonRange& d : done_) {
        for (std::uint64_t b = at; b < d.begin; b += block_) holes_.push_back({b, std::min(d.begin, b + block_)});
        at = d.end;
    }
    frontier_ = at;
}

std::uint64_t WorkPlan::previously_done_count() const { return count_photons(done_); }

PhotonRange WorkPlan::global_item(std::uint64_t g) const {
    PhotonRange r;
    if (g < holes_.size()) r = holes_[g];
    else {
        const std::uint64_t j = g - holes_.size();
        r = {frontier_ + j * block_, frontier_ + (j + 1) * block_};
    }
    r.end = std::min(r.end, budget_);
    if (r.begin >= r.end) r = {budget_, budget_};
    return r;
}

PhotonRange WorkPlan::item(int rank, std::uint64_t i) const {
    return global_item(static_cast<std::uint64_t>(rank) + i * static_cast<std::uint64_t>(ranks_));
}

std::vector<PhotonRange> WorkPlan::done_ranges(const std::vector<RankProgress>& progress) const {
    std::vector<PhotonRange> out = done_;
    for (int r = 0; r < static_cast<int>(progress.size()); ++r) {
        for (std::uint64_t i = 0; i < progress[r].items_done; ++i) out.push_back(item(r, i));
        if (progress[r].prefix > 0) {
            const PhotonRange it = item(r, progress[r].items_done);
            out.push_back({it.begin, it.begin + progress[r].prefix});
        }
    }
    return merge_ranges(std::move(out));
}

RankWork::RankWork(const WorkPlan& plan, int rank) : plan_(plan), rank_(rank) {
    item_ = plan_.item(rank_, 0);
    pos_ = item_.begin;
}

RankWork::Next RankWork::next_chunk(std::uint64_t max, PhotonRange& out) {
    std::lock_guard lock(mutex_);
    if (item_.empty()) return Next::exhausted;
    if (handed_out_ >= fence_) return Next::fenced;
    max = std::min(max, fence_ - handed_out_);
    out = {pos_, std::min(item_.end, pos_ + max)};
    pos_ = out.end;
    handed_out_ += out.size();
    if (pos_ == item_.end) {
        ++item_index_;
        item_ = plan_.item(rank_, item_index_);
        pos_ = item_.begin;
    }
    return Next::chunk;
}

bool RankWork::fence_reached() const {
    std::lock_guard lock(mutex_);
    return !item_.empty() && handed_out_ >= fence_;
}

void RankWork::set_fence(std::uint64_t handed_out) {
    std::lock_guard lock(mutex_);
    fence_ = handed_out;
}

RankProgress RankWork::progress() const {
    std::lock_guard lock(mutex_);
    return {item_index_, item_.empty() ? 0 : pos_ - item_.begin};
}

}  // namespace luxtrace
