#pragma once
// The render view's luminance view: each pixel's luminance (CIE Y of its linear RGB) in false
// colour, viridis over `decades` decades of a logarithmic scale whose top is the luminance the
// exposure shows as white.
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

}  // namespace airr::ui
