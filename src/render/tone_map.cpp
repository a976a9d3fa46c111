// Tone mapping; the formulas and their sources are in docs/TONE_MAPPING.md.
#include "luxtrace/render/tone_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxtrace {

namespace {

// About this many sample points along the longer image side.
constexpr int kGridPoints = 128;
// Pass 1 drops this fraction of the brightest sample points (light sources, highlights).
constexpr double kBrightestDropped = 0.01;
// Offset inside the logarithm of the log-average, relative to the pass-1 white level:
// keeps black pixels finite without moving the average of the lit ones.
constexpr double kLogOffset = 1e-6;
// Display white is at least this many times the adaptation luminance, so a picture of
// low contrast is not stretched until its average surface looks white.
constexpr double kMinWhiteOverAdaptation = 3.0;

double log_average(const std::vector<double>& v, double offset) {
    double s = 0.0;
    for (double x : v) s += std::log(x + offset);
    return std::exp(s / static_cast<double>(v.size())) - offset;
}

// Tumblin-Rushmeier's contrast-sensitivity exponent of an adaptation luminance.
double tr_gamma(double l) { return l > 100.0 ? 2.655 : 1.855 + 0.4 * std::log10(l + 2.3e-5); }

std::uint8_t to_byte(double v) {
    if (!(v > 0.0)) return 0;  // also NaN
    if (v >= 1.0) return 255;
    return static_cast<std::uint8_t>(std::lround(v * 255.0));
}

// A display value per pixel from its luminance; colour pictures keep the band ratios.
template <class Map>
DisplayImage map_image(const LuminanceImage& image, double gamma, Map&& map) {
    DisplayImage out(image.width, image.height);
    const bool rgb = image.is_rgb();
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double l = image.luminance(x, y);
            const double v = map(l);
            std::uint8_t* p = out.pixel(x, y);
            if (rgb && l > 0.0) {
                // White light has equal band shares, so 3 L_b / L = 1 for a grey surface.
                for (int b = 0; b < 3; ++b) p[b] = to_byte(encode_gamma(v * 3.0 * image.at(x, y, b) / l, gamma));
            } else {
                p[0] = p[1] = p[2] = to_byte(encode_gamma(v, gamma));
            }
        }
    return out;
}

}  // namespace

AutoToneParams estimate_auto_tone(const std::vector<double>& luminance, int width, int height) {
    AutoToneParams p;
    if (width <= 0 || height <= 0) return p;
    const int stride = std::max(1, (std::max(width, height) + kGridPoints - 1) / kGridPoints);
    std::vector<double> samples;
    for (int y = stride / 2; y < height; y += stride)
        for (int x = stride / 2; x < width; x += stride) {
            const double l = luminance[static_cast<std::size_t>(y) * width + x];
            samples.push_back(std::isfinite(l) ? std::max(l, 0.0) : 0.0);
        }
    p.grid_points = samples.size();
    std::sort(samples.begin(), samples.end());
    // Pass 1: without the brightest 1 %, the largest value left is the initial white level
    // and the log-average of what is left the initial adaptation.
    const auto dropped = static_cast<std::size_t>(std::floor(kBrightestDropped * static_cast<double>(samples.size())));
    samples.resize(samples.size() - dropped);
    if (samples.empty() || !(samples.back() > 0.0)) return p;  // a black picture
    const double white1 = samples.back();
    const double offset = kLogOffset * white1;
    p.first_adaptation_cd_m2 = log_average(samples, offset);
    // Pass 2: points the display cannot separate from black at that adaptation (below
    // L_wa1 / C_max) or brighter than the initial white do not set the adaptation.
    const double dark = p.first_adaptation_cd_m2 / DisplayModel{}.max_contrast;
    std::vector<double> kept;
    for (double l : samples)
        if (l >= dark && l <= white1) kept.push_back(l);
    if (kept.empty()) kept = samples;
    p.points_used = kept.size();
    p.adaptation_cd_m2 = log_average(kept, offset);
    p.white_cd_m2 = std::max(white1, kMinWhiteOverAdaptation * p.adaptation_cd_m2);
    return p;
}

AutoToneMap::AutoToneMap(const AutoToneParams& p, const DisplayModel& d) : adaptation_(p.adaptation_cd_m2) {
    if (!(adaptation_ > 0.0) || !(p.white_cd_m2 > 0.0)) {
        adaptation_ = 0.0;  // a black picture stays black
        return;
    }
    const double gamma_w = tr_gamma(adaptation_);
    const double gamma_d = tr_gamma(d.adaptation_cd_m2);
    const double gamma_wd = gamma_w / (1.855 + 0.4 * std::log10(d.adaptation_cd_m2));
    const double m = std::pow(std::sqrt(d.max_contrast), gamma_wd - 1.0);
    exponent_ = std::max(gamma_w / gamma_d, 1e-3);  // gamma_w -> 0 only for L_wa -> 0
    scale_ = m * d.adaptation_cd_m2 / d.max_cd_m2;
    white_ = tumblin_rushmeier(p.white_cd_m2);
}

double AutoToneMap::tumblin_rushmeier(double l) const {
    if (!(adaptation_ > 0.0) || !(l > 0.0)) return 0.0;
    return scale_ * std::pow(l / adaptation_, exponent_);
}

double AutoToneMap::operator()(double l) const {
    const double x = tumblin_rushmeier(l);
    if (!(x > 0.0)) return 0.0;
    if (!std::isfinite(x)) return 1.0;
    // Reinhard's white-level compression: x = white_ goes to exactly 1.
    const double y = x * (1.0 + x / (white_ * white_)) / (1.0 + x);
    return std::min(y, 1.0);
}

