// The microfacet retroreflector of spec 2.3. The branches are chosen with the random numbers
// (Russian roulette); a sample's weight is mu (surface reflection, diffuse lobe), mu R_int^3 times
// the exit transmission (retroreflection), or 0:
// - Front surface: a facet normal visible from wi (Beckmann, alpha_surface; +z when smooth).
//   With probability F(wi.m) the light reflects about it, otherwise it refracts in (Snell). The
//   entry transmission 1 - F is counted once, by this choice.
// - Inside: with probability ERA(x, phi) it takes the retroreflective path through the cube
//   corner, otherwise it leaves in a cosine-weighted lobe about +z (the remainder, as specified,
//   without further loss). x and phi are measured on the refracted ray (pointing back out), which
//   for a smooth surface has the azimuth of wi.
// - Cube corner: one of the two prism orientations (probability 1/2 each); the first face is
//   drawn with probability proportional to its projected cosine max(0, -d.n) with the ray d, the
//   second likewise among the two remaining faces with the once-reflected ray, the third is the
//   one left. Each face reflects about a facet normal drawn from the Beckmann normals visible to
//   the ray (alpha_internal, about the face normal). A ray that faces none of the candidate
//   faces, or that a reflection sends through the face, is lost.
// - Coating: each of the three faces is an aluminium mirror of reflectance internal_reflectance
//   (R_int), so the retroreflected weight carries R_int once per reflection, R_int^3 in all. The
//   light the coating does not reflect is absorbed; it never reaches the diffuse lobe, whose
//   share stays 1 - ERA of the refracted light.
// - Exit: refraction through a facet visible from inside; the weight is multiplied by the Fresnel
//   transmission. The internally reflected part, including total internal reflection, is
//   absorbed.
// Smith masking of the outgoing ray is not weighted: the wrong-side losses above stand for it.
#include "airr/models/retro_microfacet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "airr/core/error.hpp"
#include "airr/core/geometry.hpp"
#include "airr/models/preset.hpp"

namespace airr {
namespace {

double erf_inv(double y) {
  y = std::clamp(y, -1 + 1e-15, 1 - 1e-15);
  // A closed-form approximation (relative error ~2e-3) refined by Newton steps on erf.
  const double a = 0.147;
  const double l = std::log(1 - y * y);
  const double b = 2 / (pi * a) + l / 2;
  double x = std::copysign(std::sqrt(std::sqrt(b * b - l / a) - b), y);
  for (int i = 0; i < 3; ++i) {
    const double slope = 2 / std::sqrt(pi) * std::exp(-x * x);
    if (slope < 1e-300) break;
    x -= (std::erf(x) - y) / slope;
  }
  return x;
}

// Slope x of the unit-roughness Beckmann surface seen from a direction at angle theta from the
// normal, in the plane of x: density proportional to exp(-x^2) (cos theta - x sin theta) for
// x < cot theta. Inverts its cdf by safeguarded Newton iteration.
double sample_visible_slope_x(double cos_t, double sin_t, double u) {
  const auto cdf = [&](double x) {
    return 0.5 * std::sqrt(pi) * cos_t * std::erfc(-x) + 0.5 * sin_t * std::exp(-x * x);
  };
  // Beyond |x| = 8 the mass is below 1e-27.
  double lo = -8, hi = sin_t * 8 > cos_t ? cos_t / sin_t : 8;
  const double target = u * cdf(hi);
  double x = 0;
  for (int i = 0; i < 100; ++i) {
    const double f = cdf(x) - target;
    (f > 0 ? hi : lo) = x;
    const double density = std::exp(-x * x) * (cos_t - x * sin_t);
    double next = density > 0 ? x - f / density : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - x) < 1e-13;
    x = next;
    if (done) break;
  }
  return x;
}

// Cube-corner face normals (pointing into the prism) of one prism orientation.
std::array<glm::dvec3, 3> cube_faces(bool point_reflected) {
  const double s = point_reflected ? -1 : 1;
  std::array<glm::dvec3, 3> n;
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * pi * k / 3;
    n[k] = {s * 2 / std::sqrt(6.0) * std::cos(a), s * 2 / std::sqrt(6.0) * std::sin(a), 1 / std::sqrt(3.0)};
  }
  return n;
}

}  // namespace

double beckmann_d(const glm::dvec3& m, double alpha) {
  if (m.z <= 0) return 0;
  const double cos2 = m.z * m.z;
  const double tan2 = std::max(0.0, 1 - cos2) / cos2;
  return std::exp(-tan2 / (alpha * alpha)) / (pi * alpha * alpha * cos2 * cos2);
}

