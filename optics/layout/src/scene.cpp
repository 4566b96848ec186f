#include "airr/layout/scene.hpp"

#include <cmath>
#include <numbers>

#include "airr/core/files.hpp"

namespace airr {

std::string resolve_scene_path(const scene& s, const std::string& path) { return resolve_path(path, s.base_dir); }

double room_luminance(const room_params& r) {
  return r.illuminance_lux > 0 ? r.illuminance_lux / std::numbers::pi : r.luminance_cd_m2;
}

double sun_luminance(const sun_params& s) {
  const double half_angle = sun_angular_diameter_deg / 2 * std::numbers::pi / 180;
  return s.illuminance_lux / (2 * std::numbers::pi * (1 - std::cos(half_angle)));
}

double luminaire_area_mm2(const luminaire_params& l) {
  return l.shape == luminaire_shape::disc ? std::numbers::pi / 4 * l.width_mm * l.width_mm : l.width_mm * l.height_mm;
}

double luminaire_luminance(const luminaire_params& l) {
  if (l.flux_lm > 0) return l.flux_lm / (std::numbers::pi * luminaire_area_mm2(l) * 1e-6);
  return l.luminance_cd_m2;
}

bool has_ambient_light(const environment_params& e) {
  if (room_luminance(e.room) > 0 || e.sun.illuminance_lux > 0) return true;
  for (const auto& l : e.luminaires)
    if (luminaire_luminance(l) > 0) return true;
  return false;
}

bool differ_in_placement_alone(const scene& a, const scene& b) {
  if (a.retroreflectors.size() != b.retroreflectors.size() || a.props.size() != b.props.size()) return false;
  scene moved = b;
  moved.source.pose = a.source.pose;
  moved.half_mirror.pose = a.half_mirror.pose;
  for (std::size_t i = 0; i < a.retroreflectors.size(); ++i) moved.retroreflectors[i].pose = a.retroreflectors[i].pose;
  for (std::size_t i = 0; i < a.props.size(); ++i) moved.props[i].pose = a.props[i].pose;
  observer_params& o = moved.observer;
  o.azimuth_deg = a.observer.azimuth_deg;
  o.elevation_deg = a.observer.elevation_deg;
  o.distance_mm = a.observer.distance_mm;
  o.position_mm = a.observer.position_mm;
  o.look_at_mm = a.observer.look_at_mm;
  return moved == a;
}

void derive_half_mirror_light(half_mirror_params& hm) {
  if (hm.kind == half_mirror_kind::plate) {
    const plate_paths paths = plate_paths_at(hm.plate, std::sqrt(0.5), false);
    hm.reflectance = paths.reflected[0].weight;
    hm.transmittance = paths.transmitted_total;
    return;
  }
  if (hm.kind != half_mirror_kind::reflective_polarizer) return;
  const reflective_polarizer_params& p = hm.polarizer;
  hm.reflectance = 0.5 * (p.pass_reflectance + p.block_reflectance);
  hm.transmittance = 0.5 * (p.pass_transmittance + p.block_transmittance);
}

// A plate reflects s and p light unequally (Fresnel), so it polarizes.
bool scene_polarizes(const scene& s) {
  if (s.source.polarization.state != light_state::unpolarized) return true;
  if (s.half_mirror.kind != half_mirror_kind::half_mirror || s.observer.analyzer_deg) return true;
  if (!s.source.films.empty() || !s.half_mirror.films.empty()) return true;
  for (const auto& r : s.retroreflectors)
    if (!r.films.empty()) return true;
  return false;
}

}  // namespace airr
