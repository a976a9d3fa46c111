#pragma once
// The direct part of an annual sensor grid's daylight coefficients, by shadow rays from
// the sensors (issue 37, docs/ANNUAL.md "Direct light by shadow rays"): for every cell,
// the light that reaches it straight from each sky entry (the patches, then the ground,
// AnnualSky's sky vector order) and from each sun, through glazing at its T(theta), past
// whatever stands in the way. The photons then count only what arrives after a diffuse
// or glossy event, and the two parts add (estimate/annual_coefficients.hpp).
//
// Units as AnnualCoefficients': lx per unit weight, i.e. the illuminance when the entry
// emits what its light group emits (the year's sum of its luminance, or for a sun its
// hour's direct normal illuminance). Each value is a stratified sample mean; `*_var` is
// the variance of that mean, estimated from its own samples. Floats: seven digits, far
// below the shadow rays' own error, and half the memory (a whole building's 100,000
// sensors x 4,071 entries and suns x 2 are 3.3 GB as floats).
#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace luxtrace {

struct DirectCoefficients {
    // Cells [first, first + cells) of the grid (a rank's share, or the whole grid).
    std::size_t cells = 0, entries = 0, suns = 0, first = 0;
    // With [annual] indirect = "gather": the gathered tallies' unit, lx per lm
    // (tracer/gather_table.hpp); 0: the grid gathers nothing.
    double gather_unit_lx_per_lm = 0.0;
    // ... and per cell, the gathered light's relative variance from the gather's own rays
    // (GatherTable::rel_var); empty without a gather.
    std::vector<float> gather_rel_var;
    // [entry][cell], [sun][cell].
    std::vector<float> sky_lx, sky_var;
    std::vector<float> sun_lx, sun_var;

    // The index of grid cell `cell` in row `row` (an entry, or a sun) of the arrays.
    std::size_t at(std::size_t row, std::size_t cell) const { return row * cells + (cell - first); }
    bool holds(std::size_t first_cell, std::size_t last_cell) const {
        return first <= first_cell && first_cell <= last_cell && last_cell <= first + cells;
    }
    double sky(std::size_t entry, std::size_t cell) const { return sky_lx[at(entry, cell)]; }
    double sun(std::size_t s, std::size_t cell) const { return sun_lx[at(s, cell)]; }
    // The arrays' values of grid cells [from, to), row by row (a row: an entry or a sun;
    // the rows of sky_lx, sky_var, sun_lx, sun_var and gather_rel_var in turn, rows()
    // in all), rows [row_first, row_last) of them, appended to `out`; unpack_cells puts
    // them back.
    std::size_t rows() const { return 2 * (entries + suns) + (gather_rel_var.empty() ? 0 : 1); }
    void pack_cells(std::size_t from, std::size_t to, std::vector<float>& out, std::size_t row_first = 0,
                    std::size_t row_last = ~std::size_t{0}) const {
        for_rows(*this, row_first, row_last, [&](const std::vector<float>& a, std::size_t row) {
            out.insert(out.end(), a.begin() + static_cast<std::ptrdiff_t>(at(row, from)),
                       a.begin() + static_cast<std::ptrdiff_t>(at(row, to)));
        });
    }
    void unpack_cells(std::span<const float> in, std::size_t from, std::size_t to, std::size_t row_first = 0,
                      std::size_t row_last = ~std::size_t{0}) {
        std::size_t k = 0;
        for_rows(*this, row_first, row_last, [&](std::vector<float>& a, std::size_t row) {
            for (std::size_t c = from; c < to; ++c) a[at(row, c)] = in[k++];
        });
    }
    // The words pack_cells writes for n cells (all rows, or rows [row_first, row_last)).
    std::size_t packed_words(std::size_t n, std::size_t row_first = 0, std::size_t row_last = ~std::size_t{0}) const {
        return n * (std::min(row_last, rows()) - std::min(row_first, rows()));
    }
    // f(array, its row) for the rows [row_first, row_last) of all (const or not, as `self`).
    template <class Self, class F>
    static void for_rows(Self& self, std::size_t row_first, std::size_t row_last, F&& f) {
        std::size_t row = 0;
        for (auto* a : {&self.sky_lx, &self.sky_var, &self.sun_lx, &self.sun_var, &self.gather_rel_var})
            for (std::size_t r = 0; r < (self.cells > 0 ? a->size() / self.cells : 0); ++r, ++row)
                if (row >= row_first && row < row_last) f(*a, r);
    }
    void resize(std::size_t cells_, std::size_t entries_, std::size_t suns_, std::size_t first_ = 0) {
        cells = cells_;
        entries = entries_;
        suns = suns_;
        first = first_;
        sky_lx.assign(entries * cells, 0.0F);
        sky_var = sky_lx;
        sun_lx.assign(suns * cells, 0.0F);
        sun_var = sun_lx;
    }
};

// Per detector of the scene (Scene::detectors' order): the grid's direct coefficients, or
// none (cells 0) for a detector that is no annual grid. Empty: the direct light comes from
// the photons ([annual] direct = "photons").
using AnnualDirect = std::vector<DirectCoefficients>;

}  // namespace luxtrace