glm::dvec3 sample_beckmann(double alpha, double u1, double u2) {
  const double tan2 = -alpha * alpha * std::log(1 - u1);
  const double cos_t = 1 / std::sqrt(1 + tan2);
  const double sin_t = std::sqrt(tan2) * cos_t;
  const double phi = 2 * pi * u2;
  return {sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t};
}

double smith_g1_beckmann(const glm::dvec3& w, double alpha) {
  const double sin_t = std::sqrt(std::max(0.0, 1 - w.z * w.z));
  if (sin_t == 0) return 1;
  const double a = w.z / (alpha * sin_t);
  const double lambda = 0.5 * (std::erf(a) - 1) + std::exp(-a * a) / (2 * a * std::sqrt(pi));
  return 1 / (1 + lambda);
}

double beckmann_visible_d(const glm::dvec3& wi, const glm::dvec3& m, double alpha) {
  const double cos_im = glm::dot(wi, m);
  if (cos_im <= 0 || wi.z <= 0) return 0;
  return smith_g1_beckmann(wi, alpha) * cos_im * beckmann_d(m, alpha) / wi.z;
}

glm::dvec3 sample_beckmann_visible(const glm::dvec3& wi, double alpha, double u1, double u2) {
  if (alpha <= 0) return {0, 0, 1};
  // Stretch to unit roughness, sample the visible slopes there, rotate to wi's azimuth, unstretch.
  const glm::dvec3 ws = glm::normalize(glm::dvec3(alpha * wi.x, alpha * wi.y, wi.z));
  const double sin_t = std::hypot(ws.x, ws.y);
  const double sx = sample_visible_slope_x(ws.z, sin_t, u1);
  const double sy = erf_inv(2 * u2 - 1);
  const double c = sin_t > 0 ? ws.x / sin_t : 1;
  const double s = sin_t > 0 ? ws.y / sin_t : 0;
  const double x = c * sx - s * sy;
  const double y = s * sx + c * sy;
  return glm::normalize(glm::dvec3(-alpha * x, -alpha * y, 1));
}

double era(double x_deg, double phi_deg) {
  double p = std::fmod(phi_deg, 60.0);
  if (p < 0) p += 60;
  const double w = std::abs(p - 30) / 30;
  const double upper = std::max(0.0, -0.353394 * std::atan(0.055244 * x_deg - 1.632606) + 0.322462);
  const double lower = std::max(0.0, -0.480967 * std::atan(0.085856 * x_deg - 2.860831) + 0.084810);
  return w * upper + (1 - w) * lower;
}

const retro_model_kind& microfacet_retro_kind() {
  static const retro_model_kind kind = [] {
    retro_model_kind k;
    k.name = "microfacet";
    k.help = "Prism sheet with rough aluminium-coated cube corners (Saito et al. 2024), the baseline model";
    k.fields = {
        number_field("mu", "", 0, 1, 1, "Weight of every retroreflected path"),
        number_field("alpha_surface", "", 0, 1, 0, "Beckmann roughness of the front surface", 0.5),
        number_field("alpha_internal", "", 0, 1, 0.0005, "Beckmann roughness of the cube faces", 0.05),
        number_field("internal_reflectance", "", 0, 1, 0.83, "Reflectance of each aluminium-coated cube face"),
        number_field("eta", "", 1, 3, 1.5046, "Refractive index of the prism sheet"),
        text_field("polarization_preset", field_kind::preset,
                   "A preset whose Mueller matrix per incidence (fitted by airr predict-preset from a traced "
                   "sheet) the retroreflected light takes; empty: the field kept as by a mirror"),
    };
    k.make = [](const model_values& v, const model_setting& setting) -> std::unique_ptr<retro_model> {
      microfacet_params p;
      p.alpha_surface = v.number("alpha_surface");
      p.alpha_internal = v.number("alpha_internal");
      p.internal_reflectance = v.number("internal_reflectance");
      p.eta = v.number("eta");
      p.mu = v.number("mu");
      if (const std::string name = v.text("polarization_preset"); !name.empty()) {
        const sheet_preset preset = load_preset(name, setting.base_dir);
        if (preset.polarization.empty())
          v.fail("polarization_preset",
                 "the preset " + name + " has no Mueller matrices (airr predict-preset fits them from a sheet)");
        p.polarization_theta_deg = preset.theta_deg;
        p.polarization = preset.polarization;
      }
      return std::make_unique<microfacet_retro>(p);
    };
    return k;
  }();
  return kind;
}

microfacet_retro::microfacet_retro(const microfacet_params& p)
    : polarization_theta_deg_(p.polarization_theta_deg),
      polarization_(p.polarization),
      alpha_surface_(p.alpha_surface),
      alpha_internal_(p.alpha_internal),
      internal_reflectance_(p.internal_reflectance),
      eta_(p.eta),
      mu_(p.mu) {
  check_model_numbers("microfacet", microfacet_retro_kind().fields,
                      {{"alpha_surface", alpha_surface_},
                       {"alpha_internal", alpha_internal_},
                       {"internal_reflectance", internal_reflectance_},
                       {"eta", eta_}});
}

