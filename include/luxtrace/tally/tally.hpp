#pragma once
// Integer tallies of one rank, shared by all its threads.
//
// Everything lives in one flat uint64 array so that the MPI layer reduces it in one
// call and a checkpoint stores it as is. Counts are integers: adding them in any order
// gives the same bits, which is what makes any rank/thread split bit-identical.
// Threads do not write the array directly; each fills a small TallyBuffer that merges
// repeated indices and flushes with atomic adds, so memory does not grow with threads.
#include "luxtrace/core/word_array.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

struct Scene;

// Where each quantity sits in the flat array.
class TallyLayout {
public:
    // Photon fates, counted once per photon: left the scene, absorbed, stopped at the
    // bounce limit.
    enum Counter : std::size_t { kEscaped = 0, kAbsorbed = 1, kTruncated = 2, kCounters = 8 };
    // Per triangle, side and band (issue 13: two-sided maps). Side 0 is the front, the side
    // the triangle's normal points to (counter-clockwise winding); side 1 the back. kRepeats
    // is the sum over photons of n (n - 1), n the photon's arrivals on that side: with the
    // counts it gives the per-side second moment sum n^2 = count + repeats, which is zero
    // work for the photons that arrive on a side once at most.
    enum SurfaceSlot : std::size_t {
        kCountOdd = 0,
        kCountEven = 1,
        kDirectOdd = 2,
        kDirectEven = 3,
        kRepeats = 4,
        kSurfaceSlots = 5
    };
    static constexpr std::size_t kSides = 2, kCountSlots = 4;
    TallyLayout() = default;
    // replicates: R of the sobol sampler (docs/QMC.md), 0 for random; with R > 0 every
    // detector also keeps per replicate its cells' registrations and its total.
    TallyLayout(std::size_t triangles, std::size_t bands, const std::vector<int>& detector_cells,
                std::size_t replicates = 0);
    explicit TallyLayout(const Scene& scene);

    std::size_t size() const { return size_; }
    std::size_t triangles() const { return triangles_; }
    std::size_t bands() const { return bands_; }
    std::size_t detector_count() const { return det_offset_.size(); }

    std::size_t counter(Counter c) const { return c; }
    // Memory layout: the four counts of every side and band first, all front sides, then
    // all back sides (32 bytes per side and band, aligned: one cache line touched per
    // arrival, and a closed room's lit fronts lie together as one-sided maps did), then
    // the repeats of every side and band, touched only when a photon comes back.
    std::size_t surface(std::size_t tri, std::size_t side, std::size_t band, SurfaceSlot s) const {
        return side_slot(side_index(tri, side), band, s);
    }
    // Sides are numbered side * T + tri; `i` below is such a number.
    std::size_t side_index(std::size_t tri, std::size_t side) const { return side * triangles_ + tri; }
    std::size_t triangle_of(std::size_t i) const { return i % triangles_; }
    std::size_t sides() const { return triangles_ * kSides; }
    std::size_t side_slot(std::size_t i, std::size_t band, SurfaceSlot s) const {
        return s == kRepeats ? repeats_begin(i) + band : counts_begin(i) + band * kCountSlots + s;
    }
    // Side i's counts lie in [counts_begin(i), + bands * kCountSlots), its repeats in
    // [repeats_begin(i), + bands).
    std::size_t counts_begin(std::size_t i) const { return kCounters + i * bands_ * kCountSlots; }
    std::size_t repeats_begin(std::size_t i) const { return counts_begin(sides()) + i * bands_; }
    std::size_t side_slots() const { return bands_ * kSurfaceSlots; }  // per side, both parts
    // Everything after the surface map (detectors, replicates) starts here.
    std::size_t surface_end() const { return repeats_begin(sides()); }
    // n_c of cell `cell` in `band`; q_c is the next slot.
    std::size_t detector_n(std::size_t det, std::size_t cell, std::size_t band) const {
        return det_offset_[det] + (cell * bands_ + band) * 2;
    }
    std::size_t detector_q(std::size_t det, std::size_t cell, std::size_t band) const {
        return detector_n(det, cell, band) + 1;
    }
    // Photons that registered at least once in the detector.
    std::size_t detector_received(std::size_t det) const { return det_offset_[det] + det_cells_[det] * bands_ * 2; }
    // The whole grid as one cell: sum over photons of E (registrations anywhere in the
    // detector) and of E^2, for the error of the detector's mean value.
    std::size_t detector_total_n(std::size_t det) const { return detector_received(det) + 1; }
    std::size_t detector_total_q(std::size_t det) const { return detector_received(det) + 2; }

