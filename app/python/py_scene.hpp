#pragma once
// The Python module's Scene: a layout read from a file, with the `--set` overrides made to it
// since, applied and checked exactly as `airr --set` applies and checks them.
#include <string>
#include <vector>

#include "airr/formats/scene_json.hpp"
#include "airr/layout/scene.hpp"

namespace airr::python {

class py_scene {
 public:
  // Reads and checks the file (JSON, or a glTF layout). Throws input_error.
  static py_scene load(const std::string& path);

  // Applies `key=value` after the overrides so far; the scene is unchanged when that fails.
  // Throws input_error with the message `airr --set key=value` gives.
  void set(const std::string& key, const std::string& value);
  // The value a key names (the short keys floating_distance_mm and tilt_deg included).
  nlohmann::json get(const std::string& key) const { return scene_value(scene_, key); }

  // Writes the scene (atomically), its relative paths counting from the file's folder; the file
  // is then the scene's origin.
  void save(const std::string& path);

  const scene& current() const { return scene_; }
  const std::string& path() const { return path_; }
  const std::vector<scene_override>& overrides() const { return overrides_; }
  std::string json_text() const { return scene_to_json(scene_).dump(2); }

 private:
  scene read(const std::vector<scene_override>& overrides) const;

  std::string path_;
  std::string text_;  // the file's text as read (a JSON scene); empty for a glTF layout
  std::vector<scene_override> overrides_;
  scene scene_;
};

}  // namespace airr::python
