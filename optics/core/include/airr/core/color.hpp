#pragma once
// Colour: the sRGB transfer curve (IEC 61966-2-1) and Rec.709 luminance, for every layer.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace airr {

// sRGB code value in [0, 1] to linear.
inline double srgb_decode(double code) {
  return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

// Linear to sRGB code value; not clamped: callers that need display values clamp to [0, 1] first.
inline double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// Linear to an 8-bit sRGB code, clamped to [0, 1] (NaN: 0): lround(255 * srgb_encode(x)) without a
// pow per value, by a search of the 255 boundaries between codes, for images shown every frame.
inline std::uint8_t srgb_encode_8bit(float linear) {
  static const std::array<float, 255> bounds = [] {
    std::array<float, 255> b{};
    for (int c = 0; c < 255; ++c) b[std::size_t(c)] = float(srgb_decode((c + 0.5) / 255.0));
    return b;
  }();
  if (!(linear > 0)) return 0;
  return std::uint8_t(std::upper_bound(bounds.begin(), bounds.end(), linear) - bounds.begin());
}

// Rec.709 (and sRGB) luminance of linear RGB.
inline double rec709_luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

}  // namespace airr