    // Per replicate (R > 0 only): n_c of the photons of replicate r, and their sum of E.
    std::size_t replicates() const { return replicates_; }
    std::size_t detector_replicate_n(std::size_t det, std::size_t r, std::size_t cell, std::size_t band) const {
        return rep_offset_[det] + (r * det_cells_[det] + cell) * bands_ + band;
    }
    // The replicate-r slot of the cell and band whose n_c sits at `n_index`.
    std::size_t detector_replicate_of(std::size_t det, std::size_t n_index, std::size_t r) const {
        return rep_offset_[det] + r * det_cells_[det] * bands_ + (n_index - det_offset_[det]) / 2;
    }
    std::size_t detector_replicate_total_n(std::size_t det, std::size_t r) const {
        return rep_offset_[det] + replicates_ * det_cells_[det] * bands_ + r;
    }
    // Photons traced of replicate r (the last R slots).
    std::size_t replicate_photons(std::size_t r) const { return size_ - replicates_ + r; }

private:
    std::size_t triangles_ = 0, bands_ = 0, size_ = kCounters, replicates_ = 0;
    std::vector<std::size_t> det_offset_, rep_offset_;
    std::vector<std::size_t> det_cells_;
};

// A reduction message without the sides nobody has hit (the back of a closed room's
// walls is never lit): a message is the flat tally array, possibly followed by other
// words, and everything but the unlit sides' slots is kept in order. Counts only grow, so
// a side unlit on every rank is zero everywhere and unpacking restores the message exactly.
// The mask has one bit per side (word i / 64, bit i % 64), OR-ed over the ranks.
std::vector<std::uint64_t> lit_side_mask(const TallyLayout& layout, std::span<const std::uint64_t> message);
void pack_lit_sides(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                    std::span<const std::uint64_t> message, std::vector<std::uint64_t>& packed);
// `message` must have the full length; it is overwritten.
void unpack_lit_sides(const TallyLayout& layout, std::span<const std::uint64_t> mask,
                      std::span<const std::uint64_t> packed, std::span<std::uint64_t> message);

// The rank's shared tallies. The words live in a WordArray: zero without being written,
// so the sides a run never reaches take no memory.
class TallyStore {
public:
    TallyStore() = default;
    explicit TallyStore(TallyLayout layout) : layout_(std::move(layout)), data_(layout_.size()) {}
    const TallyLayout& layout() const { return layout_; }
    void add(std::size_t index, std::uint64_t value) {
        std::atomic_ref<std::uint64_t>(data_[index]).fetch_add(value, std::memory_order_relaxed);
    }
    std::uint64_t operator[](std::size_t i) const { return data_[i]; }
    const std::uint64_t* address(std::size_t i) const { return &data_[i]; }
    std::span<std::uint64_t> data() { return data_.span(); }
    std::span<const std::uint64_t> data() const { return data_.span(); }
    // Sets every word (a checkpoint's tallies); `words` must have the layout's size.
    void assign(std::span<const std::uint64_t> words);

private:
    TallyLayout layout_;
    WordArray data_;
};

// A thread's fixed-size write-combining buffer (open addressing on the tally index).
// 16 KB: it stays in the core's L1/L2 while the thread traces. Repeated indices (a small
// scene's triangles, a detector's cells) are summed in place; the slots in use are
// listed, so a flush touches only them and prefetches the store's lines ahead of its
// atomic adds (a large scene's tallies are spread over many megabytes).
class TallyBuffer {
public:
    explicit TallyBuffer(TallyStore& store);
    ~TallyBuffer() { flush(); }
    TallyBuffer(const TallyBuffer&) = delete;
    TallyBuffer& operator=(const TallyBuffer&) = delete;

    void add(std::size_t index, std::uint64_t value) {
        std::size_t h = (index * 0x9E3779B97F4A7C15ull) >> (64 - kLogCapacity);
        while (true) {
            Slot& s = slots_[h];
            if (s.index == index) {
                s.value += value;
                return;
            }
            if (s.index == kEmpty) {
                s = {index, value};
                used_[used_count_++] = static_cast<std::uint16_t>(h);
                if (used_count_ == kMaxLoad) flush();
                return;
            }
            h = (h + 1) & (kCapacity - 1);
        }
    }
    void flush();

private:
    static constexpr int kLogCapacity = 10;
    static constexpr std::size_t kCapacity = std::size_t{1} << kLogCapacity;
    static constexpr std::size_t kMaxLoad = kCapacity / 2;
    static constexpr std::size_t kEmpty = ~std::size_t{0};
    struct Slot {
        std::size_t index;
        std::uint64_t value;
    };
    TallyStore& store_;
    std::vector<Slot> slots_;
    std::vector<std::uint16_t> used_;  // slots in use, in the order they were taken
    std::size_t used_count_ = 0;
};

}  // namespace luxtrace
