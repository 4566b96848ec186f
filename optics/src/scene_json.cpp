#include "airr/optics/scene_json.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include "airr/optics/error.hpp"
#include "airr/optics/json_reader.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/preset.hpp"
#include "airr/optics/retro_model.hpp"

namespace airr {

using nlohmann::json;

std::string resolve_scene_path(const scene& s, const std::string& path) { return resolve_path(path, s.base_dir); }

scene rebase_scene_paths(const scene& s, const std::string& new_dir) {
  scene out = s;
  auto rebase = [&](std::string& p) { p = rebase_path(p, s.base_dir, new_dir); };
  rebase(out.source.image);
  rebase(out.source.mesh);
  rebase(out.half_mirror.mesh);
  rebase(out.retroreflector.mesh);
  rebase(out.retroreflector.model.shift_table);
  if (is_preset_path(out.retroreflector.model.preset)) rebase(out.retroreflector.model.preset);
  out.base_dir = new_dir;
  return out;
}

// ---------------------------------------------------------------- writing

static json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

static json model_to_json(const retro_model_params& m) {
  return {{"type", retro_model_type_names[static_cast<int>(m.type)]},
          {"mu", optional_number(m.mu)},
          {"preset", m.preset},
          {"a_per_mm", optional_number(m.a_per_mm)},
          {"c_mm", optional_number(m.c_mm)},
          {"reference_distance_mm", optional_number(m.reference_distance_mm)},
          {"shift_table", m.shift_table},
          {"alpha_surface", m.alpha_surface},
          {"alpha_internal", m.alpha_internal},
          {"internal_reflectance", m.internal_reflectance},
          {"eta", m.eta}};
}

json scene_to_json(const scene& s) {
  const auto& src = s.source;
  const auto& hm = s.half_mirror;
  const auto& rr = s.retroreflector;
  const auto& cam = s.camera;
  return {
      {"format", "airr-scene"},
      {"version", s.version},
      {"floating_distance_mm", s.floating_distance_mm},
      {"seed", s.seed},
      {"source",
       {{"image", src.image},
        {"mesh", src.mesh},
        {"width_mm", src.width_mm},
        {"height_mm", src.height_mm},
        {"intensity", src.intensity},
        {"offset_mm", src.offset_mm}}},
      {"half_mirror",
       {{"mesh", hm.mesh},
        {"width_mm", hm.width_mm},
        {"height_mm", hm.height_mm},
        {"reflectance", hm.reflectance},
        {"transmittance", hm.transmittance}}},
      {"retroreflector",
       {{"mesh", rr.mesh},
        {"width_mm", rr.width_mm},
        {"height_mm", rr.height_mm},
        {"distance_mm", rr.distance_mm},
        {"tilt_deg", rr.tilt_deg},
        {"model", model_to_json(rr.model)}}},
      {"camera",
       {{"distance_mm", cam.distance_mm}, {"fov_deg", cam.fov_deg}, {"width", cam.width}, {"height", cam.height}}},
      {"render", {{"max_depth", s.render.max_depth}}},
  };
}

// ---------------------------------------------------------------- reading

static void read_model(json_reader r, retro_model_params& m) {
  std::string type = retro_model_type_names[static_cast<int>(m.type)];
  r.string("type", type);
  bool known = false;
  for (std::size_t i = 0; i < retro_model_type_names.size(); ++i) {
    if (type == retro_model_type_names[i]) {
      m.type = static_cast<retro_model_type>(i);
      known = true;
    }
  }
  if (!known) r.fail(r.field("type"), "unknown model '" + type + "' (ideal, sinc_shift, microfacet)");
  r.nullable_number("mu", m.mu);
  r.string("preset", m.preset);
  r.nullable_number("a_per_mm", m.a_per_mm);
  r.nullable_number("c_mm", m.c_mm);
  r.nullable_number("reference_distance_mm", m.reference_distance_mm);
  r.string("shift_table", m.shift_table);
  r.number("alpha_surface", m.alpha_surface);
  r.number("alpha_internal", m.alpha_internal);
  r.number("internal_reflectance", m.internal_reflectance);
  r.number("eta", m.eta);
  r.finish();
}

scene scene_from_json(const json& j, const std::string& origin) {
  scene s;
  json_reader r(j, origin, "");
  std::string format = "airr-scene";
  r.string("format", format);
  if (format != "airr-scene") r.fail("format", "expected \"airr-scene\", found \"" + format + "\"");
  r.integer("version", s.version);
  if (s.version != scene_format_version) {
    r.fail("version", "unsupported version " + std::to_string(s.version) + " (this build reads " +
                          std::to_string(scene_format_version) + ")");
  }
  r.number("floating_distance_mm", s.floating_distance_mm);
  if (r.has("seed")) {
    const auto& v = r.raw("seed");
    if (!v.is_number_integer() || (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0)) {
      r.fail("seed", "must be a non-negative integer");
    }
    s.seed = v.get<std::uint64_t>();
  }
  if (r.has("source")) {
    auto c = r.child("source");
    c.string("image", s.source.image);
    c.string("mesh", s.source.mesh);
    c.number("width_mm", s.source.width_mm);
    c.number("height_mm", s.source.height_mm);
    c.number("intensity", s.source.intensity);
    c.numbers("offset_mm", s.source.offset_mm);
    c.finish();
  }
  if (r.has("half_mirror")) {
    auto c = r.child("half_mirror");
    c.string("mesh", s.half_mirror.mesh);
    c.number("width_mm", s.half_mirror.width_mm);
    c.number("height_mm", s.half_mirror.height_mm);
    c.number("reflectance", s.half_mirror.reflectance);
    c.number("transmittance", s.half_mirror.transmittance);
    c.finish();
  }
  if (r.has("retroreflector")) {
    auto c = r.child("retroreflector");
    c.string("mesh", s.retroreflector.mesh);
    c.number("width_mm", s.retroreflector.width_mm);
    c.number("height_mm", s.retroreflector.height_mm);
    c.number("distance_mm", s.retroreflector.distance_mm);
    c.number("tilt_deg", s.retroreflector.tilt_deg);
    if (c.has("model")) read_model(c.child("model"), s.retroreflector.model);
    c.finish();
  }
  if (r.has("camera")) {
    auto c = r.child("camera");
    c.number("distance_mm", s.camera.distance_mm);
    c.number("fov_deg", s.camera.fov_deg);
    c.integer("width", s.camera.width);
    c.integer("height", s.camera.height);
    c.finish();
  }
  if (r.has("render")) {
    auto c = r.child("render");
    c.integer("max_depth", s.render.max_depth);
    c.finish();
  }
  r.finish();
  return s;
}

// ---------------------------------------------------------------- validation

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
    if (v <= 0) fail(field, "must be positive (is " + std::to_string(v) + ")");
  }
  void range(const std::string& field, double v, double lo, double hi) const {
    finite(field, v);
    if (v < lo || v > hi) {
      fail(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (is " + std::to_string(v) + ")");
    }
  }
};
}  // namespace

