#include "airr/formats/mesh_gltf.hpp"

#include <cstring>
#include <filesystem>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_read.hpp"

namespace airr {

triangle_mesh load_gltf_mesh(const std::string& path) {
  const gltf::file f = gltf::read(path);
  triangle_mesh out;
  out.name = std::filesystem::path(path).stem().string();
  for (int root : gltf::scene_roots(f)) gltf::append_subtree(f, root, glm::dmat4(1.0), out);
  if (out.indices.empty()) throw input_error(path + ": no triangles");
  return out;
}

triangle_mesh load_gltf_prop_mesh(const std::string& path, const std::string& node) {
  const gltf::file f = gltf::read(path);
  triangle_mesh out;
  const glm::dmat4 to_mm = glm::scale(glm::dmat4(1.0), glm::dvec3(gltf::mm_per_metre));
  if (node.empty()) {
    out.name = std::filesystem::path(path).stem().string();
    for (int root : gltf::scene_roots(f)) {
      if (!gltf::is_part_role(gltf::node_role(f, root))) gltf::append_subtree(f, root, to_mm, out);
    }
  } else {
    const int k = gltf::find_node(f, node);
    out.name = f.model.nodes[std::size_t(k)].name;
    // The node's world transform less its rigid part (the prop's pose).
    prop_params rigid;
    rigid.pose = gltf::node_rigid_pose(f, k);
    const glm::dmat4 inv_rigid = glm::inverse(prop_transform(rigid));
    gltf::append_subtree(f, k, inv_rigid * to_mm, out);
  }
  if (out.indices.empty()) {
    throw input_error(path + (node.empty() ? std::string() : ": node " + node) + ": no triangles");
  }
  return out;
}

pose gltf_node_rigid_pose(const std::string& path, const std::string& node) {
  const gltf::file f = gltf::read(path);
  return gltf::node_rigid_pose(f, gltf::find_node(f, node));
}

surface_response prop_surface_of(const prop_params& p, const triangle_mesh& mesh, std::uint32_t triangle) {
  const glm::vec3 albedo(p.albedo[0], p.albedo[1], p.albedo[2]);
  switch (p.surface) {
    case prop_surface::absorber:
      return {};
    case prop_surface::diffuse:
    case prop_surface::mirror:
      return {p.surface, albedo};
    case prop_surface::material:
      break;
  }
  const mesh_material m =
      triangle < mesh.triangle_materials.size() && mesh.triangle_materials[triangle] < mesh.materials.size()
          ? mesh.materials[mesh.triangle_materials[triangle]]
          : mesh_material{};
  const bool mirror = m.metallic >= 0.5f && m.roughness <= 0.3f;
  return {mirror ? prop_surface::mirror : prop_surface::diffuse, m.base_color};
}

void save_gltf_mesh(const triangle_mesh& mesh, const std::string& path) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "airr make-assets";
  tinygltf::Buffer buffer;
  const std::size_t pos_bytes = mesh.positions.size() * sizeof(glm::vec3);
  const std::size_t idx_bytes = mesh.indices.size() * sizeof(std::uint32_t);
  buffer.data.resize(pos_bytes + idx_bytes);
  std::memcpy(buffer.data.data(), mesh.positions.data(), pos_bytes);
  std::memcpy(buffer.data.data() + pos_bytes, mesh.indices.data(), idx_bytes);
  model.buffers.push_back(buffer);

  tinygltf::BufferView pv;
  pv.buffer = 0;
  pv.byteOffset = 0;
  pv.byteLength = pos_bytes;
  pv.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  tinygltf::BufferView iv;
  iv.buffer = 0;
  iv.byteOffset = pos_bytes;
  iv.byteLength = idx_bytes;
  iv.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  model.bufferViews = {pv, iv};

  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  tinygltf::Accessor pa;
  pa.bufferView = 0;
  pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pa.type = TINYGLTF_TYPE_VEC3;
  pa.count = mesh.positions.size();
  pa.minValues = {lo.x, lo.y, lo.z};
  pa.maxValues = {hi.x, hi.y, hi.z};
  tinygltf::Accessor ia;
  ia.bufferView = 1;
  ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  ia.type = TINYGLTF_TYPE_SCALAR;
  ia.count = mesh.indices.size();
  model.accessors = {pa, ia};

  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh m;
  m.name = mesh.name;
  m.primitives.push_back(prim);
  model.meshes.push_back(m);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = mesh.name;
  model.nodes.push_back(node);
  tinygltf::Scene sc;
  sc.nodes = {0};
  model.scenes.push_back(sc);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream ss;
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  if (!writer.WriteGltfSceneToStream(&model, ss, !binary, binary)) throw input_error(path + ": cannot encode glTF");
  write_file_atomic(path, ss.str());
}

}  // namespace airr
