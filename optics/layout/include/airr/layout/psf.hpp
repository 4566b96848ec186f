#pragma once
// The model's point spread function without the tracer: the camera's ray through an aerial-image
// point is followed through (or off) the half mirror to a sheet, retroreflected (sampled many
// times), and through (or off) the half mirror again to the source plane, for every sheet; where
// it lands, relative to the ideal mirror point, is the blur, expressed on the aerial-image plane.
// Cheap enough to redraw on every edit.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/geometry.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct psf_params {
  std::uint64_t samples = 100000;
  std::uint64_t seed = 1;
  // The lobe and shift samples from a low-discrepancy sequence (smooth integrals: MTF, radii);
  // false: independent random samples, whose noise a picture shows as noise rather than as the
  // sequence's lattice.
  bool stratified = true;
};

// One sheet's share of a PSF: its brightness and chief ray, or why the chief ray misses it.
struct psf_sheet_share {
  std::size_t sheet = 0;
  double brightness = 0;
  bool by_reflection = false;  // reached by reflection in the half mirror (else through it)
  double rr_distance_mm = 0;   // sheet to aerial image along the chief ray
  double incidence_deg = 0;    // the chief ray's incidence on the sheet
  std::string missed;          // empty when the sheet was sampled
};

struct psf_samples {
  std::vector<glm::dvec2> offset_mm;    // on the aerial-image plane (x right, y up), from the ideal point
  std::vector<double> weight;           // throughput including R_hm x T_hm
  std::uint64_t launched = 0;           // per sheet
  double rr_distance_mm = 0;            // retroreflector to aerial image along the chief ray (the first sheet sampled)
  double incidence_deg = 0;             // the chief ray's incidence angle on that retroreflector
  std::vector<psf_sheet_share> sheets;  // every sheet asked for, in order

  // Aerial-image radiance per unit source radiance (what a uniform source would show): the sum of
  // the sheets' shares.
  double brightness() const;
};

// A camera ray's ideal return: through the half mirror (or mirrored by it, `by_reflection`) to a
// sheet's front, exactly back, and mirrored by (or through) the half mirror onto the display
// plane. `failed` names the first step that does not happen (the rest is then unset).
struct ideal_return {
  enum class step { none, half_mirror, sheet_front, display_plane } failed = step::none;
  glm::dvec3 sheet_point{0};
  glm::dvec3 landing{0};          // on the display plane (unbounded)
  glm::dvec3 towards_display{0};  // the returning ray's direction after the half mirror
  glm::dvec3 towards_sheet{0};    // the camera ray's direction after the half mirror
};
ideal_return follow_ideal_return(const part_frame& hm, const part_frame& rr, const part_frame& src,
                                 const glm::dvec3& origin, const glm::dvec3& dir, bool by_reflection = false);

// The chief ray through one aerial-image point: the parts it meets on its way to one sheet and
// back, and its ideal landing point on the display plane.
struct psf_chief_ray {
  part_frame hm, rr, src;
  std::size_t sheet = 0;
  bool by_reflection = false;  // the sheet is reached by reflection in the half mirror
  glm::dvec3 sheet_point{0};   // where it meets the sheet
  glm::dvec3 ideal{0};         // where an exact retroreflection lands on the display plane
  glm::dvec3 wi{0, 0, 1};      // its incidence, sheet-local, pointing back towards the camera
  double rr_distance_mm = 0;   // sheet to aerial point, along the path
  // The observer's ray through the aerial point, and its camera's right and up (polarization).
  glm::dvec3 camera_dir{0, 0, -1}, camera_right{1, 0, 0}, camera_up{0, 1, 0};
};
// Throws input_error naming the sheet ("retroreflectors[i]") when the ray misses a part.
psf_chief_ray chief_ray_through(const scene& s, const glm::dvec3& aerial_point, std::size_t sheet = 0);

// Where one retroreflected sample lands on the display plane, relative to the ideal point (world
// mm), and the direction it arrives in; empty when it misses the half mirror on the way back.
struct psf_landing {
  glm::dvec3 offset{0};
  glm::dvec3 towards_display{0};
};
std::optional<psf_landing> psf_landing_of(const psf_chief_ray& c, const retro_sample& rs);

// The PSF of one sheet, each sheet reached by its own path. Throws input_error when the chief
// ray through `aerial_point` misses a part.
psf_samples sample_sheet_psf(const scene& s, std::size_t sheet, const retro_model& model, const psf_params& p,
                             const glm::dvec3& aerial_point);

// The PSF of every sheet together (`models` in the scene's sheet order, as make_sheet_models
// builds them): each sheet's samples with the same seed, so that the whole is exactly the sum of
// the sheets alone. A sheet whose chief ray misses a part adds nothing and says why in its share;
// throws input_error (the first sheet's reason) when no sheet is reached.
psf_samples sample_psf(const scene& s, const retro_model_list& models, const psf_params& p,
                       const glm::dvec3& aerial_point);
psf_samples sample_psf(const scene& s, const retro_model_list& models, const psf_params& p);

// The first sheet's PSF alone (a bench with one sheet; the fit's setups).
psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p, const glm::dvec3& aerial_point);
psf_samples sample_psf(const scene& s, const retro_model& model, const psf_params& p);

// The radius around the ideal point holding `fraction` of the arriving energy.
double energy_radius(const psf_samples& psf, double fraction = 0.5);
// The same for several fractions at once (one sort), in the order given.
std::vector<double> energy_radii(const psf_samples& psf, const std::vector<double>& fractions);

}  // namespace airr
