#pragma once
// The meshes of props, from whichever file a prop names: glTF (mesh_gltf.hpp) or STEP
// (mesh_step.hpp).
#include <memory>
#include <string>

#include "airr/core/mesh.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

// A prop's mesh in millimetres: load_gltf_prop_mesh for glTF and GLB files, load_step_mesh at
// `tessellation_mm` for STEP files (by the path's extension). Throws input_error naming the file.
triangle_mesh load_prop_mesh(const std::string& path, const std::string& node,
                             double tessellation_mm = prop_params{}.tessellation_mm);

// load_prop_mesh, cached by path, node, tessellation, modification time and size (a large housing
// is read once however many analyses and views ask for it).
std::shared_ptr<const triangle_mesh> cached_prop_mesh(const std::string& path, const std::string& node,
                                                      double tessellation_mm = prop_params{}.tessellation_mm);

// The mesh of a scene's prop: its file resolved beside the scene, read (or found in the cache) with
// the prop's node and tessellation.
std::shared_ptr<const triangle_mesh> prop_mesh(const scene& s, const prop_params& p);

}  // namespace airr
