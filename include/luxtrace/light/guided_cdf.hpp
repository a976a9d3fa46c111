#pragma once
// Inversion of a tabulated piecewise-constant distribution in O(1) expected time: a guide
// table (Chen and Asau, 1974) holds, for G equal slices of [0, 1), the cell that holds
// the slice's lower end, so a lookup starts at most a few cells before its answer. The
// answer is the cell a binary search finds (the last k with cdf[k] <= u), bit for bit:
// switching the search leaves every sample, and so every tally, as it was.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace luxtrace {

// `cdf` has n + 1 non-decreasing entries, cdf[0] = 0 and cdf[n] = 1.
inline std::vector<std::uint32_t> build_guide(const double* cdf, int n, int slices) {
    std::vector<std::uint32_t> guide(static_cast<std::size_t>(slices));
    int k = 0;
    for (int g = 0; g < slices; ++g) {
        const double lo = static_cast<double>(g) / slices;
        while (k + 1 < n && cdf[k + 1] <= lo) ++k;
        guide[static_cast<std::size_t>(g)] = static_cast<std::uint32_t>(k);
    }
    return guide;
}

// The cell k in [0, n) with cdf[k] <= u < cdf[k + 1] (zero-width cells skipped), for u
// in [0, 1).
inline int find_cell(const double* cdf, int n, const std::uint32_t* guide, int slices, double u) {
    int k = static_cast<int>(guide[std::min(slices - 1, static_cast<int>(u * slices))]);
    while (k > 0 && cdf[k] > u) --k;  // u * slices rounded up into the next slice
    while (k + 1 < n && cdf[k + 1] <= u) ++k;
    return k;
}

}  // namespace luxtrace