double encode_gamma(double linear, double gamma) {
    if (!(linear > 0.0)) return 0.0;
    if (linear >= 1.0) return 1.0;
    return std::pow(linear, 1.0 / gamma);
}

double exposure_map(double l, double white, double gamma) {
    if (!(white > 0.0)) return 0.0;
    return encode_gamma(l / white, gamma);
}

std::array<double, 3> colour_map(double t) {
    // viridis (van der Walt and Smith, matplotlib 2.0) at 17 even steps.
    static constexpr double kViridis[17][3] = {{0.267, 0.005, 0.329}, {0.282, 0.095, 0.417}, {0.279, 0.175, 0.483},
                                               {0.259, 0.252, 0.525}, {0.230, 0.322, 0.546}, {0.199, 0.388, 0.555},
                                               {0.173, 0.449, 0.558}, {0.149, 0.508, 0.557}, {0.128, 0.567, 0.551},
                                               {0.121, 0.626, 0.533}, {0.158, 0.684, 0.502}, {0.246, 0.739, 0.452},
                                               {0.369, 0.789, 0.383}, {0.516, 0.831, 0.294}, {0.678, 0.864, 0.190},
                                               {0.846, 0.887, 0.100}, {0.993, 0.906, 0.144}};
    if (!(t > 0.0)) t = 0.0;
    t = std::min(t, 1.0) * 16.0;
    const int i = std::min(static_cast<int>(t), 15);
    const double f = t - i;
    std::array<double, 3> c{};
    for (int k = 0; k < 3; ++k) c[k] = kViridis[i][k] + f * (kViridis[i + 1][k] - kViridis[i][k]);
    return c;
}

FalseColourScale FalseColourScale::log_below(double max_cd_m2, double decades) {
    FalseColourScale s;
    s.max_cd_m2 = max_cd_m2 > 0.0 ? max_cd_m2 : 1.0;
    s.min_cd_m2 = s.max_cd_m2 * std::pow(10.0, -decades);
    s.log_scale = true;
    return s;
}

double FalseColourScale::position(double l) const {
    double t = 0.0;
    if (log_scale) {
        if (l > 0.0) t = std::log10(l / min_cd_m2) / std::log10(max_cd_m2 / min_cd_m2);
    } else {
        t = (l - min_cd_m2) / (max_cd_m2 - min_cd_m2);
    }
    if (!(t > 0.0)) return 0.0;
    return std::min(t, 1.0);
}

std::vector<double> FalseColourScale::ticks() const {
    const double lo = min_cd_m2, hi = max_cd_m2;
    std::vector<double> best;
    auto better = [&](const std::vector<double>& c) {
        auto score = [](std::size_t n) {
            return n >= 5 && n <= 7 ? 0 : (n < 5 ? 5 - static_cast<int>(n) : static_cast<int>(n) - 7);
        };
        return best.empty() || score(c.size()) < score(best.size());
    };
    const double tol = 1e-9 * (hi - lo);
    if (log_scale && lo > 0.0) {
        // Mantissa sets from coarse to fine; the first with 5..7 ticks wins.
        static const std::vector<std::vector<double>> sets = {{1}, {1, 3}, {1, 2, 5}, {1, 1.5, 2, 3, 5, 7}};
        for (const auto& set : sets) {
            std::vector<double> c;
            for (int k = static_cast<int>(std::floor(std::log10(lo))) - 1;
                 k <= static_cast<int>(std::ceil(std::log10(hi))); ++k)
                for (double m : set) {
                    const double v = m * std::pow(10.0, k);
                    if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) c.push_back(v);
                }
            if (better(c)) best = c;
            if (best.size() >= 5 && best.size() <= 7) break;
        }
        return best;
    }
    // Linear: the first step (in order of roundness) that gives 5..7 ticks.
    const int top = static_cast<int>(std::ceil(std::log10(std::max(hi - lo, 1e-300))));
    for (double step_m : {1.0, 2.0, 5.0, 2.5, 4.0, 1.5, 3.0})
        for (int k = top - 2; k <= top; ++k) {
            const double step = step_m * std::pow(10.0, k);
            std::vector<double> c;
            for (double v = std::ceil((lo - tol) / step) * step; v <= hi + tol && c.size() < 100; v += step)
                c.push_back(std::abs(v) < tol ? 0.0 : v);
            if (better(c)) best = c;
            if (best.size() >= 5 && best.size() <= 7) return best;
        }
    return best;
}

DisplayImage tone_map_auto(const LuminanceImage& image, double gamma, AutoToneParams* used) {
    const AutoToneParams p = estimate_auto_tone(image.luminance(), image.width, image.height);
    if (used != nullptr) *used = p;
    const AutoToneMap op(p);
    return map_image(image, gamma, op);
}

DisplayImage tone_map_exposure(const LuminanceImage& image, double white, double gamma) {
    return map_image(image, gamma,
                     [white](double l) { return white > 0.0 ? std::min(std::max(l / white, 0.0), 1.0) : 0.0; });
}

DisplayImage tone_map_false_colour(const LuminanceImage& image, const FalseColourScale& scale) {
    DisplayImage out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::array<double, 3> c = colour_map(scale.position(image.luminance(x, y)));
            std::uint8_t* p = out.pixel(x, y);
            for (int k = 0; k < 3; ++k) p[k] = to_byte(c[k]);
        }
    return out;
}

}  // namespace luxtrace
