// Checks of a scene: every value in range, every named file present, the layout sound, the models built.
#include "airr/formats/scene_json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include "airr/core/error.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

using nlohmann::json;

namespace {
struct checker {
  const std::string& origin;
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw input_error(origin + ": " + field + ": " + problem);
  }
  void finite(const std::string& field, double v) const {
    if (!std::isfinite(v)) fail(field, "must be a finite number");
  }
  void positive(const std::string& field, double v) const {
    finite(field, v);
    if (v <= 0) fail(field, "must be positive (is " + number_text(v) + ")");
  }
  void range(const std::string& field, double v, double lo, double hi) const {
    finite(field, v);
    if (v < lo || v > hi) {
      fail(field, "must be in [" + number_text(lo) + ", " + number_text(hi) + "] (is " + number_text(v) + ")");
    }
  }
  // Parts and observers stay within 100 m of the origin; angles within one turn either way.
  void position(const std::string& field, const std::array<double, 3>& p) const {
    for (double v : p) range(field, v, -max_distance_mm, max_distance_mm);
  }
  void part(const std::string& field, const part_params& p) const {
    positive(field + ".width_mm", p.width_mm);
    positive(field + ".height_mm", p.height_mm);
    range(field + ".width_mm", p.width_mm, min_part_size_mm, max_distance_mm);
    range(field + ".height_mm", p.height_mm, min_part_size_mm, max_distance_mm);
    pose(field + ".pose", p.pose);
    if (p.films.size() > std::size_t(max_films_per_part)) {
      fail(field + ".films", "at most " + std::to_string(max_films_per_part) + " films");
    }
    for (std::size_t i = 0; i < p.films.size(); ++i) film(field + ".films[" + std::to_string(i) + "]", p.films[i]);
  }
  void film(const std::string& field, const film_params& f) const {
    range(field + ".axis_deg", f.axis_deg, -360, 360);
    range(field + ".retardance_waves", f.retardance_waves, 0, 100);
    range(field + ".wavelength_nm", f.wavelength_nm, 200, 3000);
    range(field + ".pass_transmittance", f.pass_transmittance, 0, 1);
    range(field + ".block_transmittance", f.block_transmittance, 0, 1);
    if (f.block_transmittance > f.pass_transmittance) {
      fail(field + ".block_transmittance",
           "must not exceed pass_transmittance (" + number_text(f.pass_transmittance) + "): the pass axis passes more");
    }
  }
  void reflective_polarizer(const std::string& field, const reflective_polarizer_params& p) const {
    range(field + ".axis_deg", p.axis_deg, -360, 360);
    for (const auto& [key, v] : {std::pair{".pass_transmittance", p.pass_transmittance},
                                 {".pass_reflectance", p.pass_reflectance},
                                 {".block_reflectance", p.block_reflectance},
                                 {".block_transmittance", p.block_transmittance}}) {
      range(field + key, v, 0, 1);
    }
    if (p.pass_transmittance + p.pass_reflectance > 1 + 1e-12) {
      fail(field + ".pass_reflectance", "pass_transmittance + pass_reflectance must not exceed 1");
    }
    if (p.block_transmittance + p.block_reflectance > 1 + 1e-12) {
      fail(field + ".block_reflectance", "block_transmittance + block_reflectance must not exceed 1");
    }
  }
  void coating(const std::string& field, const coating_params& c) const {
    for (const auto& [key, v] : {std::pair{".rs", c.rs}, {".rp", c.rp}, {".ts", c.ts}, {".tp", c.tp}}) {
      range(field + key, v, 0, 1);
    }
    if (c.rs + c.ts > 1 + 1e-12) fail(field + ".ts", "rs + ts must not exceed 1");
    if (c.rp + c.tp > 1 + 1e-12) fail(field + ".tp", "rp + tp must not exceed 1");
    range(field + ".phase_deg", c.phase_deg, -360, 360);
    range(field + ".residual", c.residual, 0, 0.5);
  }
  void plate(const std::string& field, const half_mirror_params& hm) const {
    const plate_params& p = hm.plate;
    positive(field + ".thickness_mm", p.thickness_mm);
    // The plate's light leaves through its faces, not its edges.
    if (p.thickness_mm >= std::min(hm.width_mm, hm.height_mm)) {
      fail(field + ".thickness_mm", "the plate (" + number_text(p.thickness_mm) +
                                        " mm) must be thinner than its width (" +
                                        number_text(std::min(hm.width_mm, hm.height_mm)) + " mm)");
    }
    range(field + ".index", p.index, 1, 4);
    coating(field + ".front", p.front);
    coating(field + ".back", p.back);
  }
  void pose(const std::string& field, const airr::pose& p) const {
    position(field + ".center_mm", p.center_mm);
    range(field + ".yaw_deg", p.yaw_deg, -360, 360);
    range(field + ".pitch_deg", p.pitch_deg, -360, 360);
    range(field + ".roll_deg", p.roll_deg, -360, 360);
  }
  void environment(const environment_params& e) const {
    range("environment.room.luminance_cd_m2", e.room.luminance_cd_m2, 0, 1e9);
    range("environment.room.illuminance_lux", e.room.illuminance_lux, 0, 1e9);
    if (e.room.luminance_cd_m2 > 0 && e.room.illuminance_lux > 0)
      fail("environment.room", "give luminance_cd_m2 or illuminance_lux, not both");
    range("environment.sun.illuminance_lux", e.sun.illuminance_lux, 0, max_sun_illuminance_lux);
    range("environment.sun.azimuth_deg", e.sun.azimuth_deg, -360, 360);
    range("environment.sun.elevation_deg", e.sun.elevation_deg, -90, 90);
    if (e.sun.illuminance_lux > 0 && e.sun.elevation_deg <= 0)
      fail("environment.sun.elevation_deg", "the sun is below the horizon (its elevation must be above 0 degrees)");
    for (std::size_t i = 0; i < e.luminaires.size(); ++i) {
      const luminaire_params& l = e.luminaires[i];
      const std::string field = "environment.luminaires[" + std::to_string(i) + "]";
      pose(field + ".pose", l.pose);
      // A luminaire of zero area would need an infinite luminance for its flux.
      range(field + ".width_mm", l.width_mm, min_part_size_mm, max_distance_mm);
      if (l.shape == luminaire_shape::rectangle)
        range(field + ".height_mm", l.height_mm, min_part_size_mm, max_distance_mm);
      range(field + ".luminance_cd_m2", l.luminance_cd_m2, 0, 1e9);
      range(field + ".flux_lm", l.flux_lm, 0, 1e8);
      if (l.luminance_cd_m2 > 0 && l.flux_lm > 0) fail(field, "give luminance_cd_m2 or flux_lm, not both");
    }
  }
};
}  // namespace

