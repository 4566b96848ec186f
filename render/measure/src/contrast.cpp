#include "airr/measure/contrast.hpp"

#include <cmath>
#include <limits>

#include "airr/core/color.hpp"
#include "airr/measure/aerial_outline.hpp"
#include "airr/render/tracer.hpp"

namespace airr {

double pixel_contrast(double aerial, double background) {
  // Noise can leave a sample's estimate a little below 0: no light is no light.
  aerial = std::max(0.0, aerial);
  background = std::max(0.0, background);
  if (background > 0) return (aerial + background) / background;
  return aerial > 0 ? std::numeric_limits<double>::infinity() : 1.0;
}

std::array<double, 2> aerial_and_background(const float* components) {
  std::array<double, 2> out{0, 0};
  for (int k = 0; k < component_count; ++k) {
    const float* v = components + 3 * k;
    out[k == component_aerial ? 0 : 1] += rec709_luminance(double(v[0]), double(v[1]), double(v[2]));
  }
  return out;
}

namespace {

// The aerial image's luminance and the background's at pixel i of w x h; a pixel's triples are
// as many as the vector holds for each (the seven, and each luminaire's in a designer's session).
std::array<double, 2> pixel_luminances(const std::vector<float>& components, int w, int h, std::size_t i,
                                       double scale) {
  const std::size_t per_pixel = components.size() / (std::size_t(w) * std::size_t(h));
  const auto [aerial, background] = aerial_and_background(components.data() + per_pixel * i);
  return {scale * aerial, scale * background};
}

// Whether pixel (x, y) lies wholly inside the outline: its edge pixels hold the aerial image's
// border, part of their light from outside it.
bool wholly_inside(const std::array<glm::dvec2, 4>& outline, int x, int y) {
  return inside_quad(outline, x, y) && inside_quad(outline, x + 1, y) && inside_quad(outline, x, y + 1) &&
         inside_quad(outline, x + 1, y + 1);
}

}  // namespace

contrast_summary contrast_inside(const std::vector<float>& components, int w, int h,
                                 const std::array<glm::dvec2, 4>& outline, const std::vector<double>& thresholds,
                                 double scale) {
  contrast_summary out;
  out.share_above.assign(thresholds.size(), 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!wholly_inside(outline, x, y)) continue;
      const auto [aerial, background] = pixel_luminances(components, w, h, std::size_t(y) * w + x, scale);
      out.aerial_luminance += aerial;
      out.background_luminance += background;
      const double c = pixel_contrast(aerial, background);
      for (std::size_t k = 0; k < thresholds.size(); ++k) out.share_above[k] += c >= thresholds[k];
      ++out.pixels;
    }
  }
  if (out.pixels == 0) return out;
  out.aerial_luminance /= out.pixels;
  out.background_luminance /= out.pixels;
  for (double& s : out.share_above) s /= out.pixels;
  out.contrast = pixel_contrast(out.aerial_luminance, out.background_luminance);
  return out;
}

std::vector<float> contrast_map(const std::vector<float>& components, int w, int h,
                                const std::array<glm::dvec2, 4>& outline) {
  std::vector<float> out(std::size_t(w) * h, std::numeric_limits<float>::quiet_NaN());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!wholly_inside(outline, x, y)) continue;
      const std::size_t i = std::size_t(y) * w + x;
      const auto [aerial, background] = pixel_luminances(components, w, h, i, 1.0);
      out[i] = float(pixel_contrast(aerial, background));
    }
  }
  return out;
}

}  // namespace airr
