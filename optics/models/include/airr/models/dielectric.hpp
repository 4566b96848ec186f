#pragma once
// What light does at a smooth interface between two clear media.
#include <complex>
#include <optional>

#include <glm/glm.hpp>

namespace airr {

// Unpolarised Fresnel reflectance of a dielectric interface; cos_i is the cosine of the incidence
// angle and eta = n_transmitted / n_incident. Total internal reflection gives 1.
double fresnel_dielectric(double cos_i, double eta);

// The Fresnel amplitude ratios of an interface for s and p light, in the s/p frames of
// polarization.hpp (p = k x s for the light in and out): eta = n_transmitted / n_incident, complex
// for a metal (n + i kappa); cos_i in [0, 1]. Beyond the critical angle |rs| = |rp| = 1 with the
// phases of total internal reflection, and the transmitted wave is evanescent (ts, tp kept, T = 0).
struct fresnel_coefficients {
  std::complex<double> rs, rp, ts, tp;
  std::complex<double> cos_t;  // imaginary part >= 0 (the transmitted wave decays)
  bool total = false;          // total internal reflection
};
fresnel_coefficients fresnel_amplitudes(double cos_i, std::complex<double> eta);

// Refracts the propagation direction d at a surface with normal m facing against d;
// ratio = n_incident / n_transmitted. Empty on total internal reflection.
std::optional<glm::dvec3> refract(const glm::dvec3& d, const glm::dvec3& m, double ratio);

}  // namespace airr
