#include "polarized_walk.hpp"

#include "airr/models/dielectric.hpp"

namespace airr {

polarized_walk polarized_walk::arriving(const glm::dvec3& wi) {
  return {mueller::identity(), polarization_frame::about(-wi)};
}

mueller polarized_walk::leaving(const glm::dvec3& wo) const {
  // A direction spread by diffraction after the last event differs a little from frame.k: its
  // frame is the one about wo turned to face frame.x as nearly as it can.
  return reframed(frame, polarization_frame::about(wo), m);
}

void polarized_walk::reflect(const glm::dvec3& n, double cos_i, std::complex<double> eta) {
  const fresnel_coefficients f = fresnel_amplitudes(cos_i, eta);
  const double r = 0.5 * (std::norm(f.rs) + std::norm(f.rp));
  if (!(r > 0)) return;
  // Amplitudes scaled by 1 / sqrt(r): the matrix divided by r.
  const double to_unit = 1 / std::sqrt(r);
  frame = reflect_onto(m, frame, n, f.rs * to_unit, f.rp * to_unit);
}

void polarized_walk::refract(const glm::dvec3& n, double cos_i, std::complex<double> eta, const glm::dvec3& k_out) {
  const fresnel_coefficients f = fresnel_amplitudes(cos_i, eta);
  const double energy = (eta * f.cos_t).real() / cos_i;
  const double t = energy * 0.5 * (std::norm(f.ts) + std::norm(f.tp));
  if (!(t > 0)) return;
  frame = transmit_onto(m, frame, n, k_out, f.ts, f.tp, energy / t);
}

void polarized_walk::depolarize(const glm::dvec3& k_out) {
  mueller keep_intensity = mueller::scale(0);
  keep_intensity.m[0][0] = 1;
  m = keep_intensity * m;
  frame = polarization_frame::about(k_out);
}

}  // namespace airr
