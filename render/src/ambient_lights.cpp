#include "airr/render/ambient_lights.hpp"

#include <cmath>
#include <numbers>

#include "airr/core/geometry.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

ambient_lights make_ambient_lights(const environment_params& e) {
  ambient_lights a;
  a.room = float(room_luminance(e.room));
  if (e.sun.illuminance_lux > 0) {
    a.sun = float(sun_luminance(e.sun));
    a.sun_dir = sun_direction(e.sun);
    a.sun_cos_radius = std::cos(sun_angular_diameter_deg / 2 * std::numbers::pi / 180);
    a.sun_lux = e.sun.illuminance_lux;
  }
  for (const auto& l : e.luminaires) {
    a.luminaires.push_back(
        {luminaire_frame(l), l.shape == luminaire_shape::disc, float(luminaire_luminance(l)), luminaire_area_mm2(l)});
  }
  return a;
}

luminaire_hit meet_luminaire(const ambient_lights& a, const glm::dvec3& origin, const glm::dvec3& dir, double t_max) {
  luminaire_hit best;
  for (std::size_t k = 0; k < a.luminaires.size(); ++k) {
    const part_frame& f = a.luminaires[k].frame;
    const double along = glm::dot(dir, f.n);
    if (along == 0) continue;
    const double t = glm::dot(f.center - origin, f.n) / along;
    if (!(t > 0 && t < t_max) || (best.which >= 0 && t >= best.t)) continue;
    const glm::dvec3 d = origin + t * dir - f.center;
    const double x = glm::dot(d, f.u) / f.width, y = glm::dot(d, f.v) / f.height;
    const bool inside = a.luminaires[k].disc ? x * x + y * y <= 0.25 : std::abs(x) <= 0.5 && std::abs(y) <= 0.5;
    if (inside) best = {int(k), t, along < 0};
  }
  return best;
}

glm::dvec3 luminaire_point(const ambient_lights::luminaire& l, double u1, double u2) {
  const part_frame& f = l.frame;
  if (l.disc) {
    const glm::dvec2 d = uniform_disc({u1, u2}) * (f.width / 2);
    return f.center + d.x * f.u + d.y * f.v;
  }
  return f.center + (u1 - 0.5) * f.width * f.u + (u2 - 0.5) * f.height * f.v;
}

glm::dvec3 sun_sample_direction(const ambient_lights& a, double u1, double u2) {
  // Uniform over the cone's solid angle: cos theta uniform in [cos radius, 1].
  const double cos_t = 1 - u1 * (1 - a.sun_cos_radius);
  const double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  const double phi = 2 * std::numbers::pi * u2;
  return glm::normalize(make_basis(a.sun_dir).to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t}));
}

}  // namespace airr
