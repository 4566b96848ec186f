#include "airr/optics/mesh_gltf.hpp"

#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "airr/optics/error.hpp"
#include "airr/optics/scene_json.hpp"

namespace airr {

namespace {

glm::dmat4 node_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3)
    m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    m = m * glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  }
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

// Reads accessor element i as a double vector of `count` components.
template <class T>
const T* accessor_data(const tinygltf::Model& model, const tinygltf::Accessor& acc, std::size_t i,
                       std::size_t elem_size, const std::string& path) {
  if (acc.bufferView < 0 || acc.bufferView >= int(model.bufferViews.size())) {
    throw input_error(path + ": accessor without a valid buffer view");
  }
  const auto& view = model.bufferViews[acc.bufferView];
  if (view.buffer < 0 || view.buffer >= int(model.buffers.size()))
    throw input_error(path + ": buffer view without a buffer");
  const auto& buf = model.buffers[view.buffer];
  const std::size_t stride = view.byteStride ? view.byteStride : elem_size;
  const std::size_t offset = view.byteOffset + acc.byteOffset + i * stride;
  if (offset + elem_size > buf.data.size() || acc.byteOffset + i * stride + elem_size > view.byteLength) {
    throw input_error(path + ": accessor reads past the end of its buffer");
  }
  return reinterpret_cast<const T*>(buf.data.data() + offset);
}

void append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const glm::dmat4& xf,
                      triangle_mesh& out, const std::string& path) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) return;
  const auto it = prim.attributes.find("POSITION");
  if (it == prim.attributes.end()) throw input_error(path + ": primitive without POSITION");
  const auto& pacc = model.accessors.at(it->second);
  if (pacc.type != TINYGLTF_TYPE_VEC3 || pacc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
    throw input_error(path + ": POSITION must be float VEC3");
  }
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  for (std::size_t i = 0; i < pacc.count; ++i) {
    const float* p = accessor_data<float>(model, pacc, i, 12, path);
    const glm::dvec4 w = xf * glm::dvec4(p[0], p[1], p[2], 1.0);
    if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
      throw input_error(path + ": non-finite vertex");
    out.positions.emplace_back(w);
  }
  if (prim.indices < 0) {
    for (std::size_t i = 0; i + 2 < pacc.count; i += 3) {
      for (int k = 0; k < 3; ++k) out.indices.push_back(base + std::uint32_t(i + k));
    }
    return;
  }
  const auto& iacc = model.accessors.at(prim.indices);
  for (std::size_t i = 0; i < iacc.count; ++i) {
    std::uint32_t idx = 0;
    switch (iacc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        idx = *accessor_data<std::uint8_t>(model, iacc, i, 1, path);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        idx = *accessor_data<std::uint16_t>(model, iacc, i, 2, path);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        idx = *accessor_data<std::uint32_t>(model, iacc, i, 4, path);
        break;
      default:
        throw input_error(path + ": unsupported index type");
    }
    if (idx >= pacc.count) throw input_error(path + ": index out of range");
    out.indices.push_back(base + idx);
  }
  if (out.indices.size() % 3) throw input_error(path + ": index count is not a multiple of 3");
}

void append_node(const tinygltf::Model& model, int node, const glm::dmat4& parent, triangle_mesh& out,
                 const std::string& path, int depth) {
  if (node < 0 || node >= int(model.nodes.size()) || depth > 64) throw input_error(path + ": invalid node hierarchy");
  const auto& n = model.nodes[node];
  const glm::dmat4 xf = parent * node_matrix(n);
  if (n.mesh >= 0) {
    if (n.mesh >= int(model.meshes.size())) throw input_error(path + ": node refers to a missing mesh");
    for (const auto& prim : model.meshes[n.mesh].primitives) append_primitive(model, prim, xf, out, path);
  }
  for (int c : n.children) append_node(model, c, xf, out, path, depth + 1);
}

}  // namespace

triangle_mesh load_gltf_mesh(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw input_error(path + ": file not found");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool binary = std::filesystem::path(path).extension() == ".glb";
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {
    throw input_error(path + ": malformed glTF: " + e.what());
  }
  if (!ok) {
    for (auto& c : err) c = (c == '\n') ? ' ' : c;
    throw input_error(path + ": malformed glTF: " + (err.empty() ? "cannot parse" : err));
  }
  triangle_mesh out;
  out.name = std::filesystem::path(path).stem().string();
  try {
    const int sc = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (sc < int(model.scenes.size())) {
      for (int n : model.scenes[sc].nodes) append_node(model, n, glm::dmat4(1.0), out, path, 0);
    } else {
      for (const auto& m : model.meshes) {
        for (const auto& prim : m.primitives) append_primitive(model, prim, glm::dmat4(1.0), out, path);
      }
    }
  } catch (const std::out_of_range&) {
    throw input_error(path + ": reference to a missing accessor");
  }
  if (out.indices.empty()) throw input_error(path + ": no triangles");
  return out;
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
  if (!writer.WriteGltfSceneToStream(&model, ss, true, false)) throw input_error(path + ": cannot encode glTF");
  write_file_atomic(path, ss.str());
}

triangle_mesh make_unit_panel() {
  triangle_mesh m;
  m.name = "panel";
  m.positions = {{-0.5f, -0.5f, 0.f}, {0.5f, -0.5f, 0.f}, {0.5f, 0.5f, 0.f}, {-0.5f, 0.5f, 0.f}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

}  // namespace airr
