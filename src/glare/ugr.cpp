#include "luxtrace/glare/ugr.hpp"

#include <cmath>
#include <limits>

namespace luxtrace {

double guth_position_index(double alpha_deg, double beta_deg) {
    const double a = alpha_deg, b = beta_deg;
    const double ln_p = (35.2 - 0.31889 * a - 1.22 * std::exp(-2.0 * a / 9.0)) * 1e-3 * b +
                        (21.0 + 0.26667 * a - 0.002963 * a * a) * 1e-5 * b * b;
    return std::exp(ln_p);
}

UgrEstimate estimate_ugr(const std::vector<GlareSource>& sources, double indirect_illuminance_lx,
                         double indirect_sigma_rel) {
    UgrEstimate u;
    u.indirect_illuminance_lx = indirect_illuminance_lx;
    u.indirect_sigma_rel = indirect_sigma_rel;
    u.background_luminance_cd_m2 = indirect_illuminance_lx / kPi;
    for (const GlareSource& s : sources) u.glare_sum += s.term();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (u.glare_sum > 0.0 && u.background_luminance_cd_m2 > 0.0) {
        u.ugr = 8.0 * std::log10(0.25 * u.glare_sum / u.background_luminance_cd_m2);
        u.ugr_sigma = 8.0 / std::log(10.0) * indirect_sigma_rel;
    } else {
        u.ugr = nan;
        u.ugr_sigma = nan;
    }
    return u;
}

}  // namespace luxtrace