retro_sample microfacet_retro::sample(const glm::dvec3& wi, retro_samples u) const { return trace(wi, u).sample; }

retro_sample microfacet_retro::sample_polarized(const glm::dvec3& wi, retro_samples u) const {
  microfacet_trace t = trace(wi, u);
  if (t.branch == microfacet_branch::retro && t.sample.weight > 0 && !polarization_.empty())
    t.sample.polarization = interpolate_by_angle(polarization_theta_deg_, polarization_, polar_angle_deg(wi));
  return t.sample;
}

microfacet_trace microfacet_retro::trace(const glm::dvec3& wi, retro_samples u) const {
  microfacet_trace out;
  if (wi.z <= 0) return out;
  pcg32& more = u.more;

  // Front surface: reflect or refract in.
  const double entry_u1 = more.next_double(), entry_u2 = more.next_double();
  const glm::dvec3 m = sample_beckmann_visible(wi, alpha_surface_, entry_u1, entry_u2);
  const double cos_i = glm::dot(wi, m);
  if (u.lobe.x < fresnel_dielectric(cos_i, eta_)) {
    out.branch = microfacet_branch::surface;
    const glm::dvec3 wo = reflect(-wi, m);
    if (wo.z > 0) out.sample = {wo, {0, 0}, mu_};
    return out;
  }
  const auto in = refract(-wi, m, 1 / eta_);
  if (!in || in->z >= 0) return out;
  glm::dvec3 d = *in;

  const double x_deg = polar_angle_deg(-d);
  const double phi_deg = degrees(std::atan2(-d.y, -d.x));
  // The retroreflective path's share is the effective area alone; the coating loss is a weight.
  const double p_retro = std::min(1.0, era(x_deg, phi_deg));
  if (u.lobe.y >= p_retro) {
    out.branch = microfacet_branch::diffuse;
    out.sample = {cosine_hemisphere(u.shift), {0, 0}, mu_, false};
    return out;
  }

  // Cube corner: three reflections, the face order drawn by projected cosine, each on a coated
  // face that reflects internal_reflectance of the light and absorbs the rest.
  out.branch = microfacet_branch::retro;
  double coating = 1;
  const std::array<glm::dvec3, 3> faces = cube_faces(u.shift.x < 0.5);
  std::array<int, 3> left{0, 1, 2};
  int n_left = 3;
  std::array<double, 2> face_u{u.shift.y, 0};
  std::array<std::array<double, 2>, 3> facet_u{};
  facet_u[0] = {more.next_double(), more.next_double()};
  face_u[1] = more.next_double();
  for (int k = 1; k < 3; ++k) facet_u[k] = {more.next_double(), more.next_double()};
  for (int step = 0; step < 3; ++step) {
    std::array<double, 3> w{};
    double total = 0;
    for (int i = 0; i < n_left; ++i) total += w[i] = std::max(0.0, -glm::dot(d, faces[left[i]]));
    if (total <= 0) return out;
    int pick = n_left - 1;
    if (step < 2) {
      double t = face_u[step] * total;
      pick = 0;
      while (pick < n_left - 1 && t >= w[pick]) t -= w[pick++];
      while (w[pick] <= 0) --pick;  // rounding at the end of the range; total > 0 guarantees a hit
    }
    if (w[pick] <= 0) return out;  // the last face is turned away from the ray
    const glm::dvec3 n = faces[left[pick]];
    const basis f = make_basis(n);
    const glm::dvec3 mf =
        f.to_world(sample_beckmann_visible(f.to_local(-d), alpha_internal_, facet_u[step][0], facet_u[step][1]));
    d = reflect(d, mf);
    coating *= internal_reflectance_;
    if (glm::dot(d, n) <= 0) return out;
    left[pick] = left[--n_left];
  }
  if (d.z <= 0) return out;

  // Exit through the front surface; the facet normal faces into the sheet (-z).
  const glm::dvec3 v = -d;
  const double exit_u1 = more.next_double(), exit_u2 = more.next_double();
  const glm::dvec3 mv = sample_beckmann_visible({v.x, v.y, -v.z}, alpha_surface_, exit_u1, exit_u2);
  const glm::dvec3 m_in{mv.x, mv.y, -mv.z};
  const double f_out = fresnel_dielectric(glm::dot(v, m_in), 1 / eta_);
  const auto wo = refract(d, m_in, eta_);
  if (f_out >= 1 || !wo || wo->z <= 0) return out;
  out.sample = {*wo, {0, 0}, mu_ * coating * (1 - f_out)};
  return out;
}

}  // namespace airr
