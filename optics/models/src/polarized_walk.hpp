#pragma once
// A retroreflective sheet's walk followed with its polarization (private to the models library).
#include <complex>

#include <glm/glm.hpp>

#include "airr/models/polarization.hpp"

namespace airr {

// A walk's polarization (docs/polarization.md): the Mueller matrix so far, from the light arriving
// to the light now in `frame` (its k the walk's direction). Each event's matrix is divided by the
// probability (or the metal coat's reflectance) the walk weighs it with, so that it changes the
// polarization, not the light the walk counts.
struct polarized_walk {
  mueller m = mueller::identity();
  polarization_frame frame;
  static polarized_walk arriving(const glm::dvec3& wi);  // in polarization_frame::about(-wi)
  mueller leaving(const glm::dvec3& wo) const;           // the matrix into about(wo)
  void reflect(const glm::dvec3& n, double cos_i, std::complex<double> eta);
  void refract(const glm::dvec3& n, double cos_i, std::complex<double> eta, const glm::dvec3& k_out);
  // A diffuse surface sending the light on along k_out: what leaves it is unpolarized.
  void depolarize(const glm::dvec3& k_out);
};

// The phase and s/p balance of the metal coat (aluminium at 550 nm, n = 0.96 + 6.69i); how much it
// reflects is the sheet's own (a prism sheet's face_reflectance, a bead sheet's backing_reflectance).
inline constexpr std::complex<double> metal_coat_index{0.96, 6.69};

}  // namespace airr
