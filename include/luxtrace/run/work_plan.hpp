#pragma once
// Which photon indices each rank traces.
//
// The global work is a fixed sequence of items: first the holes left by an interrupted
// run (photon ranges it never traced), then blocks of `block` photons from the frontier
// on, all clipped to the photon budget. Rank r takes items r, r + R, r + 2R, ... Its
// threads take chunks of its current item in order, so when they are all paused the
// rank's finished photons are exactly: its first `items_done` items plus a prefix of
// the next. Two numbers per rank therefore describe the whole done set, which is what
// the reduction carries and what a checkpoint stores (as ranges).
#include <cstdint>
#include <mutex>
#include <vector>

namespace luxtrace {

struct PhotonRange {
    std::uint64_t begin = 0, end = 0;
    std::uint64_t size() const { return end - begin; }
    bool empty() const { return end <= begin; }
};

// A rank's position in its item sequence.
struct RankProgress {
    std::uint64_t items_done = 0;
    std::uint64_t prefix = 0;  // photons done in item `items_done`
};

class WorkPlan {
public:
    // `done`: sorted, disjoint ranges already traced (empty for a new run).
    WorkPlan(const std::vector<PhotonRange>& done, std::uint64_t budget, std::uint64_t block, int ranks);

    int ranks() const { return ranks_; }
    // Item i of `rank`, clipped to the budget; empty once the rank has no more work.
    PhotonRange item(int rank, std::uint64_t i) const;
    // Every traced range: the earlier run's plus what each rank's progress covers.
    std::vector<PhotonRange> done_ranges(const std::vector<RankProgress>& progress) const;
    std::uint64_t previously_done_count() const;

private:
    PhotonRange global_item(std::uint64_t g) const;
    std::vector<PhotonRange> done_;
    std::vector<PhotonRange> holes_;  // split into pieces of at most `block_`
    std::uint64_t frontier_ = 0, budget_ = 0, block_ = 1;
    int ranks_ = 1;
};

// Sort and merge touching or overlapping ranges.
std::vector<PhotonRange> merge_ranges(std::vector<PhotonRange> ranges);
std::uint64_t count_photons(const std::vector<PhotonRange>& ranges);

// Hands out a rank's photons to its threads in chunks. Thread-safe.
class RankWork {
public:
    enum class Next { chunk, fenced, exhausted };
    RankWork(const WorkPlan& plan, int rank);
    // Next chunk of at most `max` photons, never going past the fence; `fenced` when the
    // fence is reached, `exhausted` when the rank's work is done.
    Next next_chunk(std::uint64_t max, PhotonRange& out);
    // No more than `handed_out` photons in all until the fence is moved (reductions at
    // fixed photon counts); kNoFence lifts it.
    static constexpr std::uint64_t kNoFence = UINT64_MAX;
    void set_fence(std::uint64_t handed_out);
    // Every photon up to the fence has been handed out and work remains beyond it. Once
    // the work runs out, the end is the pool's threads all going idle instead: a thread
    // still tracing the last chunk would otherwise make every check true at once, and the
    // run would reduce again and again until that thread finished (and re-pause it).
    bool fence_reached() const;
    // Valid while no chunk is being traced (all threads paused or finished).
    RankProgress progress() const;

private:
    const WorkPlan& plan_;
    int rank_;
    mutable std::mutex mutex_;
    std::uint64_t item_index_ = 0;
    PhotonRange item_;
    std::uint64_t pos_ = 0;
    std::uint64_t handed_out_ = 0;
    std::uint64_t fence_ = kNoFence;
};

}  // namespace luxtrace
