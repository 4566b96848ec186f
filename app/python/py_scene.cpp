#include "py_scene.hpp"

#include <filesystem>

#include "airr/core/files.hpp"
#include "airr/formats/gltf_layout.hpp"

namespace airr::python {

py_scene py_scene::load(const std::string& path) {
  py_scene s;
  s.path_ = path;
  if (!is_gltf_path(path)) s.text_ = read_text_file(path);
  s.scene_ = s.read({});
  return s;
}

// The file as it was read (not as it may have changed since), with the overrides, as load_scene
// reads it.
scene py_scene::read(const std::vector<scene_override>& overrides) const {
  if (text_.empty()) return load_scene(path_, overrides);
  const std::string dir = std::filesystem::absolute(path_).parent_path().string();
  return parse_scene(text_, path_, dir, overrides);
}

void py_scene::set(const std::string& key, const std::string& value) {
  std::vector<scene_override> more = overrides_;
  more.push_back({key, value});
  scene_ = read(more);
  overrides_ = std::move(more);
}

void py_scene::save(const std::string& path) {
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  save_scene(rebase_scene_paths(scene_, dir), path);
  *this = load(path);
}

}  // namespace airr::python
