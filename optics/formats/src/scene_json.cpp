#include "airr/formats/scene_json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include "airr/core/error.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/emission_profile.hpp"
#include "airr/models/preset.hpp"
#include "airr/models/retro_model.hpp"
#include "json_enum.hpp"
#include "scene_json_environment.hpp"
#include "scene_json_polarization.hpp"

namespace airr {

using nlohmann::json;

void rebase_model_paths(retro_model_params& m, const std::string& old_dir, const std::string& new_dir) {
  const retro_model_kind& kind = find_retro_model_kind(m.type);
  for (auto& [key, value] : m.values) {
    const model_field* f = find_field(kind.fields, key);
    auto* text = std::get_if<std::string>(&value);
    if (!f || !text) continue;
    if (f->kind == field_kind::path || (f->kind == field_kind::preset && is_preset_path(*text)))
      *text = rebase_path(*text, old_dir, new_dir);
  }
}

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
    rebase_model_paths(r.model, s.base_dir, new_dir);
  }
  out.base_dir = new_dir;
  return out;
}

// ---------------------------------------------------------------- writing

static json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

static json part_json(const part_params& p, json_form form) {
  json j = {{"mesh", p.mesh}, {"width_mm", p.width_mm}, {"height_mm", p.height_mm}, {"pose", pose_to_json(p.pose)}};
  // Saved only when there are any, as props are.
  if (form == json_form::complete || !p.films.empty()) j["films"] = films_to_json(p.films);
  return j;
}

static json prop_to_json(const prop_params& p) {
  return {{"name", p.name},
          {"mesh", p.mesh},
          {"node", p.node},
          {"scale", p.scale},
          {"pose", pose_to_json(p.pose)},
          {"surface", prop_surface_names[int(p.surface)]},
          {"albedo", p.albedo},
          {"visible", p.visible},
          {"tessellation_mm", p.tessellation_mm}};
}

static const char* placement_name(observer_placement p) { return p == observer_placement::orbit ? "orbit" : "look_at"; }
static const char* lens_name(observer_lens l) { return l == observer_lens::pinhole ? "pinhole" : "thin_lens"; }

json scene_to_json(const scene& s, json_form form) {
  const auto part_to_json = [&](const part_params& p) { return part_json(p, form); };
  json src = part_to_json(s.source);
  src["image"] = s.source.image;
  src["intensity"] = s.source.intensity;
  if (form == json_form::complete || in_cd_m2(s.source)) src["luminance_cd_m2"] = s.source.luminance_cd_m2;
  src["emission_profile"] = s.source.emission_profile;
  src["bezel_mm"] = s.source.bezel_mm;
  if (form == json_form::complete || s.source.polarization != source_polarization{})
    src["polarization"] = polarization_to_json(s.source.polarization);
  json hm = part_to_json(s.half_mirror);
  hm["reflectance"] = s.half_mirror.reflectance;
  hm["transmittance"] = s.half_mirror.transmittance;
  if (form == json_form::complete || s.half_mirror.kind != half_mirror_kind::half_mirror) {
    hm["kind"] = half_mirror_kind_names[int(s.half_mirror.kind)];
    hm["polarizer"] = reflective_polarizer_to_json(s.half_mirror.polarizer);
  }
  if (form == json_form::complete || s.half_mirror.kind == half_mirror_kind::plate)
    hm["plate"] = plate_to_json(s.half_mirror.plate);
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
  if (form == json_form::complete || o.analyzer_deg) out["observer"]["analyzer_deg"] = optional_number(o.analyzer_deg);
  if (environment_written(s.environment, form)) out["environment"] = environment_to_json(s.environment);
  // Written only when there are any, so layouts without props keep their form.
  if (!s.props.empty()) {
    json props = json::array();
    for (const auto& p : s.props) props.push_back(prop_to_json(p));
    out["props"] = props;
  }
  return out;
}

// ---------------------------------------------------------------- reading

// The fields every part has; the caller reads its own and finishes.
static void read_part(json_reader& r, part_params& p) {
  r.string("mesh", p.mesh);
  r.number("width_mm", p.width_mm);
  r.number("height_mm", p.height_mm);
  if (r.has("pose")) read_pose(r.child("pose"), p.pose);
  read_films(r, p.films);
}

void read_model(json_reader r, const json& j, const std::string& where, retro_model_params& m) {
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

static void read_prop(json_reader r, prop_params& p) {
  r.string("name", p.name);
  p.mesh = r.string("mesh");
  r.string("node", p.node);
  r.number("scale", p.scale);
  if (r.has("pose")) read_pose(r.child("pose"), p.pose);
  read_enum(r, "surface", p.surface, std::array{"absorber", "diffuse", "mirror", "material"});
  r.numbers("albedo", p.albedo);
  r.boolean("visible", p.visible);
  r.number("tessellation_mm", p.tessellation_mm);
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
  r.nullable_number("analyzer_deg", o.analyzer_deg);
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
    c.number("luminance_cd_m2", s.source.luminance_cd_m2);
    c.string("emission_profile", s.source.emission_profile);
    c.number("bezel_mm", s.source.bezel_mm);
    if (c.has("polarization")) read_polarization(c.child("polarization"), s.source.polarization);
    c.finish();
  }
  if (r.has("half_mirror")) {
    auto c = r.child("half_mirror");
    read_part(c, s.half_mirror);
    c.number("reflectance", s.half_mirror.reflectance);
    c.number("transmittance", s.half_mirror.transmittance);
    read_enum(c, "kind", s.half_mirror.kind, half_mirror_kind_names);
    if (s.half_mirror.kind == half_mirror_kind::reflective_polarizer) c.require("polarizer");
    if (s.half_mirror.kind == half_mirror_kind::plate) c.require("plate");
    if (c.has("polarizer")) read_reflective_polarizer(c.child("polarizer"), s.half_mirror.polarizer);
    if (c.has("plate")) read_plate(c.child("plate"), s.half_mirror.plate);
    derive_half_mirror_light(s.half_mirror);
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
  if (r.has("environment")) read_environment(r.child("environment"), s.environment);
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

// ---------------------------------------------------------------- files

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

scene load_scene(const std::string& path, const std::vector<scene_override>& overrides,
                 std::vector<std::string>& notes) {
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  if (!is_gltf_path(path)) return parse_scene(read_text_file(path), path, dir, overrides);
  const gltf_layout layout = read_gltf_layout(path);
  notes.insert(notes.end(), layout.notes.begin(), layout.notes.end());
  try {
    return scene_from_document(layout.document, path, dir, overrides);
  } catch (const input_error& e) {
    throw input_error(gltf_layout_error(layout, e.what()));
  }
}

scene load_scene(const std::string& path, const std::vector<scene_override>& overrides) {
  std::vector<std::string> unread;
  return load_scene(path, overrides, unread);
}

void save_scene(const scene& s, const std::string& path) { write_file_atomic(path, scene_to_json(s).dump(2) + "\n"); }

}  // namespace airr
