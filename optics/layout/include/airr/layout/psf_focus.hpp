#pragma once
// Through focus: the bundle of rays that one display point sends over the whole of every sheet
// and that converges, after retroreflection, on its aerial-image point, cut by planes across the
// chief ray at signed offsets from that point. The sheets are the bundle's pupil: with an exact
// retroreflector every ray passes through the aerial point (a spot of zero width there), and at
// an offset z the spot is the sheets' aperture seen from the aerial point, scaled by z over its
// distance. A real sheet's deviations and shifts blur the waist and may move it off the plane.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"

namespace airr {

struct focus_params {
  std::uint64_t samples = 100000;  // rays per sheet
  std::uint64_t seed = 1;
  bool stratified = true;  // as psf_params::stratified
};

// The returning rays after their last pass at the half mirror, ready to be cut by planes.
struct focus_bundle {
  glm::dvec3 aerial_point{0};
  glm::dvec3 axis{0, 0, 1};                     // the chief ray's direction, from the aerial point towards the observer
  glm::dvec3 x_axis{1, 0, 0}, y_axis{0, 1, 0};  // across it: the observer's right and up
  std::vector<glm::dvec3> origin, dir;
  std::vector<double> weight;           // the ray's share of the returned power (arbitrary units)
  std::uint64_t launched = 0;           // per sheet
  std::vector<psf_sheet_share> sheets;  // per sheet: its brightness here is its share of the power
};

// Throws input_error when no sheet's bundle reaches back (the first sheet's reason).
focus_bundle sample_focus_bundle(const scene& s, const retro_model_list& models, const focus_params& p,
                                 const glm::dvec3& aerial_point);

// The bundle on the plane across the chief ray at `offset_mm` along it (positive: towards the
// observer), as offsets from the chief ray's crossing (x, y as the bundle's axes), with weights
// scaled so that brightness() is 1. A plane the rays meet before the half mirror is cut by their
// extension.
psf_samples cut_focus_bundle(const focus_bundle& b, double offset_mm);

// "start:end:step" in mm (start <= end, step > 0, at most 201 planes); throws input_error.
std::vector<double> parse_focus_offsets(const std::string& text);

}  // namespace airr
