// Version 1 scene documents (the canonical bench) in the version 2 form.
#include "airr/formats/scene_json.hpp"

#include <cmath>

#include "airr/core/error.hpp"
#include "airr/core/json_reader.hpp"

namespace airr {

using nlohmann::json;

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

}  // namespace airr
