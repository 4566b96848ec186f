#include "airr/optics/scene_json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "airr/optics/emission_profile.hpp"
#include "airr/optics/error.hpp"
#include "airr/optics/gltf_layout.hpp"
#include "airr/optics/json_reader.hpp"
#include "airr/optics/layout.hpp"
#include "airr/optics/mesh_gltf.hpp"
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
  rebase(out.source.emission_profile);
  rebase(out.half_mirror.mesh);
  for (auto& p : out.props) rebase(p.mesh);
  for (auto& r : out.retroreflectors) {
    rebase(r.mesh);
    const retro_model_kind& kind = find_retro_model_kind(r.model.type);
    for (auto& [key, value] : r.model.values) {
      const model_field* f = find_field(kind.fields, key);
      auto* text = std::get_if<std::string>(&value);
      if (!f || !text) continue;
      if (f->kind == field_kind::path || (f->kind == field_kind::preset && is_preset_path(*text))) rebase(*text);
    }
  }
  out.base_dir = new_dir;
  return out;
}

// ---------------------------------------------------------------- writing

static json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

static json pose_to_json(const pose& p) {
  return {{"center_mm", p.center_mm}, {"yaw_deg", p.yaw_deg}, {"pitch_deg", p.pitch_deg}, {"roll_deg", p.roll_deg}};
}

static json part_to_json(const part_params& p) {
  return {{"mesh", p.mesh}, {"width_mm", p.width_mm}, {"height_mm", p.height_mm}, {"pose", pose_to_json(p.pose)}};
}

static json prop_to_json(const prop_params& p) {
  return {{"name", p.name},
          {"mesh", p.mesh},
          {"node", p.node},
          {"scale", p.scale},
          {"pose", pose_to_json(p.pose)},
          {"surface", prop_surface_names[int(p.surface)]},
          {"albedo", p.albedo},
          {"visible", p.visible}};
}

static const char* placement_name(observer_placement p) { return p == observer_placement::orbit ? "orbit" : "look_at"; }
static const char* lens_name(observer_lens l) { return l == observer_lens::pinhole ? "pinhole" : "thin_lens"; }

json scene_to_json(const scene& s) {
  json src = part_to_json(s.source);
  src["image"] = s.source.image;
  src["intensity"] = s.source.intensity;
  src["emission_profile"] = s.source.emission_profile;
  src["bezel_mm"] = s.source.bezel_mm;
  json hm = part_to_json(s.half_mirror);
  hm["reflectance"] = s.half_mirror.reflectance;
  hm["transmittance"] = s.half_mirror.transmittance;
  json sheets = json::array();
  for (const auto& r : s.retroreflectors) {
    json j = part_to_json(r);
    j["model"] = model_values_to_json(r.model, find_retro_model_kind(r.model.type).fields);
    sheets.push_back(j);
  }
  const observer_params& o = s.observer;
  json out = {
      {"format", "airr-scene"},
      {"version", s.version},
      {"seed", s.seed},
      {"source", src},
      {"half_mirror", hm},
      {"retroreflectors", sheets},
      {"observer",
       {{"placement", placement_name(o.placement)},
        {"azimuth_deg", o.azimuth_deg},
        {"elevation_deg", o.elevation_deg},
        {"distance_mm", o.distance_mm},
        {"position_mm", o.position_mm},
        {"look_at_mm", o.look_at_mm},
        {"lens", lens_name(o.lens)},
        {"focal_length_mm", o.focal_length_mm},
        {"f_number", o.f_number},
        {"focus_distance_mm", optional_number(o.focus_distance_mm)},
        {"fov_deg", o.fov_deg},
        {"width", o.width},
        {"height", o.height}}},
      {"render", {{"max_depth", s.render.max_depth}}},
  };
  // Written only when there are any, so layouts without props keep their form.
  if (!s.props.empty()) {
    json props = json::array();
    for (const auto& p : s.props) props.push_back(prop_to_json(p));
    out["props"] = props;
  }
  return out;
}

// ---------------------------------------------------------------- reading

