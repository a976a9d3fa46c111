#pragma once
// The tallies as a light scene sees them (issue 22): each light group's counts scaled by
// the scene's weight w_g for that group (all 1: the plain run). Every estimate reads the
// tallies through this, so an estimate of a light scene is the plain estimate's formula.
//
// Photons of different groups are disjoint, so sums and sums of squares combine exactly:
// a site's first moment is sum_g w_g S_g and its second sum_g w_g^2 Q_g, since a photon of
// group g scores w_g times its count. The per-photon variance Q/N - (S/N)^2 then includes
// the (negative) covariance between groups that sharing the N photons brings.
#include "luxtrace/tally/tally.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace {

class WeightedTallies {
public:
    // `weights`: one per light group; empty: every group at weight 1.
    WeightedTallies(const TallyLayout& layout, std::span<const std::uint64_t> data,
                    std::span<const double> weights = {});

    const TallyLayout& layout() const { return layout_; }
    // Every group at weight 1: the plain run.
    bool plain() const { return plain_; }
    std::span<const double> weights() const { return weights_; }  // per group
    // The surface map can be weighted: it keeps the groups apart, or the weights are plain.
    bool map_available() const { return plain_ || layout_.map_groups() == layout_.groups(); }

    // Side i (TallyLayout::side_index), one band: a slot weighted by w_g, and the second
    // moment sum over photons of (w n)^2 = sum_g w_g^2 (count + repeats).
    double side(std::size_t i, std::size_t band, TallyLayout::SurfaceSlot slot) const {
        return sum(map_weights_, [&](std::size_t g) { return data_[layout_.side_slot(i, band, slot, g)]; });
    }
    double side_sumsq(std::size_t i, std::size_t band) const;
    double side_replicate(std::size_t i, std::size_t band, std::size_t r) const;

    // Detector cell sums of eq. (6): n_c = sum_g w_g n_c,g and q_c = sum_g w_g^2 q_c,g.
    double cell_n(std::size_t det, std::size_t cell, std::size_t band) const;
    double cell_q(std::size_t det, std::size_t cell, std::size_t band) const;
    double total_n(std::size_t det) const;
    double total_q(std::size_t det) const;
    // Photons of the groups with weight > 0 that registered in the detector.
    std::uint64_t received(std::size_t det) const;
    double replicate_n(std::size_t det, std::size_t r, std::size_t cell, std::size_t band) const;
    double replicate_total_n(std::size_t det, std::size_t r) const;
    std::uint64_t replicate_photons(std::size_t r) const { return data_[layout_.replicate_photons(r)]; }

private:
    // sum_g w[g] x the word at slot(g).
    template <class Slot>
    double sum(const std::vector<double>& w, Slot slot) const {
        double s = 0.0;
        for (std::size_t g = 0; g < w.size(); ++g) s += w[g] * static_cast<double>(slot(g));
        return s;
    }

    const TallyLayout& layout_;
    std::span<const std::uint64_t> data_;
    std::vector<double> weights_, squares_;          // per group
    std::vector<double> map_weights_, map_squares_;  // per map group (1 when the map is shared)
    bool plain_ = true;
};

}  // namespace luxtrace
