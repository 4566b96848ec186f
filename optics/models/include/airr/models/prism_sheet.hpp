#pragma once
// The prism sheet traced as geometry (spec section 9): a clear plate whose back is an array of
// triangular cube corners, cut by three families of V-grooves 120 deg apart. Light refracts in
// through the front surface, meets the grooves' faces (total internal reflection with Fresnel
// loss, or a metal coat), and leaves wherever the geometry sends it: back out of the front surface
// (retroreflected after a cube corner's three faces, or stray), or out of the back. The array is
// periodic, so it is traced in one unit cell's coordinates, whatever the sheet's size.
//
// Sheet-local frame: the front surface is z = 0 with the light arriving from z > 0; the grooves'
// ridges lie at z = -plate_mm and their faces go down to the cube corners' apexes, sqrt(2) pitch / 3
// deeper. Within each aperture triangle the surface is the highest of its three faces, each at
// depth sqrt(2) times the distance from its edge, so adjacent faces of a cube are perpendicular.
#include <glm/glm.hpp>

#include "airr/core/polygon.hpp"
#include "airr/core/random.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

struct prism_sheet_geometry {
  double pitch_mm = 0.1;  // spacing of parallel grooves: the height of the aperture triangles
  // Full cubes in place of triangular cube corners: the back is a lattice of cube corners of three
  // square faces each (hexagonal apertures, pitch_mm across flats), apexes 2 edge / sqrt 3 below
  // the ridges.
  bool full_cubes = false;
  double index = 1.5;              // of the plate
  double plate_mm = 0.1;           // from the front surface to the grooves' ridges
  bool metallised = false;         // faces: a metal coat (true) or total internal reflection with Fresnel loss
  double face_reflectance = 0.85;  // of the metal coat, per reflection
  double azimuth_deg = 0;          // of the grooves about the sheet normal (0: one family along x)
  // Light a cube corner retroreflects spreads by the Fraunhofer pattern of the part of its
  // aperture it used (diffraction.hpp) at this wavelength, other light that met the grooves by
  // that of the first cube corner's aperture triangle; 0: no diffraction.
  double wavelength_nm = 550;
  diffracted_light light = diffracted_light::single;  // display_rgb: wavelength_nm unused (but 0 still: none)

  double triangle_side_mm() const;  // 2 pitch / sqrt(3)
  double cube_edge_mm() const;      // triangle side / sqrt(2): the shift tables' unit (full cubes: pitch / sqrt 2)
  double depth_mm() const;          // of the apexes below the ridges: sqrt(2) pitch / 3 (full cubes: 2 edge / sqrt 3)
};

// Where a traced path ended.
enum class prism_fate {
  front_reflection,  // reflected by the front surface on the way in
  retroreflected,    // out of the front surface, exactly against the incoming light
  stray,             // out of the front surface in another direction
  transmitted,       // out of the back
  lost,              // still inside after the event limit (weight 0)
};

struct prism_path {
  prism_fate fate = prism_fate::lost;
  glm::dvec3 wo{0, 0, 1};     // the leaving direction, away from the sheet (below it when transmitted)
  glm::dvec2 shift_mm{0, 0};  // exit point minus entry point in the sheet plane
  double weight = 0;          // the metal coat's reflectance once per face; 1 otherwise (0: lost)
  int face_reflections = 0;   // on the grooves' faces, from inside the plate
  int front_reflections = 0;  // inside the plate, on the front surface
  int events = 0;             // every interaction after entry
  glm::dvec3 channels{1.0};   // of the display's R, G, B (diffracted_light)
};

// Light arriving against wi (sheet-local, wi.z > 0) at `entry` (mm) on the front surface. The
// front surface's choice between reflection and refraction takes u_front; every later Fresnel
// choice draws from rng.
// With `polarized`, the path's Mueller matrix is followed too (retro_sample::polarization).
prism_path trace_prism_sheet(const prism_sheet_geometry& g, const glm::dvec3& wi, const glm::dvec2& entry,
                             double u_front, pcg32& rng, std::optional<mueller>* polarized = nullptr);

// A cube corner's aperture triangle in the sheet plane about its centroid (mm); `pointing` as
// below.
polygon2 aperture_triangle(const prism_sheet_geometry& g, int pointing);

// The part of a cube corner's aperture that retroreflects light going along d inside the plate
// (d.z < 0): the aperture triangle's overlap with its image mirrored through the point where the
// line through the apex along d meets the aperture plane (a ray entering at x leaves at that
// mirror image of x). `pointing` is +1 for the triangles whose vertex lies along the first groove
// family's normal, -1 for the others. Sheet-plane mm about the triangle's centroid; empty when
// nothing retroreflects.
polygon2 effective_aperture(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing);

// Full cubes: a cube corner's three faces projected along d (inside, d.z < 0) onto a plane
// through its apex, about the apex: a hexagon, the corner's share of the array seen along d.
polygon2 full_cube_hexagon(const prism_sheet_geometry& g, const glm::dvec3& d);
// Full cubes: the part of that hexagon whose light retroreflects, its overlap with its image
// mirrored through the apex; empty when d meets a face from behind.
polygon2 full_cube_effective_aperture(const prism_sheet_geometry& g, const glm::dvec3& d);
// Full cubes: a point of the front surface, uniform over one cell of the apexes' lattice.
glm::dvec2 full_cube_cell_point(const prism_sheet_geometry& g, const glm::dvec2& u);

// The part of the effective aperture (either kind of prism) whose light meets the faces in the
// same order as a path retroreflected with `shift_mm` (exit minus entry): the six face orders
// divide the aperture along the lines of the cube's edges through the apex. Total internal
// reflection diffracts each part apart. `pointing` as for effective_aperture (ignored for full
// cubes).
polygon2 face_order_aperture(const prism_sheet_geometry& g, const glm::dvec3& d, int pointing,
                             const glm::dvec2& shift_mm);

// A point of the front surface, uniform over one cell of the array as u runs over [0, 1)^2 (one
// cell holds two aperture triangles, one of each orientation; full cubes: one cube corner).
glm::dvec2 prism_cell_point(const prism_sheet_geometry& g, const glm::dvec2& u);

// The prism sheet as a retroreflector model: a sample enters at a point of the array's cell drawn
// from u.lobe, the front surface's choice takes u.shift.x, and the rest draws from u.more. Out of
// the back, wo points below the sheet. Its kind is "prism_sheet".
class prism_sheet_retro final : public retro_model {
 public:
  explicit prism_sheet_retro(const prism_sheet_geometry& g);  // throws input_error out of range
  retro_sample sample(const glm::dvec3& wi, retro_samples u) const override;
  retro_sample sample_polarized(const glm::dvec3& wi, retro_samples u) const override;
  const prism_sheet_geometry& geometry() const { return g_; }

 private:
  prism_sheet_geometry g_;
};

const retro_model_kind& prism_sheet_retro_kind();

}  // namespace airr