void validate_scene(const scene& s, const std::string& origin) {
  const checker c{origin};
  c.part("source", s.source);
  c.range("source.intensity", s.source.intensity, 0, 1e9);
  c.range("source.luminance_cd_m2", s.source.luminance_cd_m2, 0, 1e9);
  c.range("source.bezel_mm", s.source.bezel_mm, 0, 1e4);
  c.environment(s.environment);
  if (has_ambient_light(s.environment) && !in_cd_m2(s.source))
    c.fail("environment",
           "ambient light is in cd/m2, so the display's luminance must be given too (source.luminance_cd_m2)");
  c.range("source.polarization.angle_deg", s.source.polarization.angle_deg, -360, 360);
  c.part("half_mirror", s.half_mirror);
  c.reflective_polarizer("half_mirror.polarizer", s.half_mirror.polarizer);
  if (s.half_mirror.kind == half_mirror_kind::plate) c.plate("half_mirror.plate", s.half_mirror);
  c.range("half_mirror.reflectance", s.half_mirror.reflectance, 0, 1);
  c.range("half_mirror.transmittance", s.half_mirror.transmittance, 0, 1);
  if (s.half_mirror.reflectance + s.half_mirror.transmittance > 1 + 1e-12) {
    c.fail("half_mirror.transmittance", "reflectance + transmittance must not exceed 1");
  }
  if (s.retroreflectors.empty() || s.retroreflectors.size() > std::size_t(max_retroreflectors)) {
    c.fail("retroreflectors", "must hold 1 to " + std::to_string(max_retroreflectors) + " sheets");
  }
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    const std::string where = "retroreflectors[" + std::to_string(i) + "]";
    c.part(where, s.retroreflectors[i]);
    try {
      const retro_model_params& m = s.retroreflectors[i].model;
      validate_model_values(m, find_retro_model_kind(m.type, where + ".model").fields, where + ".model");
    } catch (const input_error& e) {
      throw input_error(origin + ": " + e.what());
    }
  }
  if (s.props.size() > std::size_t(max_props)) c.fail("props", "at most " + std::to_string(max_props) + " props");
  for (std::size_t i = 0; i < s.props.size(); ++i) {
    const std::string where = "props[" + std::to_string(i) + "]";
    const prop_params& p = s.props[i];
    if (p.mesh.empty()) c.fail(where + ".mesh", "names no file");
    c.range(where + ".scale", p.scale, 1e-6, 1e6);
    c.pose(where + ".pose", p.pose);
    for (double a : p.albedo) c.range(where + ".albedo", a, 0, 1);
    c.range(where + ".tessellation_mm", p.tessellation_mm, 1e-4, 100);
  }
  const observer_params& o = s.observer;
  c.range("observer.azimuth_deg", o.azimuth_deg, -360, 360);
  c.range("observer.elevation_deg", o.elevation_deg, -89.9, 89.9);
  c.range("observer.distance_mm", o.distance_mm, 1, max_distance_mm);
  c.position("observer.position_mm", o.position_mm);
  c.position("observer.look_at_mm", o.look_at_mm);
  if (o.placement == observer_placement::look_at && o.position_mm == o.look_at_mm) {
    c.fail("observer.look_at_mm", "must differ from observer.position_mm");
  }
  c.range("observer.focal_length_mm", o.focal_length_mm, 1, 2000);
  c.range("observer.f_number", o.f_number, 0.5, 128);
  if (o.focus_distance_mm) c.range("observer.focus_distance_mm", *o.focus_distance_mm, 1, max_distance_mm);
  c.range("observer.fov_deg", o.fov_deg, 0.01, 170);
  c.range("observer.width", o.width, 1, max_resolution_side);
  c.range("observer.height", o.height, 1, max_resolution_side);
  if (o.analyzer_deg) c.range("observer.analyzer_deg", *o.analyzer_deg, -360, 360);
  c.range("render.max_depth", s.render.max_depth, 1, 64);
}

