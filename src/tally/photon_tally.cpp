#include "luxtrace/tally/photon_tally.hpp"

#include <algorithm>

namespace luxtrace {

PhotonTally::PhotonTally() {
    touched_.reserve(64);
    regs_.reserve(32);
    arrivals_.reserve(64);
    indices_.reserve(32);
}

void PhotonTally::end(const TallyLayout& layout, TallyLayout::Counter fate, TallyBuffer& out) {
    out.add(layout.counter(fate), 1);
    if (layout.replicates() > 0) out.add(layout.replicate_photons(bin_.replicate), 1);
    if (arrivals_.size() > 1) add_repeats(out);  // a photon arriving once repeats nothing
    arrivals_.clear();
    if (!regs_.empty()) add_registrations(layout, out);
    if (!touched_.empty()) add_gathered(out);
}

void PhotonTally::add_gathered(TallyBuffer& out) {
    // Per cell Y, Y^2 / 2^s and Y T_r / 2^s, T_r the photon's sum over region r of the cell's
    // grid; per grid T_r and T_r T_q / 2^s (in 128 bits on the way: no overflow).
    __extension__ using Wide = unsigned __int128;
    constexpr int s = TallyLayout::kGatherSquareShift;
    constexpr std::size_t R = TallyLayout::kGatherRegions;
    auto scaled = [](std::uint64_t a, std::uint64_t b) {
        return static_cast<std::uint64_t>((static_cast<Wide>(a) * b + (Wide{1} << (s - 1))) >> s);
    };
    auto totals_of = [&](std::size_t slot) {
        return std::find_if(totals_.begin(), totals_.end(), [&](const auto& x) { return x.first == slot; });
    };
    totals_.clear();
    for (const std::uint32_t cell : touched_) {
        const GatherSlot& g = slots_[cell];
        auto t = totals_of(g.total);
        if (t == totals_.end()) t = totals_.insert(t, {g.total, {}});
        t->second[g.region] += gathered_[cell];
    }
    for (const std::uint32_t cell : touched_) {
        const std::uint64_t y = gathered_[cell];
        const GatherSlot& g = slots_[cell];
        const auto& total = totals_of(g.total)->second;
        const std::size_t slot = g.first + bin_.detector_column * g.column_stride;
        out.add_through(slot, y);
        out.add_through(slot + 1, scaled(y, y));
        for (std::size_t r = 0; r < R; ++r)
            if (total[r] != 0) out.add_through(slot + 2 + r, scaled(y, total[r]));
        gathered_[cell] = 0;
    }
    for (const auto& [first, t] : totals_) {
        const std::size_t slot = first + bin_.detector_column * TallyLayout::kGatherTotalWords;
        for (std::size_t r = 0; r < R; ++r) {
            if (t[r] == 0) continue;
            out.add(slot + r, t[r]);
            for (std::size_t q = r; q < R; ++q)
                if (t[q] != 0) out.add(slot + R + TallyLayout::gather_pair(r, q), scaled(t[r], t[q]));
        }
    }
    touched_.clear();
}

void PhotonTally::add_repeats(TallyBuffer& out) {
    // Sum over sides of n (n - 1), n this photon's arrivals on the side (kRepeats). Most
    // paths are short: compare pairs; a long one (a mirror trap) is sorted instead.
    const std::size_t m = arrivals_.size();
    if (m > 32) {
        std::sort(arrivals_.begin(), arrivals_.end());
        for (std::size_t i = 0; i < m;) {
            std::size_t j = i + 1;
            while (j < m && arrivals_[j] == arrivals_[i]) ++j;
            if (const std::uint64_t n = j - i; n > 1) out.add(arrivals_[i], n * (n - 1));
            i = j;
        }
        return;
    }
    // Each pair (i < j) on one side adds 2: sum over pairs of 2 = n (n - 1).
    for (std::size_t i = 1; i < m; ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (arrivals_[j] == arrivals_[i]) out.add(arrivals_[i], 2);
}

void PhotonTally::add_registrations(const TallyLayout& layout, TallyBuffer& out) {
    // E_i of eq. (6): how many times this photon registered in each cell, in its column;
    // detectors occupy disjoint ascending index ranges, so sorted slots group them.
    const std::size_t R = layout.replicates();
    const std::size_t group = bin_.detector_column % layout.groups();
    indices_.clear();
    const bool apart = layout.any_direct_apart();
    const bool gathered = layout.any_gathered();
    for (const Registration& r : regs_)
        if (!(apart && r.direct && layout.direct_apart(r.detector)) &&
            !(gathered && r.after_diffuse && layout.gathered(r.detector)))
            indices_.push_back(layout.detector_cell(r.detector, r.cell, bin_.detector_column));
    std::sort(indices_.begin(), indices_.end());
    std::size_t det = 0;  // detectors are visited in index order
    std::uint32_t open = UINT32_MAX;
    std::uint64_t in_detector = 0;  // this photon's registrations in the open detector
    auto close_detector = [&] {
        if (open == UINT32_MAX) return;
        out.add(layout.detector_received(open, group), 1);
        out.add(layout.detector_total_n(open, group), in_detector);
        out.add(layout.detector_total_q(open, group), in_detector * in_detector);
        if (R > 0) out.add(layout.detector_replicate_total_n(open, bin_.replicate, group), in_detector);
    };
    for (std::size_t i = 0; i < indices_.size();) {
        std::size_t j = i;
        while (j < indices_.size() && indices_[j] == indices_[i]) ++j;
        const std::uint64_t e = j - i;
        const std::size_t n_c = indices_[i];
        while (det + 1 < layout.detector_count() && n_c >= layout.detector_cell(det + 1, 0, 0)) ++det;
        out.add(n_c, e);          // n_c
        out.add(n_c + 1, e * e);  // q_c
        if (R > 0) out.add(layout.detector_replicate_of(det, n_c, bin_.replicate), e);
        if (det != open) {
            close_detector();
            open = static_cast<std::uint32_t>(det);
            in_detector = 0;
        }
        in_detector += e;
        i = j;
    }
    close_detector();
    // A grid whose direct light comes from shadow rays keeps no direct count: its slots stay
    // zero and take no memory (WordArray), and no reduction sends them.
    if (layout.direct_scores())
        for (const Registration& r : regs_)
            if (r.direct && !(apart && layout.direct_apart(r.detector)))
                out.add(layout.detector_direct(r.detector, r.cell, bin_.detector_column), 1);
    regs_.clear();
}

}  // namespace luxtrace