void validate_scene(const scene& s, const std::string& origin) {
  const checker c{origin};
  c.positive("floating_distance_mm", s.floating_distance_mm);
  c.positive("source.width_mm", s.source.width_mm);
  c.positive("source.height_mm", s.source.height_mm);
  c.range("source.intensity", s.source.intensity, 0, 1e9);
  for (int i = 0; i < 3; ++i) c.finite("source.offset_mm", s.source.offset_mm[i]);
  c.positive("half_mirror.width_mm", s.half_mirror.width_mm);
  c.positive("half_mirror.height_mm", s.half_mirror.height_mm);
  c.range("half_mirror.reflectance", s.half_mirror.reflectance, 0, 1);
  c.range("half_mirror.transmittance", s.half_mirror.transmittance, 0, 1);
  if (s.half_mirror.reflectance + s.half_mirror.transmittance > 1 + 1e-12) {
    c.fail("half_mirror.transmittance", "reflectance + transmittance must not exceed 1");
  }
  c.positive("retroreflector.width_mm", s.retroreflector.width_mm);
  c.positive("retroreflector.height_mm", s.retroreflector.height_mm);
  c.positive("retroreflector.distance_mm", s.retroreflector.distance_mm);
  c.range("retroreflector.tilt_deg", s.retroreflector.tilt_deg, -80, 80);
  const retro_model_params& m = s.retroreflector.model;
  if (m.mu) c.range("retroreflector.model.mu", *m.mu, 0, 1);
  if (m.a_per_mm) c.positive("retroreflector.model.a_per_mm", *m.a_per_mm);
  if (m.c_mm) c.range("retroreflector.model.c_mm", *m.c_mm, 0, 100);
  if (m.reference_distance_mm) c.positive("retroreflector.model.reference_distance_mm", *m.reference_distance_mm);
  c.range("retroreflector.model.alpha_surface", m.alpha_surface, 0, 1);
  c.range("retroreflector.model.alpha_internal", m.alpha_internal, 0, 1);
  c.range("retroreflector.model.internal_reflectance", m.internal_reflectance, 0, 1);
  c.range("retroreflector.model.eta", m.eta, 1, 3);
  c.positive("camera.distance_mm", s.camera.distance_mm);
  c.range("camera.fov_deg", s.camera.fov_deg, 0.01, 170);
  c.range("camera.width", s.camera.width, 1, max_resolution_side);
  c.range("camera.height", s.camera.height, 1, max_resolution_side);
  if (static_cast<long long>(s.camera.width) * s.camera.height > max_resolution_pixels) {
    c.fail("camera.width", "resolution " + std::to_string(s.camera.width) + "x" + std::to_string(s.camera.height) +
                               " exceeds the cap of " + std::to_string(max_resolution_pixels) + " pixels");
  }
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
  need("retroreflector.model.shift_table", s.retroreflector.model.shift_table);
  need("source.mesh", s.source.mesh);
  need("half_mirror.mesh", s.half_mirror.mesh);
  need("retroreflector.mesh", s.retroreflector.mesh);
}

