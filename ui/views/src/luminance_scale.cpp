#include "airr/ui/views/luminance_scale.hpp"

#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "airr/core/color.hpp"
#include "airr/measure/contrast.hpp"
#include "airr/ui/views/plot_widget.hpp"

namespace airr::ui {

double luminance_scale::bottom() const { return top * std::pow(10.0, -decades); }

double luminance_scale::position(double luminance) const {
  if (!(luminance > bottom())) return 0;
  return std::clamp(std::log10(luminance / bottom()) / decades, 0.0, 1.0);
}

static std::array<std::uint8_t, 3> viridis_rgb(double t) {
  const ImU32 c = viridis(t);
  return {std::uint8_t(c >> IM_COL32_R_SHIFT), std::uint8_t(c >> IM_COL32_G_SHIFT),
          std::uint8_t(c >> IM_COL32_B_SHIFT)};
}

std::array<std::uint8_t, 3> luminance_scale::colour(const float* rgb) const {
  return viridis_rgb(position(rec709_luminance(rgb[0], rgb[1], rgb[2])));
}

double contrast_scale::position(double contrast) const {
  if (!(contrast > 1)) return 0;
  return std::clamp(std::log10(contrast) / std::log10(top), 0.0, 1.0);
}

std::array<std::uint8_t, 3> contrast_scale::colour(const float* components) const {
  const auto [aerial, background] = aerial_and_background(components);
  return viridis_rgb(position(pixel_contrast(aerial, background)));
}

}  // namespace airr::ui
