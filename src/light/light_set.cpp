#include "luxtrace/light/light_set.hpp"

#include "luxtrace/light/uniform_sampling.hpp"

#include <cmath>

namespace luxtrace {

LightSet::LightSet(std::vector<Light> lights) : lights_(std::move(lights)) {
    double sum = 0.0;
    for (const Light& l : lights_) {
        sum += l.flux_lm;
        light_cdf_.push_back(sum);
        std::vector<double> bands;
        double s = 0.0;
        for (double share : l.band_share) bands.push_back(s += share);
        for (double& v : bands) v /= s;
        band_cdf_.push_back(std::move(bands));
    }
    total_flux_lm_ = sum;
    double mf = 0.0;
    for (const Light& l : lights_) {
        mf += l.maintenance_factor * l.flux_lm;
        maintenance_factor_uniform_ = maintenance_factor_uniform_ &&
                                      std::abs(l.maintenance_factor - lights_.front().maintenance_factor) <= 1e-12;
    }
    if (sum > 0.0) maintenance_factor_ = mf / sum;
    for (double& v : light_cdf_) v /= sum;
}

namespace {
// sample_cdf for the few entries of a light or band table: a scan, same answer.
std::size_t scan_cdf(const std::vector<double>& cdf, double u) {
    std::size_t i = 0;
    while (i + 1 < cdf.size() && cdf[i] <= u) ++i;
    return i;
}
}  // namespace

std::size_t LightSet::pick_light(double u) const {
    return light_cdf_.size() <= 16 ? scan_cdf(light_cdf_, u) : sample_cdf(light_cdf_, u);
}

int LightSet::pick_band(std::size_t light, double u) const {
    return static_cast<int>(scan_cdf(band_cdf_[light], u));  // at most a few bands
}

}  // namespace luxtrace