static void read_pose(json_reader r, pose& p) {
  r.numbers("center_mm", p.center_mm);
  r.number("yaw_deg", p.yaw_deg);
  r.number("pitch_deg", p.pitch_deg);
  r.number("roll_deg", p.roll_deg);
  r.finish();
}

// The fields every part has; the caller reads its own and finishes.
static void read_part(json_reader& r, part_params& p) {
  r.string("mesh", p.mesh);
  r.number("width_mm", p.width_mm);
  r.number("height_mm", p.height_mm);
  if (r.has("pose")) read_pose(r.child("pose"), p.pose);
}

// `where` is the model's dotted path, e.g. "retroreflectors[0].model".
static void read_model(json_reader r, const json& j, const std::string& where, retro_model_params& m) {
  std::string type = m.type;
  r.string("type", type);
  const retro_model_kind* kind = nullptr;
  try {
    kind = &find_retro_model_kind(type, where);
  } catch (const input_error& e) {
    throw input_error(r.origin() + ": " + e.what());
  }
  m = retro_model_params{};
  m.type = type;
  for (const auto& [key, value] : j.items()) {
    if (key == "type") continue;
    model_value_from_json(m, kind->fields, key, value, r.origin(), where);
    r.raw(key);
  }
  r.finish();
}

template <class Enum, std::size_t N>
static void read_enum(json_reader& r, const std::string& key, Enum& out, const std::array<const char*, N>& names) {
  if (!r.has(key)) return;
  std::string v;
  r.string(key, v);
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (v == names[i]) {
      out = static_cast<Enum>(i);
      return;
    }
    list += (i ? ", " : "") + std::string(names[i]);
  }
  r.fail(r.field(key), "unknown value '" + v + "' (" + list + ")");
}

static void read_prop(json_reader r, prop_params& p) {
  r.string("name", p.name);
  p.mesh = r.string("mesh");
  r.string("node", p.node);
  r.number("scale", p.scale);
  if (r.has("pose")) read_pose(r.child("pose"), p.pose);
  read_enum(r, "surface", p.surface, std::array{"absorber", "diffuse", "mirror", "material"});
  r.numbers("albedo", p.albedo);
  r.boolean("visible", p.visible);
  r.finish();
}

static void read_observer(json_reader r, observer_params& o) {
  read_enum(r, "placement", o.placement, std::array{"orbit", "look_at"});
  r.number("azimuth_deg", o.azimuth_deg);
  r.number("elevation_deg", o.elevation_deg);
  r.number("distance_mm", o.distance_mm);
  r.numbers("position_mm", o.position_mm);
  r.numbers("look_at_mm", o.look_at_mm);
  read_enum(r, "lens", o.lens, std::array{"pinhole", "thin_lens"});
  r.number("focal_length_mm", o.focal_length_mm);
  r.number("f_number", o.f_number);
  r.nullable_number("focus_distance_mm", o.focus_distance_mm);
  r.number("fov_deg", o.fov_deg);
  r.integer("width", o.width);
  r.integer("height", o.height);
  r.finish();
}

