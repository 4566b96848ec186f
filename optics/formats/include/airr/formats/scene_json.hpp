#pragma once
// Versioned JSON form of the layout: strict loading (unknown keys, wrong types and out-of-range
// values are errors naming the file and the field), exact round trips, atomic saves.
#include <memory>

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/layout/scene.hpp"
#include "airr/layout/sheet_models.hpp"
#include "airr/models/retro_model.hpp"

namespace airr {

// A command-line key that is not a field: the floating distance (see set_floating_distance).
inline constexpr const char* floating_distance_key = "floating_distance_mm";
// Short for the first sheet's pitch, retroreflectors.0.pose.pitch_deg: the tilt.
inline constexpr const char* tilt_key = "tilt_deg";

// A sheet's model set from a named sheet: retroreflectors.N.sheet=NAME (a shipped sheet of
// assets/sheets, e.g. prism-rf-ay-like) or =PATH.json; applied before the other overrides.
inline constexpr const char* named_sheet_suffix = ".sheet";

// A command-line override "dotted.key=value", e.g. "retroreflectors.0.pose.pitch_deg=20"
// (array elements by index), "floating_distance_mm=200", "tilt_deg=20" or
// "retroreflectors.0.sheet=prism-rf-ay-like".
struct scene_override {
  std::string key;
  std::string value;
};
scene_override parse_override(const std::string& text);

// The current version's form (version 2): as files are saved (fields at their defaults that older
// files lack left out: props, films, polarization), or complete, as --set acts on it.
enum class json_form { saved, complete };
nlohmann::json scene_to_json(const scene& s, json_form form = json_form::saved);
// Reads version 2, or version 1 through migrate_scene_v1. `origin` names the file (or "--set") in
// error messages.
scene scene_from_json(const nlohmann::json& j, const std::string& origin);
// A version 1 document (the canonical bench with D, offsets, tilt and an on-axis camera) in the
// version 2 form of the same layout; unknown keys are errors, as in version 1.
nlohmann::json migrate_scene_v1(const nlohmann::json& j, const std::string& origin);

// Applies overrides to the JSON form; the key must name an existing field.
void apply_overrides(nlohmann::json& j, const std::vector<scene_override>& overrides);
// The scene with overrides applied, the short keys (floating distance, tilt) included; not
// validated. `origin` names the overrides in error messages.
scene with_overrides(scene s, const std::vector<scene_override>& overrides, const std::string& origin);

// The number an override key names in s (the short keys included); throws input_error for a key
// the scene does not have or that names no number (an unset value, a group, a text).
double scene_number(const scene& s, const std::string& key);
// The value an override key names in s, as the scene's complete JSON holds it (a number, text,
// true/false, null for an unset value, a list or a group); throws input_error for a key it lacks.
nlohmann::json scene_value(const scene& s, const std::string& key);

// Checks every value's range; throws input_error "<origin>: <field>: <problem>".
void validate_scene(const scene& s, const std::string& origin);
// Checks that every referenced file exists.
void validate_scene_files(const scene& s, const std::string& origin);

// All of the above plus the layout, the emission profile and the retroreflector models (presets,
// tables) resolving; returns the models it built, for the caller to share.
retro_model_list check_scene(const scene& s, const std::string& origin);

// Reads, overrides, validates (values, files and layout). A .gltf or .glb file is read as a whole
// layout (read_gltf_layout): its notes and warnings are appended to `notes` (lines "note: ..." or
// "warning: ...", for the caller to show), and its errors name the node a field came from.
// Throws input_error.
scene load_scene(const std::string& path, const std::vector<scene_override>& overrides,
                 std::vector<std::string>& notes);
scene load_scene(const std::string& path, const std::vector<scene_override>& overrides = {});
// Parses scene JSON text (base_dir for relative paths), then as load_scene.
scene parse_scene(const std::string& text, const std::string& origin, const std::string& base_dir,
                  const std::vector<scene_override>& overrides = {});

// Writes the scene to a temporary file beside `path`, then renames it over `path`.
void save_scene(const scene& s, const std::string& path);

// The scene with its relative paths rewritten to count from new_dir (for saving it there).
scene rebase_scene_paths(const scene& s, const std::string& new_dir);
// A model's path and preset-file values rewritten from old_dir to new_dir.
void rebase_model_paths(retro_model_params& m, const std::string& old_dir, const std::string& new_dir);

// Reads a model object (`j` is what `r` reads; "type" and the model's fields) into m, strictly.
// `where` is the model's dotted path in errors, e.g. "retroreflectors[0].model".
void read_model(json_reader r, const nlohmann::json& j, const std::string& where, retro_model_params& m);

}  // namespace airr
