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

// The dimensions every score is kept apart by besides its site (a triangle side, a
// detector cell): the photon's band, its light group (issue 22: light scenes recombine
// the groups after the run) and, for the sobol sampler, its replicate (docs/QMC.md).
struct TallyDims {
    std::size_t bands = 1;
    std::size_t groups = 1;      // light groups the detectors keep apart
    std::size_t map_groups = 1;  // light groups the surface map keeps apart: groups, or 1
    std::size_t replicates = 0;  // sobol's R; 0 for random
    // Also count, per detector cell and column, the registrations of photons still on the
    // straight line from their light (annual daylight's direct sun, issue 24).
    bool direct_scores = false;
    // Per detector (empty: none): its direct registrations count in the direct slots only,
    // not in n, q and the totals (annual grids whose direct light comes from shadow rays,
    // annual_sky.hpp: AnnualOptions::direct).
    std::vector<std::uint8_t> direct_apart;
    // Per detector (empty: none): it also keeps, per cell and column, the light gathered to
    // it from the surfaces the photons arrive on (annual grids with [annual] indirect =
    // "gather", tracer/gather_table.hpp), and its n and q then count no registration that
    // came after a diffuse reflection.
    std::vector<std::uint8_t> gathered;
    // With gathered detectors: the gather's sites (GatherTable::sites), whose arrivals of
    // every group are counted (the surfaces' irradiance at the patches' scale, for the
    // gather's own error).
    std::size_t gather_sites = 0;
};

// Where one photon's scores go besides the site, fixed when it starts: a column is a
// (band, group) pair, band-major.
struct TallyBin {
    std::size_t map_column = 0;       // band * map_groups + map group
    std::size_t detector_column = 0;  // band * groups + group
    std::size_t replicate = 0;        // 0 without replicates
    bool odd = false;                 // SPEC §3: odd photons feed the odd map
};

// Where each quantity sits in the flat array.
class TallyLayout {
public:
    // Photon fates, counted once per photon: left the scene, absorbed, stopped at the
    // bounce limit.
    enum Counter : std::size_t { kEscaped = 0, kAbsorbed = 1, kTruncated = 2, kCounters = 8 };
    // Per triangle side and column (issue 13: two-sided maps). Side 0 is the front, the side
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
    TallyLayout(std::size_t triangles, const TallyDims& dims, const std::vector<int>& detector_cells);
    // One light group: the layout of a scene without groups.
    TallyLayout(std::size_t triangles, std::size_t bands, const std::vector<int>& detector_cells,
                std::size_t replicates = 0)
        : TallyLayout(triangles, TallyDims{bands, 1, 1, replicates, false, {}, {}, 0}, detector_cells) {}

    std::size_t size() const { return size_; }
    std::size_t triangles() const { return triangles_; }
    std::size_t bands() const { return dims_.bands; }
    std::size_t groups() const { return dims_.groups; }
    std::size_t map_groups() const { return dims_.map_groups; }
    std::size_t replicates() const { return dims_.replicates; }
    std::size_t detector_count() const { return det_offset_.size(); }
    std::size_t map_columns() const { return dims_.bands * dims_.map_groups; }
    std::size_t detector_columns() const { return dims_.bands * dims_.groups; }
    std::size_t map_column(std::size_t band, std::size_t group) const { return band * dims_.map_groups + group; }
    std::size_t detector_column(std::size_t band, std::size_t group) const { return band * dims_.groups + group; }
    // The bin of a photon of `band` and light `group` (of replicate `replicate`, parity `odd`).
    TallyBin bin(std::size_t band, std::size_t group, std::size_t replicate, bool odd) const {
        return {map_column(band, dims_.map_groups > 1 ? group : 0), detector_column(band, group), replicate, odd};
    }

