#include "airr/layout/legibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "airr/core/geometry.hpp"

namespace airr {

const char* to_string(legibility_limit l) {
  switch (l) {
    case legibility_limit::optics:
      return "optics";
    case legibility_limit::pixels:
      return "pixels";
    case legibility_limit::eye:
      return "eye";
    case legibility_limit::contrast:
      return "contrast";
  }
  return "?";
}

legible_character smallest_legible_character(const std::function<double(double)>& mtf_at, double max_lp_per_mm,
                                             double contrast, double distance_mm, double pixel_mm,
                                             const legibility_criterion& criterion) {
  // What contrast leaves of the modulation: (C - 1) / (C + 1), 1 in the dark.
  const double kept = std::isinf(contrast) ? 1.0 : (contrast - 1) / (contrast + 1);
  legible_character out;
  if (!(kept >= criterion.modulation)) {
    out.height_mm = out.arcmin = std::numeric_limits<double>::infinity();
    out.limit = legibility_limit::contrast;
    return out;
  }
  // The highest frequency below which the modulation never falls short, in fine steps; the
  // crossing found by bisection.
  constexpr int steps = 400;
  const auto enough = [&](double f) { return mtf_at(f) * kept >= criterion.modulation; };
  double f_ok = max_lp_per_mm;
  for (int i = 1; i <= steps; ++i) {
    const double f = max_lp_per_mm * i / steps;
    if (enough(f)) continue;
    double lo = max_lp_per_mm * (i - 1) / steps, hi = f;
    for (int k = 0; k < 40; ++k) {
      const double mid = (lo + hi) / 2;
      (enough(mid) ? lo : hi) = mid;
    }
    f_ok = lo;
    break;
  }
  const double by_optics = f_ok > 0 ? criterion.cycles_per_height / f_ok : std::numeric_limits<double>::infinity();
  // The display shows at most one cycle per two pixels.
  const double by_pixels = criterion.cycles_per_height * 2 * pixel_mm;
  const double by_eye = distance_mm * std::tan(radians(criterion.min_arcmin / 60));
  out.height_mm = std::max({by_optics, by_pixels, by_eye});
  out.limit = out.height_mm == by_optics   ? legibility_limit::optics
              : out.height_mm == by_pixels ? legibility_limit::pixels
                                           : legibility_limit::eye;
  out.arcmin = degrees(std::atan(out.height_mm / distance_mm)) * 60;
  return out;
}

}  // namespace airr
