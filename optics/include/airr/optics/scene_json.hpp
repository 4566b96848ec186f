#pragma once
// Versioned JSON form of the layout: strict loading (unknown keys, wrong types and out-of-range
// values are errors naming the file and the field), exact round trips, atomic saves.
#include <memory>

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "airr/optics/files.hpp"
#include "airr/optics/scene.hpp"

namespace airr {

class retro_model;

// A command-line override "dotted.key=value", e.g. "retroreflector.tilt_deg=20".
struct scene_override {
  std::string key;
  std::string value;
};
scene_override parse_override(const std::string& text);

nlohmann::json scene_to_json(const scene& s);
// `origin` names the file (or "--set") in error messages.
scene scene_from_json(const nlohmann::json& j, const std::string& origin);

// Applies overrides to the JSON form; the key must name an existing field.
void apply_overrides(nlohmann::json& j, const std::vector<scene_override>& overrides);

// Checks every value's range; throws input_error "<origin>: <field>: <problem>".
void validate_scene(const scene& s, const std::string& origin);
// Checks that every referenced file exists.
void validate_scene_files(const scene& s, const std::string& origin);

// All of the above plus the layout and the retroreflector model (presets, tables) resolving;
// returns the model it built, for the caller to share.
std::shared_ptr<const retro_model> check_scene(const scene& s, const std::string& origin);

// Reads, overrides, validates (values, files and layout). Throws input_error.
scene load_scene(const std::string& path, const std::vector<scene_override>& overrides = {});
// Parses scene JSON text (base_dir for relative paths), then as load_scene.
scene parse_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                  const std::vector<scene_override>& overrides = {});

// Writes the scene to a temporary file beside `path`, then renames it over `path`.
void save_scene(const scene& s, const std::string& path);

// The scene with its relative paths rewritten to count from new_dir (for saving it there).
scene rebase_scene_paths(const scene& s, const std::string& new_dir);

}  // namespace airr