    std::size_t counter(Counter c) const { return c; }
    // Memory layout: the four counts of every side and column first, all front sides, then
    // all back sides (32 bytes per side and column, aligned: one cache line touched per
    // arrival, and a closed room's lit fronts lie together), then the repeats of every
    // side and column, touched only when a photon comes back, then (sobol) every side's
    // arrivals per column and replicate.
    std::size_t surface(std::size_t tri, std::size_t side, std::size_t band, SurfaceSlot s, std::size_t group) const {
        return map_slot(side_index(tri, side), map_column(band, group), s);
    }
    // Sides are numbered side * T + tri; `i` below is such a number.
    std::size_t side_index(std::size_t tri, std::size_t side) const { return side * triangles_ + tri; }
    std::size_t triangle_of(std::size_t i) const { return i % triangles_; }
    std::size_t sides() const { return triangles_ * kSides; }
    std::size_t map_slot(std::size_t i, std::size_t column, SurfaceSlot s) const {
        return s == kRepeats ? repeats_begin(i) + column : counts_begin(i) + column * kCountSlots + s;
    }
    std::size_t side_slot(std::size_t i, std::size_t band, SurfaceSlot s, std::size_t group) const {
        return map_slot(i, map_column(band, group), s);
    }
    // Arrivals of replicate r on side i in `column` (sobol only).
    std::size_t map_replicate(std::size_t i, std::size_t column, std::size_t r) const {
        return replicas_begin(i) + column * dims_.replicates + r;
    }
    // Side i's counts lie in [counts_begin(i), + map_columns * kCountSlots), its repeats in
    // [repeats_begin(i), + map_columns), its replicate arrivals in [replicas_begin(i),
    // + map_columns * R): the three runs a reduction packs per lit side (message_packing.hpp).
    std::size_t counts_begin(std::size_t i) const { return kCounters + i * map_columns() * kCountSlots; }
    std::size_t repeats_begin(std::size_t i) const { return counts_begin(sides()) + i * map_columns(); }
    std::size_t replicas_begin(std::size_t i) const {
        return repeats_begin(sides()) + i * map_columns() * dims_.replicates;
    }
    std::size_t side_slots() const { return map_columns() * (kSurfaceSlots + dims_.replicates); }  // per side
    // Everything after the surface map (detectors, replicates) starts here.
    std::size_t surface_end() const { return replicas_begin(sides()); }

    // n_c of `cell` in a detector column; q_c is the next slot.
    std::size_t detector_cell(std::size_t det, std::size_t cell, std::size_t column) const {
        return det_offset_[det] + (cell * detector_columns() + column) * 2;
    }
    std::size_t detector_n(std::size_t det, std::size_t cell, std::size_t band, std::size_t group) const {
        return detector_cell(det, cell, detector_column(band, group));
    }
    std::size_t detector_q(std::size_t det, std::size_t cell, std::size_t band, std::size_t group) const {
        return detector_n(det, cell, band, group) + 1;
    }
    // Per light group, photons that registered at least once in the detector, and the
    // whole grid as one cell: sum over photons of E (registrations anywhere in the
    // detector) and of E^2, for the error of the detector's mean value.
    std::size_t detector_received(std::size_t det, std::size_t group) const {
        return det_offset_[det] + det_cells_[det] * detector_columns() * 2 + group * 3;
    }
    std::size_t detector_total_n(std::size_t det, std::size_t group) const { return detector_received(det, group) + 1; }
    std::size_t detector_total_q(std::size_t det, std::size_t group) const { return detector_received(det, group) + 2; }

