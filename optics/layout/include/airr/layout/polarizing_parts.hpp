#pragma once
// What a scene says of polarization (docs/polarization.md): the display's light, films laid on a
// part's face, the half mirror as a reflective polarizer, and a polarizer before the observer.
// Angles lie in a part's plane, from its width axis (u) towards its height axis (v).
#include <optional>
#include <vector>

namespace airr {

// The display's light: unpolarized, linear at angle_deg, or circular with S3 > 0 ("positive") or
// S3 < 0 as it leaves the display.
enum class light_state { unpolarized, linear, circular_positive, circular_negative };

struct source_polarization {
  light_state state = light_state::unpolarized;
  double angle_deg = 0;  // linear light's field axis

  bool operator==(const source_polarization&) const = default;
};

enum class film_kind { retarder, polarizer };
enum class part_face { front, back };

// A film on one face of a part: a retarder (fast axis, retardance in waves at a design
// wavelength, growing off-axis with the path in the film) or an absorbing polarizer (pass axis,
// the intensity passed along and across it). Films on one face are listed from the part out.
struct film_params {
  film_kind kind = film_kind::retarder;
  part_face face = part_face::front;
  double axis_deg = 45;
  double retardance_waves = 0.25;
  double wavelength_nm = 550;
  double pass_transmittance = 1.0;
  double block_transmittance = 0.0;

  bool operator==(const film_params&) const = default;
};
inline constexpr int max_films_per_part = 8;

// The half mirror as a reflective polarizer: light along its pass axis is transmitted (with a
// leak reflected), light across it reflected (with a leak transmitted).
struct reflective_polarizer_params {
  double axis_deg = 90;  // the pass axis
  double pass_transmittance = 1.0;
  double pass_reflectance = 0.0;
  double block_reflectance = 1.0;
  double block_transmittance = 0.0;

  bool operator==(const reflective_polarizer_params&) const = default;
};

}  // namespace airr
