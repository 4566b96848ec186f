#pragma once
// The bead sheet traced as geometry: glass spheres in a hexagonal array, half sunk into a backing
// that is a mirror (a hemispherical coat under each bead, the binder between them) or diffuse.
// Light meets a bead's exposed half (Fresnel reflection, or refraction in), crosses it to the
// backing under it, comes back through the bead and leaves, or meets the binder between the
// beads. The array is periodic, so it is traced in one cell's coordinates, whatever the sheet's
// size.
//
// Sheet-local frame: the beads' tops touch z = 0 (the sheet plane) with the light arriving from
// z > 0; their centres and the backing lie at z = -diameter / 2.
#include <optional>

#include <glm/glm.hpp>

#include "airr/core/random.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct bead_sheet_geometry {
  double diameter_mm = 0.06;
  double index = 1.93;           // of the glass
  double fill_fraction = 0.8;    // of the sheet's area the beads cover, at most 0.9069 (close packed)
  bool diffuse_backing = false;  // a Lambertian backing (true) or a mirror
  double backing_reflectance = 0.85;
  // Light that went through a bead spreads by the Fraunhofer pattern of its circular pupil at this
  // wavelength; 0: no diffraction.
  double wavelength_nm = 550;
  diffracted_light light = diffracted_light::single;  // display_rgb: wavelength_nm unused (but 0 still: none)

  double spacing_mm() const;  // between neighbouring beads' centres
};

struct bead_path {
  glm::dvec3 wo{0, 0, 1};     // leaving the sheet (z > 0)
  glm::dvec2 shift_mm{0, 0};  // exit point minus entry point in the sheet plane
  double weight = 0;          // the backing's reflectance once per reflection on it; 0 when lost
  bool lost = false;          // still inside after the event limit
  bool through_bead = false;  // it entered a bead and left through the same bead's front
  int backing_reflections = 0;
  glm::dvec3 channels{1.0};  // of the display's R, G, B (diffracted_light)
};

// Light arriving against wi (sheet-local, wi.z > 0) at `entry` (mm) on the sheet plane; every
// choice draws from rng. With `polarized`, it also gets the walk's Mueller matrix, from the frame
// about -wi to the frame about wo, divided by the path's weight (the beads' Fresnel refractions
// and reflections, the mirror backing's metal phases, a diffuse backing's depolarization).
bead_path trace_bead_sheet(const bead_sheet_geometry& g, const glm::dvec3& wi, const glm::dvec2& entry, pcg32& rng,
                           std::optional<mueller>* polarized = nullptr);

// A point of the sheet plane, uniform over one cell of the array as u runs over [0, 1)^2.
glm::dvec2 bead_cell_point(const bead_sheet_geometry& g, const glm::dvec2& u);

// The bead sheet as a retroreflector model: the entry point from u.lobe, the rest from u.more.
// Its kind is "bead_sheet".
class bead_sheet_retro final : public retro_model {
 public:
  explicit bead_sheet_retro(const bead_sheet_geometry& g);  // throws input_error out of range
  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override;
  retro_sample sample_polarized(const glm::dvec3& wi, retro_samples u) const override;

 private:
  bead_sheet_geometry g_;
};

const retro_model_kind& bead_sheet_retro_kind();

}  // namespace airr
