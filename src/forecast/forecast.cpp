#include "luxtrace/forecast/forecast.hpp"

#include <algorithm>
#include <cmath>

namespace luxtrace {

double photon_rate(const std::vector<HistoryPoint>& h) {
    if (h.size() < 2) return h.empty() || h.back().time_s <= 0.0 ? 0.0 : h.back().photons / h.back().time_s;
    const std::size_t first = h.size() >= 4 ? h.size() / 2 : 0;
    double st = 0, sn = 0, stt = 0, stn = 0;
    const double m = static_cast<double>(h.size() - first);
    for (std::size_t i = first; i < h.size(); ++i) {
        st += h[i].time_s;
        sn += h[i].photons;
        stt += h[i].time_s * h[i].time_s;
        stn += h[i].time_s * h[i].photons;
    }
    const double den = m * stt - st * st;
    if (den <= 0.0) return h.back().time_s > 0.0 ? h.back().photons / h.back().time_s : 0.0;
    return (m * stn - st * sn) / den;
}

namespace {

Forecast finish(const std::vector<HistoryPoint>& h, double photons_needed, double rate) {
    Forecast f;
    if (!(rate > 0.0) || !std::isfinite(photons_needed)) return f;
    f.valid = true;
    f.photons_needed = photons_needed;
    f.time_s = h.back().time_s + (photons_needed - h.back().photons) / rate;
    return f;
}

}  // namespace

Forecast forecast_error(const std::vector<HistoryPoint>& h, double goal, double rate) {
    if (h.empty() || !(goal > 0.0)) return {};
    const double n_last = h.back().photons;
    // log C = log(sigma) + log(N) / 2 for every point; average with weights N.
    double sw = 0.0, swl = 0.0;
    for (const HistoryPoint& p : h) {
        if (p.photons < 0.1 * n_last || !(p.value > 0.0) || !std::isfinite(p.value)) continue;
        const double log_c = std::log(p.value) + 0.5 * std::log(p.photons);
        sw += p.photons;
        swl += p.photons * log_c;
    }
    if (sw <= 0.0) return {};
    const double c = std::exp(swl / sw);
    return finish(h, (c / goal) * (c / goal), rate);
}

Forecast forecast_error_fitted(const std::vector<HistoryPoint>& h, double goal, double rate) {
    if (h.empty() || !(goal > 0.0)) return {};
    const double n_last = h.back().photons;
    double sw = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0, n_min = n_last;
    int points = 0;
    for (const HistoryPoint& p : h) {
        if (p.photons < 0.1 * n_last || !(p.value > 0.0) || !std::isfinite(p.value) || !(p.photons > 0.0)) continue;
        const double w = p.photons, x = std::log(p.photons), y = std::log(p.value);
        sw += w;
        sx += w * x;
        sy += w * y;
        sxx += w * x * x;
        sxy += w * x * y;
        n_min = std::min(n_min, p.photons);
        ++points;
    }
    if (sw <= 0.0) return {};
    double alpha = 0.5;
    const double den = sw * sxx - sx * sx;
    if (points >= 3 && n_last >= 4.0 * n_min && den > 0.0) alpha = std::max(0.5, -(sw * sxy - sx * sy) / den);
    // log C = mean(log sigma + alpha log N) over the weighted points.
    const double log_c = (sy + alpha * sx) / sw;
    Forecast f = finish(h, std::pow(std::exp(log_c) / goal, 1.0 / alpha), rate);
    f.exponent = alpha;
    return f;
}

Forecast forecast_count(const std::vector<HistoryPoint>& h, double goal, double rate) {
    if (h.empty()) return {};
    double snn = 0.0, snv = 0.0;
    for (const HistoryPoint& p : h) {
        snn += p.photons * p.photons;
        snv += p.photons * p.value;
    }
    if (!(snv > 0.0)) return {};
    return finish(h, goal * snn / snv, rate);
}

}  // namespace luxtrace