std::shared_ptr<const retro_model> check_scene(const scene& s, const std::string& origin) {
  validate_scene(s, origin);
  validate_scene_files(s, origin);
  check_layout(s, origin);
  try {
    return make_retro_model(s.retroreflector.model, s.base_dir);  // presets and tables load, values resolve
  } catch (const input_error& e) {
    const std::string what = e.what();
    throw input_error(what.rfind("retroreflector.", 0) == 0 ? origin + ": " + what : what);
  }
}

// ---------------------------------------------------------------- overrides

scene_override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw input_error("--set " + text + ": expected key=value, e.g. retroreflector.tilt_deg=20");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

static json override_value(const std::string& v) {
  if (v == "nan" || v == "NaN") return std::numeric_limits<double>::quiet_NaN();
  if (v == "inf" || v == "-inf") return v[0] == '-' ? -HUGE_VAL : HUGE_VAL;
  try {
    return json::parse(v);
  } catch (const json::exception&) {
    return v;  // a bare word is a string, e.g. model.type=ideal
  }
}

void apply_overrides(json& j, const std::vector<scene_override>& overrides) {
  for (const auto& o : overrides) {
    json* node = &j;
    std::string rest = o.key;
    std::string walked;
    while (true) {
      const auto dot = rest.find('.');
      const std::string part = rest.substr(0, dot);
      walked += (walked.empty() ? "" : ".") + part;
      if (!node->is_object() || !node->contains(part))
        throw input_error("--set " + o.key + ": unknown key '" + walked + "'");
      node = &(*node)[part];
      if (dot == std::string::npos) break;
      rest = rest.substr(dot + 1);
    }
    const json value = override_value(o.value);
    if (node->is_number() && value.is_number_float() && !std::isfinite(value.get<double>())) {
      throw input_error("--set " + o.key + ": must be a finite number (got " + o.value + ")");
    }
    if (node->is_object()) throw input_error("--set " + o.key + ": names a group, not a value");
    *node = value;
  }
}

// ---------------------------------------------------------------- files

scene parse_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                  const std::vector<scene_override>& overrides) {
  scene s = scene_from_json(parse_json(text, origin), origin);
  const std::string where = overrides.empty() ? origin : origin + " (with --set)";
  if (!overrides.empty()) {
    // Overrides act on the complete form, so they may name fields the file leaves at default.
    json full = scene_to_json(s);
    apply_overrides(full, overrides);
    s = scene_from_json(full, where);
  }
  s.base_dir = base_dir;
  check_scene(s, where);
  return s;
}

scene load_scene(const std::string& path, const std::vector<scene_override>& overrides) {
  const std::string text = read_text_file(path);
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  return parse_scene(text, path, dir, overrides);
}

void save_scene(const scene& s, const std::string& path) { write_file_atomic(path, scene_to_json(s).dump(2) + "\n"); }

}  // namespace airr