    // Per replicate (R > 0 only): n_c of the photons of replicate r, and their sum of E.
    std::size_t detector_replicate_n(std::size_t det, std::size_t r, std::size_t cell, std::size_t band,
                                     std::size_t group) const {
        return rep_offset_[det] + (r * det_cells_[det] + cell) * detector_columns() + detector_column(band, group);
    }
    // The replicate-r slot of the cell and column whose n_c sits at `n_index`.
    std::size_t detector_replicate_of(std::size_t det, std::size_t n_index, std::size_t r) const {
        return rep_offset_[det] + r * det_cells_[det] * detector_columns() + (n_index - det_offset_[det]) / 2;
    }
    std::size_t detector_replicate_total_n(std::size_t det, std::size_t r, std::size_t group) const {
        return rep_offset_[det] + dims_.replicates * det_cells_[det] * detector_columns() + r * dims_.groups + group;
    }
    // Direct registrations of `cell` in a detector column (direct_scores only). A photon's
    // direct flights lie on one straight line, which crosses a cell once at most: the
    // per-photon count is 0 or 1, so this is also its sum of squares.
    bool direct_scores() const { return dims_.direct_scores; }
    bool direct_apart(std::size_t det) const { return det < dims_.direct_apart.size() && dims_.direct_apart[det] != 0; }
    bool any_direct_apart() const { return !dims_.direct_apart.empty(); }
    std::size_t detector_direct(std::size_t det, std::size_t cell, std::size_t column) const {
        return direct_offset_[det] + cell * detector_columns() + column;
    }
    // The gathered light of `cell` in a detector column (gathered detectors only): the sum
    // over photons of Y, the photon's gathered value in the table's integer units, then the
    // sum of Y^2 / 2^kGatherSquareShift (rounded), like n_c and q_c, then for each of the
    // grid's kGatherRegions regions r the sum of Y T_r / 2^kGatherSquareShift, T_r the
    // photon's Y summed over the region's cells (GatherSlot::region): its covariance with
    // each part of the grid, how the cell's error moves with the others'
    // (estimate/gather_factors.hpp). kGatherWords words, column by column: a photon adds
    // to many cells of its own column, which then lie together.
    bool gathered(std::size_t det) const { return det < dims_.gathered.size() && dims_.gathered[det] != 0; }
    bool any_gathered() const { return !dims_.gathered.empty(); }
    std::size_t detector_gathered(std::size_t det, std::size_t cell, std::size_t column) const {
        return gather_offset_[det] + (column * det_cells_[det] + cell) * kGatherWords;
    }
    static constexpr std::size_t kGatherRegions = 4;
    static constexpr std::size_t kGatherWords = 2 + kGatherRegions;
    // From a cell's slot in one column to the next column's.
    std::size_t gathered_column_stride(std::size_t det) const { return det_cells_[det] * kGatherWords; }
    // The regions' totals: per column, the sums over photons of T_r (kGatherRegions words),
    // then of T_r T_s / 2^kGatherSquareShift for r <= s, row by row (gather_pair(r, s)).
    std::size_t detector_gathered_total(std::size_t det, std::size_t column) const {
        return gather_offset_[det] + detector_columns() * det_cells_[det] * kGatherWords + column * kGatherTotalWords;
    }
    static constexpr std::size_t kGatherPairs = kGatherRegions * (kGatherRegions + 1) / 2;
    static constexpr std::size_t kGatherTotalWords = kGatherRegions + kGatherPairs;
    // Where T_r T_s (r <= s) lies after the kGatherRegions sums: row r of the upper triangle.
    static constexpr std::size_t gather_pair(std::size_t r, std::size_t s) {
        return r * kGatherRegions - r * (r - 1) / 2 + (s - r);
    }
    static constexpr int kGatherSquareShift = 24;
    // The arrivals on gather site i, all photons (TallyDims::gather_sites).
    std::size_t gather_site(std::size_t i) const { return gather_sites_begin_ + i; }
    std::size_t gather_sites() const { return dims_.gather_sites; }
    // Photons traced of replicate r (the last R slots).
    std::size_t replicate_photons(std::size_t r) const { return size_ - dims_.replicates + r; }

private:
    std::size_t triangles_ = 0, size_ = kCounters, gather_sites_begin_ = 0;
    TallyDims dims_;
    std::vector<std::size_t> det_offset_, rep_offset_, direct_offset_, gather_offset_;
    std::vector<std::size_t> det_cells_;
};

// The rank's shared tallies. The words live in a WordArray: zero without being written,
// so the sides a run never reaches take no memory.
//
// Two arrays take turns (issue 26): the threads add to one while the counts of the other,
// everything added since the previous reduction, travel. take() swaps them while no thread
// traces, so a reduction costs the threads a pause, not a copy of the tallies.
class TallyStore {
public:
    TallyStore() = default;
    explicit TallyStore(TallyLayout layout) : layout_(std::move(layout)), data_{WordArray(layout_.size()), {}} {
        words_ = data_[0].data();
    }
    TallyStore(const TallyStore&) = delete;
    TallyStore& operator=(const TallyStore&) = delete;
    const TallyLayout& layout() const { return layout_; }
    void add(std::size_t index, std::uint64_t value) {
        std::atomic_ref<std::uint64_t>(words_[index]).fetch_add(value, std::memory_order_relaxed);
    }
    std::uint64_t operator[](std::size_t i) const { return words_[i]; }
    const std::uint64_t* address(std::size_t i) const { return &words_[i]; }
    // The array the threads add to.
    std::span<std::uint64_t> data() { return data_[active_].span(); }
    std::span<const std::uint64_t> data() const { return data_[active_].span(); }
    // Sets every word of the array the threads add to (a checkpoint's tallies); `words`
    // must have the layout's size.
    void assign(std::span<const std::uint64_t> words);
    // Only while no thread adds: the words added since the previous take (or since the
    // start); the threads add to the other array from now on, which the caller must have
    // zeroed (every word it was handed by the take before).
    std::span<std::uint64_t> take();
    // Only while no thread adds: swaps the array the last take handed out with `other`
    // (the layout's size, all zero), which the threads will add to after the next take.
    void exchange_taken(WordArray& other);

private:
    TallyLayout layout_;
    WordArray data_[2];
    int active_ = 0;
    std::uint64_t* words_ = nullptr;  // data_[active_]
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
    // Straight to the store, past the buffer: words a photon adds once and the next
    // photons seldom (a gathered cell's, TallyLayout::detector_gathered), which the buffer
    // could only hash and hand on.
    void add_through(std::size_t index, std::uint64_t value) { store_.add(index, value); }
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
