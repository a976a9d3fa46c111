#include "luxtrace/light/sky_directions.hpp"

#include <stdexcept>

namespace luxtrace {

SkyDirections::SkyDirections(const std::optional<SkyModel>& sky, double zenith_luminance_cd_m2,
                             double ground_luminance_cd_m2)
    : luminance_{sky, zenith_luminance_cd_m2, ground_luminance_cd_m2} {
    std::vector<DirectionTable::Cell> cells(static_cast<std::size_t>(kRows) * kColumns);
    double horizontal = 0.0;
    const double a_half = 0.5 * DirectionTable::kDegree;
    for (int row = 0; row < kRows; ++row) {
        const double mu_hi = DirectionTable::mu_top(row), mu_lo = DirectionTable::mu_bottom(row);
        const double mu_half = 0.5 * (mu_hi - mu_lo);
        const bool above = row < kRows / 2;
        for (int col = 0; col < kColumns; ++col) {
            DirectionTable::Cell& c = cells[static_cast<std::size_t>(row) * kColumns + static_cast<std::size_t>(col)];
            if (!above) {
                c.weight = ground_luminance_cd_m2 * (mu_hi - mu_lo) * DirectionTable::kDegree;
                continue;
            }
            if (!sky) continue;
            const DirectionTable::CellIntegral in =
                DirectionTable::integrate(row, col, [&](double zenith, double azimuth) {
                    return sky->relative_luminance(zenith, azimuth);
                });
            if (in.integral > 0.0) {
                c.slope_s = DirectionTable::slope(in.moment_s / in.integral);
                c.slope_a = DirectionTable::slope(in.moment_a / in.integral);
                // As sampled: the linear density's mean cos Z, the cell's own to the rule's accuracy.
                horizontal += in.integral * zenith_luminance_cd_m2 * mu_half * a_half *
                              (mu_hi - 2.0 * mu_half * DirectionTable::mean_s(c.slope_s));
            }
            c.weight = in.integral * zenith_luminance_cd_m2 * mu_half * a_half;
        }
    }
    try {
        table_ = DirectionTable(kRows, cells);
    } catch (const std::invalid_argument&) {
        throw std::invalid_argument("the sky and ground emit nothing");
    }
    horizontal_lx_ = horizontal;
}

}  // namespace luxtrace
