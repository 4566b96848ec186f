#include "airr/optics/retro_sinc_shift.hpp"

#include <cmath>
#include <numbers>

#include "airr/optics/error.hpp"
#include "airr/optics/sinc_lobe.hpp"

namespace airr {

sinc_shift_params resolve_sinc_shift_params(const retro_model_params& m, const std::string& base_dir) {
  sinc_shift_params p;
  if (!m.preset.empty()) {
    const sheet_preset preset = load_preset(m.preset, base_dir);
    p.theta_deg = preset.theta_deg;
    p.a_per_mm = preset.a_per_mm;
    p.mu = preset.mu;
    p.c_mm = preset.c_mm;
    p.reference_distance_mm = preset.reference_distance_mm;
  } else if (!m.a_per_mm) {
    throw input_error("retroreflector.model.a_per_mm: needed by the sinc_shift model without a preset");
  }
  if (m.a_per_mm) p.a_per_mm = {*m.a_per_mm};
  if (m.mu) p.mu = {*m.mu};
  if (m.c_mm) p.c_mm = *m.c_mm;
  if (m.reference_distance_mm) p.reference_distance_mm = *m.reference_distance_mm;
  return p;
}

sinc_shift_retro::sinc_shift_retro(sinc_shift_params p, std::shared_ptr<const shift_table> shifts)
    : p_(std::move(p)), shifts_(std::move(shifts)) {}

double sinc_shift_retro::a_at(double theta_deg) const { return interpolate_by_angle(p_.theta_deg, p_.a_per_mm, theta_deg); }
double sinc_shift_retro::mu_at(double theta_deg) const { return interpolate_by_angle(p_.theta_deg, p_.mu, theta_deg); }

retro_sample sinc_shift_retro::sample(const glm::dvec3& wi, const retro_randoms& r) const {
  if (wi.z <= 0) return {};
  const double theta_deg = std::acos(std::min(1.0, wi.z)) * 180.0 / std::numbers::pi;
  const double k = a_at(theta_deg) * p_.reference_distance_mm;
  const double delta = sinc_lobe::instance().sample_delta(k, r.u[0], r.u[1]);
  const double phi = 2.0 * std::numbers::pi * r.u[2];

  // Rotate the retro direction (wo = wi) by delta at azimuth phi.
  const glm::dvec3 axis = std::abs(wi.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t1 = glm::normalize(glm::cross(axis, wi));
  const glm::dvec3 t2 = glm::cross(wi, t1);
  retro_sample s;
  s.wo = std::cos(delta) * wi + std::sin(delta) * (std::cos(phi) * t1 + std::sin(phi) * t2);
  if (s.wo.z <= 0) return {};  // sent below the sheet: absorbed

  if (p_.c_mm > 0 && shifts_) {
    const double shift = sample_shift(*shifts_, theta_deg, r.u[3], r.u[4], r.u[5]) * p_.c_mm;
    const double psi = 2.0 * std::numbers::pi * r.u[6];
    s.shift_mm = {shift * std::cos(psi), shift * std::sin(psi)};
  }
  s.weight = mu_at(theta_deg);
  return s;
}

}  // namespace airr
