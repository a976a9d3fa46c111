#pragma once
// From luminance (cd/m^2) to display values: the automatic operator (improved
// Tumblin-Rushmeier with Reinhard's white-level compression, parameters estimated on a
// sparse sample grid in two passes), a plain exposure/gamma mapping, and a false-colour
// luminance scale. docs/TONE_MAPPING.md gives the formulas and their sources.
#include "luxtrace/render/image_io.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace luxtrace {

// The display the operator aims at (Tumblin-Rushmeier's display model).
struct DisplayModel {
    double adaptation_cd_m2 = 30.0;  // L_da: the viewer's adaptation at the display
    double max_cd_m2 = 100.0;        // L_dmax: display white
    double max_contrast = 100.0;     // C_max: the display's usable contrast
};

// What the two passes over the sample grid found.
struct AutoToneParams {
    double adaptation_cd_m2 = 0.0;        // L_wa: final log-average (pass 2)
    double white_cd_m2 = 0.0;             // L_white: shown as display white
    double first_adaptation_cd_m2 = 0.0;  // pass-1 log-average
    std::size_t grid_points = 0;          // points on the sample grid
    std::size_t points_used = 0;          // points kept for the final log-average
};

// Two passes over a sparse grid (about 128 x 128 points) of the luminance image.
AutoToneParams estimate_auto_tone(const std::vector<double>& luminance, int width, int height);

// The automatic operator: luminance -> display value in [0, 1] (linear, before gamma).
// Monotone; 0 -> 0; L_white -> 1; values above white are clipped to 1.
class AutoToneMap {
public:
    explicit AutoToneMap(const AutoToneParams& p, const DisplayModel& d = {});
    double operator()(double luminance_cd_m2) const;
    // Tumblin-Rushmeier display luminance over L_dmax, before the white compression.
    double tumblin_rushmeier(double luminance_cd_m2) const;

private:
    double adaptation_ = 0.0, exponent_ = 1.0, scale_ = 0.0, white_ = 1.0;
};

// Exposure mapping: (L / white)^(1/gamma), clipped to [0, 1].
double exposure_map(double luminance_cd_m2, double white_cd_m2, double gamma);

// Display encoding of a linear display value: v^(1/gamma) in [0, 1].
double encode_gamma(double linear, double gamma);

// Perceptual colour map (viridis): t in [0, 1] -> RGB in [0, 1].
std::array<double, 3> colour_map(double t);

// The luminance range of a false-colour picture and its legend.
struct FalseColourScale {
    double min_cd_m2 = 0.1, max_cd_m2 = 100.0;
    bool log_scale = true;

    // The default log scale: three decades below `max`.
    static FalseColourScale log_below(double max_cd_m2, double decades = 3.0);
    // Position of a luminance on the colour bar, clipped to [0, 1].
    double position(double luminance_cd_m2) const;
    // 5 to 7 round values inside [min, max] for the legend (1-2-5 or 1-3 steps).
    std::vector<double> ticks() const;
};

// Whole images. Colour (bands R, G, B) keeps each pixel's band ratios and maps its
// luminance (the band sum); other band sets are shown grey.
DisplayImage tone_map_auto(const LuminanceImage& image, double gamma, AutoToneParams* used = nullptr);
DisplayImage tone_map_exposure(const LuminanceImage& image, double white_cd_m2, double gamma);
DisplayImage tone_map_false_colour(const LuminanceImage& image, const FalseColourScale& scale);

}  // namespace luxtrace
