#pragma once
// Contrast of the aerial image against everything else the eye sees (spec section 11): per pixel
// C = (L_aerial + L_background) / L_background, L_background the luminance of every image
// component but the aerial image's (tracer.hpp), over the pixels wholly inside the aerial image's
// outline (its border pixels hold light from outside it too).
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace airr {

// Contrasts the guidelines name: 1.5 just visible, 2 to 4 usable, 25 or more best.
inline const std::vector<double> default_contrast_thresholds = {1.5, 3, 25};
// An eye reads the aerial image when at least this share of it reaches the contrast asked for.
inline constexpr double legible_image_share = 0.9;

// One pixel's contrast: infinite where only the aerial image is lit, 1 where neither is.
double pixel_contrast(double aerial, double background);
// One pixel's aerial-image and background luminance from its components (component_count RGB
// triples in image_component order; any after them, each luminaire's own, are not read).
std::array<double, 2> aerial_and_background(const float* components);

struct contrast_summary {
  double aerial_luminance = 0;      // the aerial image's mean luminance inside its outline
  double background_luminance = 0;  // everything else's, there
  double contrast = 1;              // of the two means: (aerial + background) / background
  std::vector<double> share_above;  // of the outline's pixels whose contrast reaches each threshold
  int pixels = 0;                   // wholly inside the outline
};

// From components (RGB triples per pixel, row-major w x h: component_count of them in
// image_component order, and any more a session keeps after them), each value times
// `scale` (1 for an image, 1 / spp for sums); the outline in pixels (aerial_outline).
contrast_summary contrast_inside(const std::vector<float>& components, int w, int h,
                                 const std::array<glm::dvec2, 4>& outline, const std::vector<double>& thresholds,
                                 double scale = 1);

// Each pixel's contrast wholly inside the outline, NaN elsewhere (w x h, row-major).
std::vector<float> contrast_map(const std::vector<float>& components, int w, int h,
                                const std::array<glm::dvec2, 4>& outline);

}  // namespace airr