void validate_scene_files(const scene& s, const std::string& origin) {
  auto need = [&](const std::string& field, const std::string& path) {
    if (path.empty()) return;
    const std::string full = resolve_scene_path(s, path);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(full, ec)) {
      throw input_error(origin + ": " + field + ": file not found: " + full);
    }
  };
  need("source.image", s.source.image);
  need("source.mesh", s.source.mesh);
  need("source.emission_profile", s.source.emission_profile);
  need("half_mirror.mesh", s.half_mirror.mesh);
  for (std::size_t i = 0; i < s.props.size(); ++i) need("props[" + std::to_string(i) + "].mesh", s.props[i].mesh);
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    const std::string where = "retroreflectors[" + std::to_string(i) + "]";
    const retroreflector_params& r = s.retroreflectors[i];
    need(where + ".mesh", r.mesh);
    const retro_model_kind& kind = find_retro_model_kind(r.model.type, where + ".model");
    const model_values v(r.model, kind.fields, where + ".model");
    for (const auto& f : kind.fields) {
      const std::string path = v.text(f.key);
      if (f.kind == field_kind::path || (f.kind == field_kind::preset && is_preset_path(path))) {
        need(where + ".model." + f.key, path);
      }
    }
  }
}

retro_model_list check_scene(const scene& s, const std::string& origin) {
  validate_scene(s, origin);
  validate_scene_files(s, origin);
  check_layout(s, origin);
  if (!s.source.emission_profile.empty()) load_emission_profile(resolve_scene_path(s, s.source.emission_profile));
  for (std::size_t i = 0; i < s.props.size(); ++i) {
    try {
      prop_mesh(s, s.props[i]);
    } catch (const input_error& e) {
      throw input_error(origin + ": props[" + std::to_string(i) + "]: " + e.what());
    }
  }
  retro_model_list models;
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    const std::string where = "retroreflectors[" + std::to_string(i) + "]";
    try {
      // Presets and tables load, values resolve.
      models.push_back(make_sheet_model(s, i));
    } catch (const input_error& e) {
      const std::string what = e.what();
      throw input_error(what.rfind(where, 0) == 0 ? origin + ": " + what : what);
    }
  }
  return models;
}

}  // namespace airr