static scene scene_from_json_v2(json_reader& r) {
  scene s;
  if (r.has("seed")) {
    const auto& v = r.raw("seed");
    if (!v.is_number_integer() || (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() < 0)) {
      r.fail("seed", "must be a non-negative integer");
    }
    s.seed = v.get<std::uint64_t>();
  }
  if (r.has("source")) {
    auto c = r.child("source");
    read_part(c, s.source);
    c.string("image", s.source.image);
    c.number("intensity", s.source.intensity);
    c.string("emission_profile", s.source.emission_profile);
    c.number("bezel_mm", s.source.bezel_mm);
    c.finish();
  }
  if (r.has("half_mirror")) {
    auto c = r.child("half_mirror");
    read_part(c, s.half_mirror);
    c.number("reflectance", s.half_mirror.reflectance);
    c.number("transmittance", s.half_mirror.transmittance);
    c.finish();
  }
  if (r.has("retroreflectors")) {
    const json& list = r.raw("retroreflectors");
    if (!list.is_array() || list.empty() || list.size() > std::size_t(max_retroreflectors)) {
      r.fail("retroreflectors", "must be an array of 1 to " + std::to_string(max_retroreflectors) + " sheets");
    }
    s.retroreflectors.assign(list.size(), retroreflector_params{});
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = "retroreflectors[" + std::to_string(i) + "]";
      json_reader c(list[i], r.origin(), where);
      read_part(c, s.retroreflectors[i]);
      if (c.has("model"))
        read_model(c.child("model"), list[i].at("model"), where + ".model", s.retroreflectors[i].model);
      c.finish();
    }
  }
  if (r.has("props")) {
    const json& list = r.raw("props");
    if (!list.is_array() || list.size() > std::size_t(max_props)) {
      r.fail("props", "must be an array of at most " + std::to_string(max_props) + " props");
    }
    s.props.assign(list.size(), prop_params{});
    for (std::size_t i = 0; i < list.size(); ++i)
      read_prop(json_reader(list[i], r.origin(), "props[" + std::to_string(i) + "]"), s.props[i]);
  }
  if (r.has("observer")) read_observer(r.child("observer"), s.observer);
  if (r.has("render")) {
    auto c = r.child("render");
    c.integer("max_depth", s.render.max_depth);
    c.finish();
  }
  r.finish();
  return s;
}

scene scene_from_json(const json& j, const std::string& origin) {
  json_reader r(j, origin, "");
  std::string format = "airr-scene";
  r.string("format", format);
  if (format != "airr-scene") r.fail("format", "expected \"airr-scene\", found \"" + format + "\"");
  int version = scene_format_version;
  r.integer("version", version);
  if (version == 1) return scene_from_json(migrate_scene_v1(j, origin), origin + " (version 1)");
  if (version != scene_format_version) {
    r.fail("version", "unsupported version " + std::to_string(version) + " (this build reads 1 and " +
                          std::to_string(scene_format_version) + ")");
  }
  return scene_from_json_v2(r);
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
  }
  void pose(const std::string& field, const airr::pose& p) const {
    position(field + ".center_mm", p.center_mm);
    range(field + ".yaw_deg", p.yaw_deg, -360, 360);
    range(field + ".pitch_deg", p.pitch_deg, -360, 360);
    range(field + ".roll_deg", p.roll_deg, -360, 360);
  }
};
}  // namespace

