#pragma once
// Triangle meshes in glTF 2.0 files: the part geometry of a layout.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace airr {

struct triangle_mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle
};

// Loads every triangle primitive of every mesh in the file, with node transforms applied.
// Throws input_error naming the file and the problem.
triangle_mesh load_gltf_mesh(const std::string& path);

// Writes one mesh as a self-contained .gltf (buffer embedded as a data URI), atomically.
void save_gltf_mesh(const triangle_mesh& mesh, const std::string& path);

// The unit panel every flat part is made of: [-0.5, 0.5]^2 in the xy plane, normal +z.
triangle_mesh make_unit_panel();

}  // namespace airr
