#pragma once
// The scene's lights, and the choice of light and band for a photon in proportion to flux
// (SPEC §3), both by inversion of cumulative tables.
#include "luxtrace/light/light.hpp"

#include <vector>

namespace luxtrace {

class LightSet {
public:
    LightSet() = default;
    explicit LightSet(std::vector<Light> lights);
    const std::vector<Light>& lights() const { return lights_; }
    double total_flux_lm() const { return total_flux_lm_; }
    // The lights' maintenance factors weighted by flux, and whether they are all the same
    // (then maintained values are exactly this times the initial ones).
    double maintenance_factor() const { return maintenance_factor_; }
    bool maintenance_factor_uniform() const { return maintenance_factor_uniform_; }
    std::size_t pick_light(double u) const;
    int pick_band(std::size_t light, double u) const;

private:
    std::vector<Light> lights_;
    std::vector<double> light_cdf_;
    std::vector<std::vector<double>> band_cdf_;
    double total_flux_lm_ = 0.0;
    double maintenance_factor_ = 1.0;
    bool maintenance_factor_uniform_ = true;
};

}  // namespace luxtrace
