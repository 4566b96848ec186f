#include "airr/optics/retro_sinc_shift.hpp"

#include <algorithm>
#include <cmath>

#include "airr/optics/error.hpp"
#include "airr/optics/geometry.hpp"
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

double sinc_shift_retro::a_at(double theta_deg) const {
  return interpolate_by_angle(p_.theta_deg, p_.a_per_mm, theta_deg);
}
double sinc_shift_retro::mu_at(double theta_deg) const { return interpolate_by_angle(p_.theta_deg, p_.mu, theta_deg); }

retro_sample sinc_shift_retro::sample(const glm::dvec3& wi, retro_samples u) const {
  if (wi.z <= 0) return {};
  const double theta_deg = polar_angle_deg(wi);
  const double k = a_at(theta_deg) * p_.reference_distance_mm;
  const double delta = sinc_lobe::instance().sample_delta(k, u.lobe.x, u.more.next_double());
  const double phi = 2.0 * pi * u.lobe.y;

  // Rotate the retro direction (wo = wi) by delta at azimuth phi.
  const basis b = make_basis(wi);
  retro_sample s;
  s.wo = b.to_world({std::sin(delta) * std::cos(phi), std::sin(delta) * std::sin(phi), std::cos(delta)});
  if (s.wo.z <= 0) return {};  // sent below the sheet: absorbed

  if (p_.c_mm > 0 && shifts_) {
    const double pick = u.more.next_double();
    const double shift = sample_shift(*shifts_, theta_deg, pick, u.shift.x, u.more.next_double()) * p_.c_mm;
    const double psi = 2.0 * pi * u.shift.y;
    s.shift_mm = {shift * std::cos(psi), shift * std::sin(psi)};
  }
  s.weight = mu_at(theta_deg);
  return s;
}

std::optional<double> sinc_shift_retro::pdf(const glm::dvec3& wi, const glm::dvec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0;
  const double cos_delta = std::clamp(glm::dot(wi, wo), -1.0, 1.0);
  const double sin_delta = std::sqrt(std::max(0.0, 1 - cos_delta * cos_delta));
  if (sin_delta <= 0) return std::nullopt;  // the lobe's axis: a density per steradian diverges there
  const double k = a_at(polar_angle_deg(wi)) * p_.reference_distance_mm;
  // p(delta) d(delta) spread uniformly over the azimuth: d(omega) = sin(delta) d(delta) d(phi).
  return sinc_lobe::pdf(std::acos(cos_delta), k) / (2.0 * pi * sin_delta);
}

std::optional<double> sinc_shift_retro::eval(const glm::dvec3& wi, const glm::dvec3& wo) const {
  const auto p = pdf(wi, wo);
  if (!p) return p;
  return *p * mu_at(polar_angle_deg(wi));
}

}  // namespace airr
