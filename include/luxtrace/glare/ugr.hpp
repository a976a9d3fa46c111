#pragma once
// The Unified Glare Rating of CIE 117:1995 at an observer:
//   UGR = 8 log10( (0.25 / Lb) sum over luminaires of L^2 omega / p^2 )
// with Lb = E_ind / pi the background luminance from the indirect vertical illuminance at
// the eye, L, omega and p each luminaire's luminance, solid angle and Guth position index
// (observer.hpp). docs/GLARE.md has the choices made and the limits.
#include "luxtrace/glare/observer.hpp"

#include <vector>

namespace luxtrace {

// Guth's position index in the analytic form CIE 117:1995 gives for its table:
//   ln p = (35.2 - 0.31889 alpha - 1.22 e^(-2 alpha / 9)) 1e-3 beta
//        + (21 + 0.26667 alpha - 0.002963 alpha^2) 1e-5 beta^2,
// alpha, beta in degrees (GlareSource). p = 1 on the line of sight.
double guth_position_index(double alpha_deg, double beta_deg);

// CIE 117's domain of validity: sources of 0.0003 to 0.1 sr, UGR from 10 to 30.
constexpr double kUgrMinSolidAngleSr = 3e-4;
constexpr double kUgrMaxSolidAngleSr = 0.1;
constexpr double kUgrMin = 10.0;
constexpr double kUgrMax = 30.0;

struct UgrEstimate {
    double indirect_illuminance_lx = 0.0;     // E_ind at the eye
    double indirect_sigma_rel = 0.0;          // its relative standard error
    double background_luminance_cd_m2 = 0.0;  // Lb = E_ind / pi
    double glare_sum = 0.0;                   // sum of L^2 omega / p^2
    // NaN when there is no luminaire in view or no indirect light was registered.
    double ugr = 0.0;
    // First order: dUGR = 8 / ln(10) dLb / Lb, and Lb's relative error is E_ind's.
    double ugr_sigma = 0.0;
    bool in_cie117_range() const { return ugr >= kUgrMin && ugr <= kUgrMax; }
};

UgrEstimate estimate_ugr(const std::vector<GlareSource>& sources, double indirect_illuminance_lx,
                         double indirect_sigma_rel);

}  // namespace luxtrace
