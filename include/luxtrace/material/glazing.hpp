#pragma once
// Glazing: a window pane modelled as one thin surface, alike from both sides. A photon is
// reflected specularly with probability R(theta), goes straight through (a thin pane: no
// displacement, no change of direction) with T(theta), or is absorbed. R and T come either
// from the physics of a clear or tinted pane (two Fresnel interfaces, absorption along the
// refracted path, every internal reflection summed per polarisation, as Radiance's `glass`
// primitive) or from a maker's table against the angle of incidence. Either is held as a
// curve piecewise linear in cos(theta), so a hit costs one table look-up
// (docs/DAYLIGHT.md "Glazing").
#include <cstdint>
#include <string>
#include <vector>

namespace luxtrace {

struct PaneOptics {
    double reflectance = 0.0;
    double transmittance = 0.0;
};

// Reflectance of one air-glass interface at normal incidence, ((n - 1) / (n + 1))^2.
double interface_reflectance(double ior);

// The most a pane of index `ior` can transmit at normal incidence (no absorption):
// (1 - r0)^2 / (1 - r0^2) = (1 - r0) / (1 + r0).
double max_pane_transmittance(double ior);

// The pane's internal transmissivity at normal incidence (the fraction one pass through
// the glass keeps) that gives the normal transmittance `normal_transmittance`: the root in
// (0, 1] of T = (1 - r0)^2 tau / (1 - r0^2 tau^2), in the form free of cancellation.
// Requires 0 < normal_transmittance <= max_pane_transmittance(ior).
double pane_transmissivity(double normal_transmittance, double ior);

// R and T of the pane at incidence cosine cos_i, per polarisation x in {s, p}:
//   tau = tau0^(1 / cos(theta_t))               (Beer-Lambert along the refracted path)
//   T_x = (1 - r_x)^2 tau / (1 - r_x^2 tau^2)
//   R_x = r_x + r_x (1 - r_x)^2 tau^2 / (1 - r_x^2 tau^2)
// with r_x the Fresnel reflectances of one interface; R, T the means over s and p.
PaneOptics pane_optics(double cos_i, double ior, double tau0);

// R(theta) and T(theta) piecewise linear in cos(theta) between knots, constant beyond the
// first and the last knot. `at` finds the segment by a uniform bin over [0, 1] and steps
// forward over the few knots a bin may hold. A pane's curve is evaluated exactly (closed
// form) below cos(theta) = kPaneExactBelow, where its R and T bend too sharply for knots.
class GlazingCurve {
public:
    GlazingCurve() = default;
    // cos_knots strictly increasing in [0, 1]; one value per knot.
    GlazingCurve(std::vector<double> cos_knots, const std::vector<PaneOptics>& values);

    PaneOptics at(double cos_i) const {
        const double c = cos_i < 0.0 ? 0.0 : (cos_i > 1.0 ? 1.0 : cos_i);
        if (c < exact_below_) return pane_optics(c, ior_, tau0_);
        if (c <= knots_.front()) return {reflect_.front(), pass_.front() - reflect_.front()};
        if (c >= knots_.back()) return {reflect_.back(), pass_.back() - reflect_.back()};
        auto b = static_cast<std::size_t>(c * static_cast<double>(first_knot_.size() - 1));
        std::size_t k = first_knot_[b];
        while (c > knots_[k + 1]) ++k;
        const double f = (c - knots_[k]) / (knots_[k + 1] - knots_[k]);
        const double r = reflect_[k] + f * (reflect_[k + 1] - reflect_[k]);
        const double p = pass_[k] + f * (pass_[k + 1] - pass_[k]);
        return {r, p - r};
    }

private:
    friend GlazingCurve pane_curve(double normal_transmittance, double ior);
    double exact_below_ = 0.0;  // cos(theta) under which pane_optics(ior_, tau0_) is used
    double ior_ = 1.0, tau0_ = 1.0;
    std::vector<double> knots_;    // cos(theta), increasing
    std::vector<double> reflect_;  // R at each knot
    std::vector<double> pass_;     // R + T at each knot (what is not absorbed)
    // For bin b = floor(c * (size - 1)): the last knot at or below b / (size - 1).
    std::vector<std::uint32_t> first_knot_;
};

// The physical pane as a curve on kPaneKnots knots uniform in cos(theta), exact below
// kPaneExactBelow (theta above 88.2 deg, where the internal reflections of a weakly
// absorbing pane turn within a few thousandths of cos(theta)): linear interpolation stays
// within 1e-5 of pane_optics for indices in [1.2, 3] (glazing_test).
inline constexpr int kPaneKnots = 1025;
inline constexpr double kPaneExactBelow = 1.0 / 32.0;
GlazingCurve pane_curve(double normal_transmittance, double ior);

// A maker's table: angles of incidence in degrees, strictly increasing in [0, 90], with
// the transmittance and reflectance at each; interpolated linearly in cos(theta).
struct GlazingTable {
    std::vector<double> angles_deg;
    std::vector<double> transmittance;
    std::vector<double> reflectance;
};
// What is wrong with a table (empty when nothing): the key at fault and the message.
struct GlazingTableError {
    std::string key;
    std::string what;
};
GlazingTableError check_glazing_table(const GlazingTable& t);
GlazingCurve table_curve(const GlazingTable& t);

}  // namespace luxtrace
