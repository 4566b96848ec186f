#pragma once
// The sRGB transfer curve (IEC 61966-2-1), shared by image reading, writing and display.
#include <cmath>

namespace airr {

inline double srgb_decode(double code) {
  return code <= 0.04045 ? code / 12.92 : std::pow((code + 0.055) / 1.055, 2.4);
}

// Not clamped: callers that need display values clamp to [0, 1] first.
inline double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

}  // namespace airr
