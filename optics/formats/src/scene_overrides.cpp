// Command-line overrides (--set key=value) on the JSON form, and the derived keys.
#include "airr/formats/scene_json.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "airr/core/error.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

using nlohmann::json;

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

// The node a dotted key names (array elements by index), its parent, and the key as walked.
struct key_node {
  json* node = nullptr;
  json* parent = nullptr;
  std::string walked;
};

static key_node find_key(json& j, const std::string& key) {
  key_node out{&j, nullptr, ""};
  json*& node = out.node;
  json*& parent = out.parent;
  std::string& walked = out.walked;
  std::string rest = key;
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
        throw input_error("--set " + key + ": no element '" + walked + "' (" + std::to_string(node->size()) +
                          " present, numbered from 0)");
      }
      node = &(*node)[index];
    } else {
      if (!node->is_object() || !node->contains(part))
        throw input_error("--set " + key + ": unknown key '" + walked + "'");
      node = &(*node)[part];
    }
    if (dot == std::string::npos) break;
    rest = rest.substr(dot + 1);
  }
  return out;
}

void apply_overrides(json& j, const std::vector<scene_override>& overrides) {
  for (const auto& o : overrides) {
    const auto [node, parent, walked] = find_key(j, o.key);
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

// retroreflectors.N.sheet=NAME: the sheet's model becomes the named sheet's.
static void use_named_sheet(scene& s, const scene_override& o) {
  const std::string index = o.key.substr(16, o.key.size() - 16 - std::string(named_sheet_suffix).size());
  std::size_t i = 0, used = 0;
  try {
    i = std::stoul(index, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (index.empty() || used != index.size() || i >= s.retroreflectors.size()) {
    throw input_error("--set " + o.key + ": no sheet '" + index + "' (" + std::to_string(s.retroreflectors.size()) +
                      " present, numbered from 0)");
  }
  const json v = override_value(o.value);
  if (!v.is_string()) throw input_error("--set " + o.key + ": must name a sheet");
  try {
    use_sheet_model(s.retroreflectors[i], load_named_sheet(v.get<std::string>()), s.base_dir);
  } catch (const input_error& e) {
    throw input_error("--set " + o.key + ": " + e.what());
  }
}

scene with_overrides(scene s, const std::vector<scene_override>& overrides, const std::string& origin) {
  // The floating distance is derived from the display's pose; setting it moves the display.
  std::vector<scene_override> fields;
  std::optional<std::string> distance;
  for (const auto& o : overrides) {
    if (o.key.starts_with("retroreflectors.") && o.key.ends_with(named_sheet_suffix)) {
      use_named_sheet(s, o);
    } else if (o.key == floating_distance_key) {
      distance = o.value;
    } else if (o.key == tilt_key) {
      fields.push_back({"retroreflectors.0.pose.pitch_deg", o.value});
    } else {
      fields.push_back(o);
    }
  }
  if (!fields.empty()) {
    // Overrides act on the complete form, so they may name fields the file leaves at default.
    json full = scene_to_json(s, json_form::complete);
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

json scene_value(const scene& s, const std::string& key) {
  if (key == floating_distance_key) return floating_distance(s);
  json full = scene_to_json(s, json_form::complete);
  return *find_key(full, key == tilt_key ? "retroreflectors.0.pose.pitch_deg" : key).node;
}

double scene_number(const scene& s, const std::string& key) {
  const json v = scene_value(s, key);
  if (!v.is_number()) throw input_error("--set " + key + ": not a number in the scene");
  return v.get<double>();
}

}  // namespace airr
