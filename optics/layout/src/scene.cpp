#include "airr/layout/scene.hpp"

#include "airr/core/files.hpp"

namespace airr {

std::string resolve_scene_path(const scene& s, const std::string& path) { return resolve_path(path, s.base_dir); }

}  // namespace airr
