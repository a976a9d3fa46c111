#include "luxtrace/material/glazing.hpp"

#include "luxtrace/core/math.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace luxtrace {

namespace {

double sq(double x) { return x * x; }

// One polarisation of the pane: the interface reflectance r, the pass transmissivity tau.
PaneOptics pane_polarisation(double r, double tau) {
    if (r >= 1.0) return {1.0, 0.0};  // grazing incidence: everything is reflected
    const double loss = (1.0 - r * tau) * (1.0 + r * tau);
    return {r + r * sq((1.0 - r) * tau) / loss, sq(1.0 - r) * tau / loss};
}

// Lookup bins over cos(theta) in [0, 1] for GlazingCurve::at.
constexpr std::size_t kLookupBins = 1024;

}  // namespace

double interface_reflectance(double ior) { return sq((ior - 1.0) / (ior + 1.0)); }

double max_pane_transmittance(double ior) {
    const double r0 = interface_reflectance(ior);
    return (1.0 - r0) / (1.0 + r0);
}

double pane_transmissivity(double normal_transmittance, double ior) {
    // T r0^2 tau^2 + (1 - r0)^2 tau - T = 0; its positive root, multiplied through by the
    // conjugate so that r0 -> 0 (ior -> 1) gives tau = T without cancellation.
    const double t = normal_transmittance, r0 = interface_reflectance(ior);
    const double a = sq(1.0 - r0);
    const double tau = 2.0 * t / (a + std::sqrt(a * a + 4.0 * sq(r0 * t)));
    return std::min(tau, 1.0);
}

PaneOptics pane_optics(double cos_i, double ior, double tau0) {
    const double c = std::clamp(cos_i, 0.0, 1.0);
    const double sin2_t = (1.0 - c * c) / (ior * ior);
    const double ct = std::sqrt(1.0 - sin2_t);
    const double rs = sq((c - ior * ct) / (c + ior * ct));
    const double rp = sq((ct - ior * c) / (ct + ior * c));
    const double tau = tau0 >= 1.0 ? 1.0 : std::exp(std::log(tau0) / ct);
    const PaneOptics s = pane_polarisation(rs, tau), p = pane_polarisation(rp, tau);
    return {0.5 * (s.reflectance + p.reflectance), 0.5 * (s.transmittance + p.transmittance)};
}

GlazingCurve::GlazingCurve(std::vector<double> cos_knots, const std::vector<PaneOptics>& values)
    : knots_(std::move(cos_knots)) {
    if (knots_.empty() || knots_.size() != values.size())
        throw std::invalid_argument("GlazingCurve: one value per knot, at least one knot");
    for (std::size_t k = 0; k < knots_.size(); ++k) {
        if (!(knots_[k] >= 0.0 && knots_[k] <= 1.0) || (k > 0 && !(knots_[k] > knots_[k - 1])))
            throw std::invalid_argument("GlazingCurve: knots must increase strictly within [0, 1]");
        reflect_.push_back(values[k].reflectance);
        pass_.push_back(values[k].reflectance + values[k].transmittance);
    }
    first_knot_.resize(kLookupBins + 1);
    std::size_t k = 0;
    for (std::size_t b = 0; b <= kLookupBins; ++b) {
        const double c = static_cast<double>(b) / static_cast<double>(kLookupBins);
        while (k + 2 < knots_.size() && knots_[k + 1] <= c) ++k;
        first_knot_[b] = static_cast<std::uint32_t>(k);
    }
}

GlazingCurve pane_curve(double normal_transmittance, double ior) {
    const double tau0 = pane_transmissivity(normal_transmittance, ior);
    std::vector<double> knots(kPaneKnots);
    std::vector<PaneOptics> values(kPaneKnots);
    for (int k = 0; k < kPaneKnots; ++k) {
        knots[static_cast<std::size_t>(k)] = static_cast<double>(k) / (kPaneKnots - 1);
        values[static_cast<std::size_t>(k)] = pane_optics(knots[static_cast<std::size_t>(k)], ior, tau0);
    }
    GlazingCurve curve(std::move(knots), values);
    curve.exact_below_ = kPaneExactBelow;
    curve.ior_ = ior;
    curve.tau0_ = tau0;
    return curve;
}

namespace {

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// cos of an angle in degrees, exact at 0 and 90.
double cos_deg(double a) { return a == 90.0 ? 0.0 : (a == 0.0 ? 1.0 : std::cos(a * kPi / 180.0)); }

}  // namespace

GlazingTableError check_glazing_table(const GlazingTable& t) {
    const std::size_t n = t.angles_deg.size();
    if (n < 2) return {"angles_deg", "needs at least 2 angles"};
    if (t.transmittance.size() != n)
        return {"transmittance_at", "has " + std::to_string(t.transmittance.size()) + " values for " +
                                        std::to_string(n) + " angles in 'angles_deg'"};
    if (t.reflectance.size() != n)
        return {"reflectance_at", "has " + std::to_string(t.reflectance.size()) + " values for " + std::to_string(n) +
                                      " angles in 'angles_deg'"};
    for (std::size_t i = 0; i < n; ++i) {
        const std::string entry = "entry " + std::to_string(i + 1);
        const double a = t.angles_deg[i];
        if (!(a >= 0.0 && a <= 90.0)) return {"angles_deg", entry + " (" + num(a) + ") is not in [0, 90]"};
        if (i > 0 && !(cos_deg(a) < cos_deg(t.angles_deg[i - 1])))
            return {"angles_deg",
                    entry + " (" + num(a) + ") does not increase strictly (after " + num(t.angles_deg[i - 1]) + ")"};
        if (!(t.transmittance[i] >= 0.0 && t.transmittance[i] <= 1.0))
            return {"transmittance_at", entry + " (" + num(t.transmittance[i]) + ") is not in [0, 1]"};
        if (!(t.reflectance[i] >= 0.0 && t.reflectance[i] <= 1.0))
            return {"reflectance_at", entry + " (" + num(t.reflectance[i]) + ") is not in [0, 1]"};
        if (t.transmittance[i] + t.reflectance[i] > 1.0 + 1e-12)
            return {"transmittance_at", entry + ": transmittance + reflectance = " +
                                            num(t.transmittance[i] + t.reflectance[i]) + " > 1 at " + num(a) + " deg"};
    }
    return {};
}

GlazingCurve table_curve(const GlazingTable& t) {
    const GlazingTableError e = check_glazing_table(t);
    if (!e.key.empty()) throw std::invalid_argument("glazing table: " + e.key + " " + e.what);
    // Knots increase in cos(theta): the table's last angle first.
    std::vector<double> knots;
    std::vector<PaneOptics> values;
    for (std::size_t i = t.angles_deg.size(); i-- > 0;) {
        knots.push_back(cos_deg(t.angles_deg[i]));
        values.push_back({t.reflectance[i], t.transmittance[i]});
    }
    return GlazingCurve(std::move(knots), values);
}

}  // namespace luxtrace
