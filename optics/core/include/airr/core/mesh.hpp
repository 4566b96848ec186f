#pragma once
// Triangle meshes: the geometry of parts and props, whatever file they come from.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace airr {

// A glTF material as far as the tracer uses it (glTF's defaults: white, metallic 1, roughness 1).
// base_color is linear: baseColorFactor times its base-colour texture's mean (mesh_gltf.hpp).
struct mesh_material {
  std::string name;
  glm::vec3 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;

  bool operator==(const mesh_material&) const = default;
};

struct triangle_mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from the front
  // The materials of the file's primitives, and each triangle's index into them (both empty for
  // meshes that do not come from a glTF file's materials).
  std::vector<mesh_material> materials;
  std::vector<std::uint32_t> triangle_materials;
};

// The unit panel every flat part is made of: [-0.5, 0.5]^2 in the xy plane, normal +z.
triangle_mesh make_unit_panel();

// Corner points of the mesh's axis-aligned bounds (for drawing a prop's outline); empty mesh: none.
struct mesh_bounds {
  glm::vec3 lo{0.0f}, hi{0.0f};
};
mesh_bounds bounds_of(const triangle_mesh& mesh);

// Mesh files are read by the formats library (mesh_gltf.hpp), which lies above the models that
// may need one (a sheet's unit cell); it installs its reader here. The reader gives the file's
// whole default scene in millimetres and throws input_error naming the file.
using mesh_file_reader = std::function<std::shared_ptr<const triangle_mesh>(const std::string& path)>;
void install_mesh_file_reader(mesh_file_reader reader);
// Throws input_error when no reader is installed.
std::shared_ptr<const triangle_mesh> read_mesh_file(const std::string& path);

}  // namespace airr
