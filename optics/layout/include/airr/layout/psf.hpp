#pragma once
// The model's point spread function without the tracer: the camera's ray through an aerial-image
// point is followed through half mirror, retroreflector (sampled many times) and half mirror to
// the source plane; where it lands, relative to the ideal mirror point, is the blur, expressed on
// the aerial-image plane. Cheap enough to redraw on every edit.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct psf_params {
  std::uint64_t samples = 100000;
  std::uint64_t seed = 1;
};

struct psf_samples {
  std::vector<glm::dvec2> offset_mm;  // on the aerial-image plane (x right, y up), from the ideal point
  std::vector<double> weight;         // throughput including R_hm x T_hm
  std::uint64_t launched = 0;
  double rr_distance_mm = 0;  // retroreflector to aerial image along the chief ray
  double incidence_deg = 0;   // the chief ray's incidence angle on the retroreflector

  // Aerial-image radiance per unit source radiance (what a uniform source would show).
  double brightness() const;
};

// A camera ray's ideal return: through the half mirror to the first sheet's front, exactly back,
// and mirrored by the half mirror onto the display plane. `failed` names the first step that
// does not happen (the rest is then unset).
struct ideal_return {
  enum class step { none, half_mirror, sheet_front, display_plane } failed = step::none;
  glm::dvec3 sheet_point{0};
  glm::dvec3 landing{0};          // on the display plane (unbounded)
  glm::dvec3 towards_display{0};  // the returning ray's direction after the half mirror
};
ideal_return follow_ideal_return(const part_frame& hm, const part_frame& rr, const part_frame& src,
                                 const glm::dvec3& origin, const glm::dvec3& dir);

// The chief ray through one aerial-image point: the parts it meets on its way to the first sheet
// and back, and its ideal landing point on the display plane.
struct psf_chief_ray {
  part_frame hm, rr, src;
  glm::dvec3 sheet_point{0};  // where it meets the sheet
  glm::dvec3 ideal{0};        // where an exact retroreflection lands on the display plane
  glm::dvec3 wi{0, 0, 1};     // its incidence, sheet-local, pointing back towards the camera
  double rr_distance_mm = 0;  // sheet to aerial point
};
// Throws input_error when the ray misses a part.
psf_chief_ray chief_ray_through(const scene& s, const glm::dvec3& aerial_point);

// Where one retroreflected sample lands on the display plane, relative to the ideal point (world
// mm); empty when it misses the half mirror on the way back.
std::optional<glm::dvec3> psf_landing_offset(const psf_chief_ray& c, const retro_sample& rs);

// The PSF of the first sheet (the one behind the half mirror). Throws input_error when the chief
// ray through `aerial_point` misses a part.
psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p, const glm::dvec3& aerial_point);
psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p);

// The radius around the ideal point holding `fraction` of the arriving energy.
double energy_radius(const psf_samples& psf, double fraction = 0.5);

}  // namespace airr
