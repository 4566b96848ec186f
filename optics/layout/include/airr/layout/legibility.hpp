#pragma once
// When text shown on the aerial image can be read (spec section 11): the smallest character whose
// stroke frequency keeps enough modulation, MTF x (C - 1) / (C + 1), and that subtends enough of
// the eye's view. docs/ambient-light.md gives the criterion and its sources.
#include <functional>
#include <string>

namespace airr {

struct legibility_criterion {
  double cycles_per_height = 2.5;  // a character's stroke frequency, cycles per character height
  double modulation = 0.1;         // the least modulation at that frequency a reader needs
  double min_arcmin = 16;          // the least height a character subtends at the eye

  bool operator==(const legibility_criterion&) const = default;
};

// What bounds the smallest legible character: the aerial image's blur, the display's pixels, the
// eye's angle, or nothing (the contrast is too low for any size: height infinite).
enum class legibility_limit { optics, pixels, eye, contrast };
const char* to_string(legibility_limit l);

struct legible_character {
  double height_mm = 0;  // on the aerial image
  double arcmin = 0;     // as the eye sees it
  legibility_limit limit = legibility_limit::optics;
};

// The smallest legible character on the aerial image seen from `distance_mm` at contrast
// `contrast` (infinite in a dark room), given the aerial image's MTF as a function of lp/mm on the
// image (searched up to max_lp_per_mm; 1 beyond it is taken as the MTF's last value) and the
// display's pixel pitch in mm (0: no pixels).
legible_character smallest_legible_character(const std::function<double(double)>& mtf_at, double max_lp_per_mm,
                                             double contrast, double distance_mm, double pixel_mm,
                                             const legibility_criterion& criterion = {});

}  // namespace airr
