#pragma once
// The render view's false-colour scales. The luminance view: each pixel's luminance (CIE Y of its
// linear RGB), viridis over `decades` decades of a logarithmic scale whose top is the luminance
// the exposure shows as white. The contrast view: each pixel's contrast (measure/contrast.hpp),
// viridis over a logarithmic scale from 1 (no aerial image) to `top`.
#include <array>
#include <cstdint>

namespace airr::ui {

struct luminance_scale {
  double top = 1;  // in the image's units (cd/m2 or relative)
  int decades = 3;

  // The render view's scale: its top is the luminance `exposure` shows as white.
  static luminance_scale for_exposure(double exposure) { return {.top = 1.0 / exposure}; }

  double bottom() const;
  // Where a luminance lies on the scale: 0 at the bottom (and below), 1 at the top (and above).
  double position(double luminance) const;
  // The false colour of a pixel's linear RGB.
  std::array<std::uint8_t, 3> colour(const float* rgb) const;
};

struct contrast_scale {
  double top = 100;

  // 0 at a contrast of 1 (and below), 1 at the top (and above).
  double position(double contrast) const;
  // The false colour of a pixel's components (component_count RGB triples).
  std::array<std::uint8_t, 3> colour(const float* components) const;
};

}  // namespace airr::ui
