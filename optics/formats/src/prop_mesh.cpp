#include "airr/formats/prop_mesh.hpp"

#include "airr/core/files.hpp"
#include "airr/formats/mesh_gltf.hpp"
#include "airr/formats/mesh_step.hpp"
#include "airr/layout/layout.hpp"

namespace airr {

triangle_mesh load_prop_mesh(const std::string& path, const std::string& node, double tessellation_mm) {
  return is_step_path(path) ? load_step_mesh(path, node, tessellation_mm) : load_gltf_prop_mesh(path, node);
}

std::shared_ptr<const triangle_mesh> cached_prop_mesh(const std::string& path, const std::string& node,
                                                      double tessellation_mm) {
  static file_cache<triangle_mesh> cache;
  // The tolerance is part of a STEP mesh's key only: a glTF mesh is the same at any.
  const std::string key = path + "#" + node + (is_step_path(path) ? "@" + std::to_string(tessellation_mm) : "");
  return cache.get(key, path,
                   [&] { return std::make_shared<const triangle_mesh>(load_prop_mesh(path, node, tessellation_mm)); });
}

std::shared_ptr<const triangle_mesh> prop_mesh(const scene& s, const prop_params& p) {
  return cached_prop_mesh(resolve_scene_path(s, p.mesh), p.node, p.tessellation_mm);
}

// Models below this library read mesh files through core's hook (a sheet's unit cell).
[[maybe_unused]] static const bool mesh_reader_installed = [] {
  install_mesh_file_reader([](const std::string& path) { return cached_prop_mesh(path, ""); });
  return true;
}();

}  // namespace airr
