#pragma once
// The replicates' common draws of the gathered light (tracer/gather_table.hpp). One photon
// arriving on a patch lights every sensor that sees it, so the cells' errors move
// together: the replicate years must draw them together, or a grid mean (mean DA over the
// dim back of a room) reads its error as if its cells were independent. Per light group the
// tally keeps, besides each cell's Y and Q, its sums X_r = sum Y T_r with the totals T_r of
// the grid's regions (tracer/gather_table.hpp's gather_regions) and the regions' sums and
// products. Then each cell's noise is drawn as
//     sigma_c (a_c . z_g + sqrt(1 - |a_c|^2) z_c),  a_c = L^-1 Cov(c, T) / sigma_c,
// with L L^T = Cov(T, T) and z_g one standard normal vector per group and replicate: the
// cell's regression on the regions' totals (a factor model). Its common part has exactly the
// measured covariance with every region's total, so each region's sum, and the dim cells of
// one region together, scatter as the run's photons make them; what the regions do not
// explain is the cell's own.
#include "luxtrace/tally/tally.hpp"

#include <cstddef>
#include <span>

namespace luxtrace {

constexpr std::size_t kGatherRegions = TallyLayout::kGatherRegions;
// Per light group: the regions' sums T_r (units), then L^-1 row by row (lower triangle,
// units^-1), rows of regions whose totals add nothing new (an empty region) all zero.
constexpr std::size_t kGatherFactorWords = kGatherRegions + TallyLayout::kGatherPairs;

// A group's factor from the regions' sums `sums` (kGatherRegions) and their products
// `products` (TallyLayout::gather_pair order, units^2) over `photons` photons.
void gather_group_factor(std::span<const double> sums, std::span<const double> products, double photons,
                         std::span<double> factor);

// A cell's loadings a (kGatherRegions) from its sum y, its standard deviation sd (of its
// sum, units) and its sums X_r (units^2), with its group's `factor`; |a| <= 1.
void gather_cell_loadings(std::span<const double> factor, double y, double sd, std::span<const double> x,
                          double photons, std::span<float> a);

}  // namespace luxtrace
