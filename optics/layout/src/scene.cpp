#include "airr/layout/scene.hpp"

#include "airr/core/files.hpp"

namespace airr {

std::string resolve_scene_path(const scene& s, const std::string& path) { return resolve_path(path, s.base_dir); }

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

}  // namespace airr
