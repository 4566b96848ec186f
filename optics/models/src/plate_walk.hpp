#pragma once
// A clear plate over a structured back (the prism sheet's grooves, a tile sheet's unit cells),
// walked event by event: the front surface's Fresnel choices, then the back's faces (total
// internal reflection with Fresnel loss, or a metal coat) until the light leaves by the front or
// out of the back. The back's geometry comes from `follow`; diffraction is the caller's.
#include <complex>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "airr/core/random.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/polarization.hpp"
#include "airr/models/prism_sheet.hpp"
#include "polarized_walk.hpp"

namespace airr {

// Where a straight stretch ends: on a face (its normal pointing into the plate) or leaving the
// structure's slab (above its top inside the plate, below its bottom outside it).
struct stretch_end {
  stretch_end(const glm::dvec3& point, std::optional<glm::dvec3> face_normal, int pointing = 1)
      : point(point), face_normal(face_normal), pointing(pointing) {}
  glm::dvec3 point{0};
  std::optional<glm::dvec3> face_normal;
  int pointing = 1;  // triangular cube corners: +1 the triangles whose f's sum to 1, -1 the others
  std::optional<double> metal_reflectance;  // the face's metal coat; empty: a bare face
  int face = -1;                            // a tile sheet's face, and the tile frame's origin of its cell
  glm::dvec3 cell_origin{0};
};

// The walk's straight stretches, from p along d, in the plate or in the air under its back.
using follow_back = std::function<stretch_end(const glm::dvec3& p, const glm::dvec3& d, bool in_plate)>;

struct plate_optics {
  double index = 1.5;
  double plate_mm = 0.1;          // from the front surface (z = 0) down to the top of the structure
  double length_mm = 0.1;         // the structure's scale, for numerical tolerances
  double retro_tolerance = 1e-9;  // |wo - wi| under which light out of the front is retroreflected
};

// What the walk saw besides the path: the refracted direction inside the plate, and the faces met
// from inside the plate, in order.
struct plate_walk_record {
  glm::dvec3 inside{0, 0, -1};
  std::vector<stretch_end> faces;
  int crossings = 0;  // of the back surface, out into the air under it or back in
};

// Light arriving against wi (sheet-local, wi.z > 0) at `entry` (mm) on the front surface; the
// front surface's first choice takes u_front, every later Fresnel choice draws from rng. With
// `light`, its polarization is followed too.
prism_path walk_plate(const plate_optics& o, const follow_back& follow, const glm::dvec3& wi, const glm::dvec2& entry,
                      double u_front, pcg32& rng, plate_walk_record& record, polarized_walk* light = nullptr);

// A path out of the front spread by the far field of the aperture it used, at a wavelength drawn
// for `light`; an evanescent draw absorbs it.
void diffract_exit(const aperture& used, diffracted_light light, double wavelength_nm, pcg32& rng, prism_path& path);

}  // namespace airr
