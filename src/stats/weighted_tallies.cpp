#include "luxtrace/stats/weighted_tallies.hpp"

#include <stdexcept>

namespace luxtrace {

WeightedTallies::WeightedTallies(const TallyLayout& layout, std::span<const std::uint64_t> data,
                                 std::span<const double> weights)
    : layout_(layout), data_(data), weights_(layout.groups(), 1.0) {
    if (!weights.empty()) {
        if (weights.size() != layout.groups())
            throw std::logic_error("WeightedTallies: " + std::to_string(weights.size()) + " weights for " +
                                   std::to_string(layout.groups()) + " light groups");
        weights_.assign(weights.begin(), weights.end());
    }
    for (double w : weights_) {
        squares_.push_back(w * w);
        plain_ = plain_ && w == 1.0;
    }
    // A map shared by all groups is read at weight 1 (map_available() says whether that
    // is the scene's map).
    if (layout.map_groups() == layout.groups()) {
        map_weights_ = weights_;
        map_squares_ = squares_;
    } else {
        map_weights_.assign(layout.map_groups(), 1.0);
        map_squares_.assign(layout.map_groups(), 1.0);
    }
}

double WeightedTallies::side_sumsq(std::size_t i, std::size_t band) const {
    return sum(map_squares_, [&](std::size_t g) {
        return data_[layout_.side_slot(i, band, TallyLayout::kCountOdd, g)] +
               data_[layout_.side_slot(i, band, TallyLayout::kCountEven, g)] +
               data_[layout_.side_slot(i, band, TallyLayout::kRepeats, g)];
    });
}

double WeightedTallies::side_replicate(std::size_t i, std::size_t band, std::size_t r) const {
    return sum(map_weights_,
               [&](std::size_t g) { return data_[layout_.map_replicate(i, layout_.map_column(band, g), r)]; });
}

double WeightedTallies::cell_n(std::size_t det, std::size_t cell, std::size_t band) const {
    return sum(weights_, [&](std::size_t g) { return data_[layout_.detector_n(det, cell, band, g)]; });
}

double WeightedTallies::cell_q(std::size_t det, std::size_t cell, std::size_t band) const {
    return sum(squares_, [&](std::size_t g) { return data_[layout_.detector_q(det, cell, band, g)]; });
}

double WeightedTallies::total_n(std::size_t det) const {
    return sum(weights_, [&](std::size_t g) { return data_[layout_.detector_total_n(det, g)]; });
}

double WeightedTallies::total_q(std::size_t det) const {
    return sum(squares_, [&](std::size_t g) { return data_[layout_.detector_total_q(det, g)]; });
}

std::uint64_t WeightedTallies::received(std::size_t det) const {
    std::uint64_t n = 0;
    for (std::size_t g = 0; g < weights_.size(); ++g)
        if (weights_[g] > 0.0) n += data_[layout_.detector_received(det, g)];
    return n;
}

double WeightedTallies::replicate_n(std::size_t det, std::size_t r, std::size_t cell, std::size_t band) const {
    return sum(weights_, [&](std::size_t g) { return data_[layout_.detector_replicate_n(det, r, cell, band, g)]; });
}

double WeightedTallies::replicate_total_n(std::size_t det, std::size_t r) const {
    return sum(weights_, [&](std::size_t g) { return data_[layout_.detector_replicate_total_n(det, r, g)]; });
}

}  // namespace luxtrace