void validate_scene(const scene& s, const std::string& origin) {
  const checker c{origin};
  c.part("source", s.source);
  c.range("source.intensity", s.source.intensity, 0, 1e9);
  c.range("source.bezel_mm", s.source.bezel_mm, 0, 1e4);
  c.part("half_mirror", s.half_mirror);
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
  if (static_cast<long long>(o.width) * o.height > max_resolution_pixels) {
    c.fail("observer.width", "resolution " + std::to_string(o.width) + "x" + std::to_string(o.height) +
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
      cached_prop_mesh(resolve_scene_path(s, s.props[i].mesh), s.props[i].node);
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

// ---------------------------------------------------------------- version 1

json migrate_scene_v1(const json& j, const std::string& origin) {
  // Version 1 was the canonical bench: D and a source offset placed the display, the sheet sat at
  // z = -distance tilted about x, the camera looked along -z at (0, 0, D).
  json_reader r(j, origin, "");
  std::string format;
  r.string("format", format);
  int version = 1;
  r.integer("version", version);
  double d = 150;
  r.number("floating_distance_mm", d);
  json out = {{"format", "airr-scene"}, {"version", 2}};
  if (r.has("seed")) out["seed"] = r.raw("seed");

  std::array<double, 3> offset{0, 0, 0};
  json src = {{"pose", {{"center_mm", {0.0, -d, 0.0}}, {"pitch_deg", 90.0}}}};
  if (r.has("source")) {
    auto c = r.child("source");
    for (const char* key : {"image", "mesh", "width_mm", "height_mm", "intensity"}) {
      if (c.has(key)) src[key] = c.raw(key);
    }
    c.numbers("offset_mm", offset);
    c.finish();
    src["pose"]["center_mm"] = {offset[0], -d + offset[1], offset[2]};
  }
  out["source"] = src;
  if (r.has("half_mirror")) {
    auto c = r.child("half_mirror");
    json hm = json::object();
    for (const char* key : {"mesh", "width_mm", "height_mm", "reflectance", "transmittance"}) {
      if (c.has(key)) hm[key] = c.raw(key);
    }
    c.finish();
    out["half_mirror"] = hm;
  }
  json sheet = json::object();
  double rr_distance = 150, tilt = 0;
  if (r.has("retroreflector")) {
    auto c = r.child("retroreflector");
    for (const char* key : {"mesh", "width_mm", "height_mm"}) {
      if (c.has(key)) sheet[key] = c.raw(key);
    }
    c.number("distance_mm", rr_distance);
    c.number("tilt_deg", tilt);
    if (c.has("model")) {
      // Version 1 wrote every model's fields; the active model's non-null ones carry over.
      const json& m = c.raw("model");
      if (!m.is_object()) c.fail(c.field("model"), "must be a JSON object");
      const std::string type = m.contains("type") && m["type"].is_string() ? m["type"].get<std::string>() : "ideal";
      json model = {{"type", type}};
      const retro_model_kind* kind = nullptr;
      for (const retro_model_kind* k : retro_model_kinds()) {
        if (k->name == type) kind = k;
      }
      static const std::set<std::string> v1_keys = {"type",
                                                    "mu",
                                                    "preset",
                                                    "a_per_mm",
                                                    "c_mm",
                                                    "reference_distance_mm",
                                                    "shift_table",
                                                    "alpha_surface",
                                                    "alpha_internal",
                                                    "internal_reflectance",
                                                    "eta"};
      for (const auto& [key, value] : m.items()) {
        if (!v1_keys.count(key)) c.fail(c.field("model." + key), "unknown key");
        if (key == "type" || value.is_null() || !kind || !find_field(kind->fields, key)) continue;
        model[key] = value;
      }
      sheet["model"] = model;
    }
    c.finish();
  }
  sheet["pose"] = {{"center_mm", {0.0, 0.0, -rr_distance}}, {"pitch_deg", tilt}};
  out["retroreflectors"] = json::array({sheet});

  json observer = json::object();
  double cam_distance = 300;
  if (r.has("camera")) {
    auto c = r.child("camera");
    for (const char* key : {"fov_deg", "width", "height"}) {
      if (c.has(key)) observer[key] = c.raw(key);
    }
    c.number("distance_mm", cam_distance);
    c.finish();
  }
  if (offset == std::array<double, 3>{0, 0, 0}) {
    observer["distance_mm"] = cam_distance;
  } else {
    // The version 1 camera stayed on the canonical axis when the source moved.
    observer["placement"] = "look_at";
    observer["position_mm"] = {0.0, 0.0, d + cam_distance};
    observer["look_at_mm"] = {0.0, 0.0, d};
  }
  out["observer"] = observer;
  if (r.has("render")) out["render"] = r.raw("render");
  r.finish();
  return out;
}

// ---------------------------------------------------------------- overrides

scene_override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw input_error("--set " + text + ": expected key=value, e.g. retroreflectors.0.pose.pitch_deg=20");
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

// The model object m switched to `type`: the values the old model set and the new one has carry
// over, defaults do not (an unknown type is left for the reader to report).
static bool switch_model_type(json& m, const std::string& type, const std::string& where) {
  if (!m.is_object() || !m.contains("type") || !m["type"].is_string()) return false;
  const auto known = [](const std::string& name) {
    const auto& kinds = retro_model_kinds();
    return std::any_of(kinds.begin(), kinds.end(), [&](const retro_model_kind* k) { return k->name == name; });
  };
  if (!known(m["type"].get<std::string>()) || !known(type)) return false;
  retro_model_params old{.type = m["type"].get<std::string>(), .values = {}};
  const retro_model_kind& old_kind = find_retro_model_kind(old.type);
  for (const auto& [key, value] : m.items()) {
    if (key != "type") model_value_from_json(old, old_kind.fields, key, value, "--set", where);
  }
  m = model_values_to_json(with_model_type(old, type), find_retro_model_kind(type).fields);
  return true;
}

void apply_overrides(json& j, const std::vector<scene_override>& overrides) {
  for (const auto& o : overrides) {
    json* node = &j;
    json* parent = nullptr;
    std::string rest = o.key;
    std::string walked;
    while (true) {
      const auto dot = rest.find('.');
      const std::string part = rest.substr(0, dot);
      walked += (walked.empty() ? "" : ".") + part;
      parent = node;
      if (node->is_array()) {
        // Sheets are numbered from 0: retroreflectors.1.pose.pitch_deg.
        std::size_t index = 0, used = 0;
        try {
          index = std::stoul(part, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != part.size() || part.empty() || index >= node->size()) {
          throw input_error("--set " + o.key + ": no element '" + walked + "' (" + std::to_string(node->size()) +
                            " present, numbered from 0)");
        }
        node = &(*node)[index];
      } else {
        if (!node->is_object() || !node->contains(part))
          throw input_error("--set " + o.key + ": unknown key '" + walked + "'");
        node = &(*node)[part];
      }
      if (dot == std::string::npos) break;
      rest = rest.substr(dot + 1);
    }
    const json value = override_value(o.value);
    const bool model_type = walked.size() >= 10 && walked.compare(walked.size() - 10, 10, "model.type") == 0;
    if (model_type && value.is_string() &&
        switch_model_type(*parent, value.get<std::string>(), walked.substr(0, walked.size() - 5))) {
      continue;
    }
    if (node->is_number() && value.is_number_float() && !std::isfinite(value.get<double>())) {
      throw input_error("--set " + o.key + ": must be a finite number (got " + o.value + ")");
    }
    if (node->is_object() || (node->is_array() && !value.is_array())) {
      throw input_error("--set " + o.key + ": names a group, not a value");
    }
    *node = value;
  }
}

// ---------------------------------------------------------------- files

scene with_overrides(scene s, const std::vector<scene_override>& overrides, const std::string& origin) {
  // The floating distance is derived from the display's pose; setting it moves the display.
  std::vector<scene_override> fields;
  std::optional<std::string> distance;
  for (const auto& o : overrides) {
    if (o.key == floating_distance_key) {
      distance = o.value;
    } else if (o.key == tilt_key) {
      fields.push_back({"retroreflectors.0.pose.pitch_deg", o.value});
    } else {
      fields.push_back(o);
    }
  }
  if (!fields.empty()) {
    // Overrides act on the complete form, so they may name fields the file leaves at default.
    json full = scene_to_json(s);
    apply_overrides(full, fields);
    const std::string base_dir = s.base_dir;
    s = scene_from_json(full, origin);
    s.base_dir = base_dir;
  }
  if (distance) {
    const json v = override_value(*distance);
    if (!v.is_number()) throw input_error("--set " + std::string(floating_distance_key) + ": must be a number");
    try {
      set_floating_distance(s, v.get<double>());
    } catch (const input_error& e) {
      throw input_error("--set " + std::string(e.what()));
    }
  }
  return s;
}

// A scene document (JSON form) read, overridden, given its folder and checked.
static scene scene_from_document(const json& j, const std::string& origin, const std::string& base_dir,
                                 const std::vector<scene_override>& overrides) {
  const std::string where = overrides.empty() ? origin : origin + " (with --set)";
  scene s = with_overrides(scene_from_json(j, origin), overrides, where);
  s.base_dir = base_dir;
  check_scene(s, where);
  return s;
}

scene parse_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                  const std::vector<scene_override>& overrides) {
  return scene_from_document(parse_json(text, origin), origin, base_dir, overrides);
}

scene load_scene(const std::string& path, const std::vector<scene_override>& overrides) {
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  if (is_gltf_path(path)) return scene_from_document(gltf_layout_document(path), path, dir, overrides);
  return parse_scene(read_text_file(path), path, dir, overrides);
}

void save_scene(const scene& s, const std::string& path) { write_file_atomic(path, scene_to_json(s).dump(2) + "\n"); }

}  // namespace airr
