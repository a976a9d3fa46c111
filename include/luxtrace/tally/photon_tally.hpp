#pragma once
// The scorer: one photon's scores, committed into the tally layout (filters x scores, as
// OpenMC's tallies). Filters on the photon's flight (the surface map's arrivals, the
// detectors' registrations, tracer/detector_filters.hpp) say *where*; this says *what* is
// added, in which bin (band, light group, replicate, odd/even: TallyBin).
//
// A surface arrival adds its counts at once; what needs the photon's count per site
// squared (eq. 6's q_c, a side's repeats) is kept until the photon ends.
#include "luxtrace/tally/tally.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace luxtrace {

// A cell's share of an arrival's gathered light (tracer/gather_table.hpp).
struct GatherEntry {
    std::uint32_t cell = 0;    // the gathered cell, numbered across the gathered grids
    std::uint32_t weight = 0;  // units
};

// A gathered cell's slot in column 0 (TallyLayout::detector_gathered), the step from one
// column to the next, its grid's totals' slot in column 0 (detector_gathered_total), and
// the grid's region it lies in (< TallyLayout::kGatherRegions).
struct GatherSlot {
    std::size_t first = 0, column_stride = 0, total = 0;
    std::size_t region = 0;
};

// A detector cell the photon registered in.
struct Registration {
    std::uint32_t detector = 0;
    std::uint32_t cell = 0;
    bool direct = false;  // on the photon's straight line from its light (TallyLayout::detector_direct)
    // After a diffuse reflection (and panes the gather passes too): a gathered grid's light
    // (TallyDims::gathered), not its disc's.
    bool after_diffuse = false;
};

class PhotonTally {
public:
    PhotonTally();
    // A new photon, scoring into `bin` of `layout`.
    void begin(const TallyBin& bin) {
        bin_ = bin;
        regs_.clear();
        arrivals_.clear();
    }
    // An arrival on side i (TallyLayout::side_index); `direct`: the photon's first.
    void arrive(const TallyLayout& layout, std::size_t side, bool direct, TallyBuffer& out) {
        const std::size_t counts = layout.map_slot(side, bin_.map_column, TallyLayout::kCountOdd);
        out.add(counts + (bin_.odd ? TallyLayout::kCountOdd : TallyLayout::kCountEven), 1);
        if (direct) out.add(counts + (bin_.odd ? TallyLayout::kDirectOdd : TallyLayout::kDirectEven), 1);
        if (layout.replicates() > 0) out.add(layout.map_replicate(side, bin_.map_column, bin_.replicate), 1);
        arrivals_.push_back(layout.map_slot(side, bin_.map_column, TallyLayout::kRepeats));
    }
    // An arrival whose light goes to the cells of `entries` (gather_table.hpp), summed per
    // cell until the photon ends; `slots` per gathered cell: where it lies in the layout.
    void gather(std::span<const GatherEntry> entries, std::span<const GatherSlot> slots) {
        if (entries.empty()) return;
        if (gathered_.size() != slots.size()) gathered_.assign(slots.size(), 0);
        slots_ = slots;
        for (const GatherEntry& e : entries) {
            if (gathered_[e.cell] == 0) touched_.push_back(e.cell);
            gathered_[e.cell] += e.weight;
        }
    }
    // Filters append the cells the photon registers in here.
    std::vector<Registration>& registrations() { return regs_; }
    // The photon ended with `fate`: its fate, its replicate's photon count, its repeats and
    // its detector registrations (eq. 6).
    void end(const TallyLayout& layout, TallyLayout::Counter fate, TallyBuffer& out);

private:
    void add_repeats(TallyBuffer& out);
    void add_registrations(const TallyLayout& layout, TallyBuffer& out);
    void add_gathered(TallyBuffer& out);

    TallyBin bin_;
    std::vector<Registration> regs_;
    std::vector<std::size_t> arrivals_;  // kRepeats slot of every surface arrival
    std::vector<std::size_t> indices_;   // scratch: the registrations' n_c slots
    // The photon's gathered units per gathered cell (zero where untouched), and the cells
    // it touched.
    std::span<const GatherSlot> slots_;
    std::vector<std::uint64_t> gathered_;
    std::vector<std::uint32_t> touched_;
    // Scratch: per grid (its totals' slot), the photon's Y summed over each region.
    std::vector<std::pair<std::size_t, std::array<std::uint64_t, TallyLayout::kGatherRegions>>> totals_;
};

}  // namespace luxtrace
