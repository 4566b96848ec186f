#include "gltf_read.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "airr/core/error.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_materials.hpp"

namespace airr::gltf {

namespace {

// Images are decoded only when asked for (gltf_images.hpp): keep a data URI's bytes, which
// tinygltf passes here alone (a buffer view's stay in its buffer).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && image->uri.empty() && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

glm::dmat4 local_matrix(const file& f, int node) {
  const tinygltf::Node& n = f.model.nodes[std::size_t(node)];
  auto fail = [&](const std::string& what) { throw input_error(f.path + ": " + node_label(f, node) + ": " + what); };
  glm::dmat4 m(1.0);
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) fail("matrix must have 16 numbers");
    m = glm::make_mat4(n.matrix.data());
  } else {
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) fail("translation must have 3 numbers");
      m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) fail("rotation must have 4 numbers");
      glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      const double len = glm::length(q);
      if (!(len > 0.5) || !std::isfinite(len)) fail("rotation must be a unit quaternion");
      m = m * glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) fail("scale must have 3 numbers");
      m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    }
  }
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) fail("transform has a non-finite number");
    }
  }
  return m;
}

// The accessor's element i as a byte pointer, every offset checked against its view and buffer.
struct accessor_view {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

std::size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

accessor_view view_of(const file& f, int index, std::size_t elem_size, const std::string& what) {
  const auto& m = f.model;
  const std::string label = what + ": accessor " + std::to_string(index);
  auto fail = [&](const std::string& problem) { throw input_error(f.path + ": " + label + ": " + problem); };
  if (index < 0 || std::size_t(index) >= m.accessors.size()) fail("does not exist");
  const tinygltf::Accessor& acc = m.accessors[std::size_t(index)];
  if (acc.sparse.isSparse) fail("sparse accessors are not supported");
  if (acc.bufferView < 0 || std::size_t(acc.bufferView) >= m.bufferViews.size()) fail("has no valid buffer view");
  const tinygltf::BufferView& view = m.bufferViews[std::size_t(acc.bufferView)];
  if (view.buffer < 0 || std::size_t(view.buffer) >= m.buffers.size()) {
    fail("its buffer view " + std::to_string(acc.bufferView) + " has no valid buffer");
  }
  const std::size_t buffer_size = m.buffers[std::size_t(view.buffer)].data.size();
  if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
    fail("buffer view " + std::to_string(acc.bufferView) + " reaches past the end of buffer " +
         std::to_string(view.buffer) + " (" + std::to_string(buffer_size) + " bytes)");
  }
  const std::size_t stride = view.byteStride ? view.byteStride : elem_size;
  if (stride < elem_size) fail("byte stride is smaller than an element");
  if (acc.count == 0) return {nullptr, stride, 0};
  // Overflow-safe: the last element must end inside the view.
  if (acc.byteOffset > view.byteLength || acc.count - 1 > (view.byteLength - acc.byteOffset) / stride ||
      acc.byteOffset + (acc.count - 1) * stride + elem_size > view.byteLength) {
    fail("reads past the end of its buffer view (" + std::to_string(acc.count) + " elements)");
  }
  return {m.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + acc.byteOffset, stride, acc.count};
}

std::uint32_t index_at(const accessor_view& v, int component_type, std::size_t i) {
  const unsigned char* p = v.data + i * v.stride;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t x;
      std::memcpy(&x, p, 2);
      return x;
    }
    default: {
      std::uint32_t x;
      std::memcpy(&x, p, 4);
      return x;
    }
  }
}

}  // namespace

std::string node_label(const file& f, int node) {
  const std::string& name = f.model.nodes[std::size_t(node)].name;
  return "node " + (name.empty() ? std::string() : "'" + name + "' ") + "(#" + std::to_string(node) + ")";
}

// A GLB's JSON chunk (empty when the header is too short to say; tinygltf then refuses the file).
static std::string_view glb_json_chunk(const std::string& bytes) {
  if (bytes.size() < 20) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return std::string_view(bytes).substr(20, length);
}

file read(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw input_error(path + ": file not found");
  if (std::filesystem::file_size(path, ec) > max_gltf_bytes)
    throw input_error(path + ": larger than the limit of " + std::to_string(max_gltf_bytes >> 20) +
                      " MiB for a glTF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path + ": cannot open for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  file f;
  f.path = path;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, nullptr);
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  std::string err, warn;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  check_json_depth(binary ? glb_json_chunk(bytes) : std::string_view(bytes), path);
  bool ok = false;
  try {
    ok = binary
             ? loader.LoadBinaryFromMemory(&f.model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                           unsigned(std::min<std::size_t>(bytes.size(), UINT32_MAX)), dir)
             : loader.LoadASCIIFromString(&f.model, &err, &warn, bytes.data(),
                                          unsigned(std::min<std::size_t>(bytes.size(), UINT32_MAX)), dir);
  } catch (const std::exception& e) {
    throw input_error(path + ": malformed glTF: " + one_line(e.what()));
  }
  if (!ok)
    throw input_error(path + ": malformed " + (binary ? "GLB" : "glTF") + ": " +
                      (err.empty() ? "cannot parse" : one_line(err)));

  // The hierarchy: every child in range, no node with two parents, no cycle.
  const std::size_t n = f.model.nodes.size();
  f.parent.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c : f.model.nodes[i].children) {
      if (c < 0 || std::size_t(c) >= n) {
        throw input_error(path + ": " + node_label(f, int(i)) + ": child " + std::to_string(c) + " does not exist");
      }
      if (std::size_t(c) == i) throw input_error(path + ": " + node_label(f, c) + ": is its own child");
      if (f.parent[std::size_t(c)] != -1) {
        throw input_error(path + ": " + node_label(f, c) + ": has more than one parent");
      }
      f.parent[std::size_t(c)] = int(i);
    }
  }
  f.world.assign(n, glm::dmat4(1.0));
  std::vector<int> state(n, 0);  // 0 unvisited, 1 in progress, 2 done
  for (std::size_t i = 0; i < n; ++i) {
    // Walk up to a finished ancestor, then down again.
    std::vector<int> chain;
    for (int k = int(i); k >= 0 && state[std::size_t(k)] != 2; k = f.parent[std::size_t(k)]) {
      if (state[std::size_t(k)] == 1) throw input_error(path + ": " + node_label(f, k) + ": is its own ancestor");
      state[std::size_t(k)] = 1;
      chain.push_back(k);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int p = f.parent[std::size_t(*it)];
      f.world[std::size_t(*it)] = (p >= 0 ? f.world[std::size_t(p)] : glm::dmat4(1.0)) * local_matrix(f, *it);
      state[std::size_t(*it)] = 2;
    }
  }
  for (const auto& s : f.model.scenes) {
    for (int r : s.nodes) {
      if (r < 0 || std::size_t(r) >= n) throw input_error(path + ": scene refers to missing node " + std::to_string(r));
    }
  }
  return f;
}

int find_node(const file& f, const std::string& ref) {
  const auto& nodes = f.model.nodes;
  if (!ref.empty() && ref[0] == '#') {
    std::size_t used = 0;
    long long i = -1;
    try {
      i = std::stoll(ref.substr(1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used + 1 != ref.size() || i < 0 || std::size_t(i) >= nodes.size()) {
      throw input_error(f.path + ": no node " + ref + " (" + std::to_string(nodes.size()) +
                        " nodes, numbered from #0)");
    }
    return int(i);
  }
  int found = -1;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].name != ref) continue;
    if (found >= 0)
      throw input_error(f.path + ": more than one node is named '" + ref + "'; name it by index, e.g. #" +
                        std::to_string(found));
    found = int(i);
  }
  if (found < 0) throw input_error(f.path + ": no node named '" + ref + "'");
  return found;
}

std::vector<int> scene_roots(const file& f) {
  const auto& m = f.model;
  if (!m.scenes.empty()) {
    const int sc = m.defaultScene >= 0 && std::size_t(m.defaultScene) < m.scenes.size() ? m.defaultScene : 0;
    return m.scenes[std::size_t(sc)].nodes;
  }
  std::vector<int> roots;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    if (f.parent[i] < 0) roots.push_back(int(i));
  }
  return roots;
}

void visit_node_primitives(const file& f, int node, const glm::dmat4& xf, const primitive_visitor& visit) {
  const tinygltf::Node& n = f.model.nodes[std::size_t(node)];
  if (n.mesh < 0) return;
  const std::string where = node_label(f, node);
  if (std::size_t(n.mesh) >= f.model.meshes.size()) {
    throw input_error(f.path + ": " + where + ": mesh " + std::to_string(n.mesh) + " does not exist");
  }
  const bool mirrored = glm::determinant(glm::dmat3(xf)) < 0;
  const auto& prims = f.model.meshes[std::size_t(n.mesh)].primitives;
  for (std::size_t pi = 0; pi < prims.size(); ++pi) {
    const tinygltf::Primitive& prim = prims[pi];
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      continue;  // points and lines have no area
    }
    const std::string what = where + ": mesh " + std::to_string(n.mesh) + " primitive " + std::to_string(pi);
    const auto it = prim.attributes.find("POSITION");
    if (it == prim.attributes.end()) throw input_error(f.path + ": " + what + ": has no POSITION");
    if (it->second < 0 || std::size_t(it->second) >= f.model.accessors.size()) {
      throw input_error(f.path + ": " + what + ": POSITION accessor " + std::to_string(it->second) + " does not exist");
    }
    const tinygltf::Accessor& pacc = f.model.accessors[std::size_t(it->second)];
    if (pacc.type != TINYGLTF_TYPE_VEC3 || pacc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      throw input_error(f.path + ": " + what + ": accessor " + std::to_string(it->second) +
                        ": POSITION must be float VEC3");
    }
    const accessor_view pv = view_of(f, it->second, 12, what + " POSITION");
    if (pv.count > 3 * max_triangles)
      throw input_error(f.path + ": " + what + ": too many vertices (" + std::to_string(pv.count) + ")");
    std::vector<glm::dvec3> positions;
    positions.reserve(pv.count);
    for (std::size_t i = 0; i < pv.count; ++i) {
      float p[3];
      std::memcpy(p, pv.data + i * pv.stride, 12);
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        throw input_error(f.path + ": " + what + ": accessor " + std::to_string(it->second) + ": vertex " +
                          std::to_string(i) + " is not finite");
      }
      const glm::dvec4 w = xf * glm::dvec4(p[0], p[1], p[2], 1.0);
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) || std::abs(w.x) > 1e9 ||
          std::abs(w.y) > 1e9 || std::abs(w.z) > 1e9) {
        throw input_error(f.path + ": " + what + ": vertex " + std::to_string(i) +
                          " lies out of range after the node transforms");
      }
      positions.emplace_back(w);
    }
    // The primitive's vertex sequence: its indices, or 0, 1, 2, ...
    std::vector<std::uint32_t> seq;
    if (prim.indices >= 0) {
      if (std::size_t(prim.indices) >= f.model.accessors.size()) {
        throw input_error(f.path + ": " + what + ": index accessor " + std::to_string(prim.indices) +
                          " does not exist");
      }
      const tinygltf::Accessor& iacc = f.model.accessors[std::size_t(prim.indices)];
      const int ct = iacc.componentType;
      if (iacc.type != TINYGLTF_TYPE_SCALAR ||
          (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
           ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
        throw input_error(f.path + ": " + what + ": accessor " + std::to_string(prim.indices) +
                          ": indices must be unsigned byte, short or int scalars");
      }
      const accessor_view iv = view_of(f, prim.indices, component_size(ct), what + " indices");
      if (iv.count > 3 * max_triangles)
        throw input_error(f.path + ": " + what + ": too many indices (" + std::to_string(iv.count) + ")");
      seq.resize(iv.count);
      for (std::size_t i = 0; i < iv.count; ++i) {
        seq[i] = index_at(iv, ct, i);
        if (seq[i] >= pv.count) {
          throw input_error(f.path + ": " + what + ": accessor " + std::to_string(prim.indices) + ": index " +
                            std::to_string(i) + " is " + std::to_string(seq[i]) + ", out of range (" +
                            std::to_string(pv.count) + " vertices)");
        }
      }
    } else {
      seq.resize(pv.count);
      for (std::size_t i = 0; i < pv.count; ++i) seq[i] = std::uint32_t(i);
    }
    std::vector<std::uint32_t> triangles;
    auto triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (a == b || b == c || a == c) return;  // degenerate, no area
      if (mirrored) std::swap(b, c);
      triangles.insert(triangles.end(), {a, b, c});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (seq.size() % 3) throw input_error(f.path + ": " + what + ": vertex count is not a multiple of 3");
      for (std::size_t i = 0; i + 2 < seq.size(); i += 3) triangle(seq[i], seq[i + 1], seq[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < seq.size(); ++i) {
        if (i % 2 == 0)
          triangle(seq[i], seq[i + 1], seq[i + 2]);
        else
          triangle(seq[i + 1], seq[i], seq[i + 2]);
      }
    } else {
      for (std::size_t i = 1; i + 1 < seq.size(); ++i) triangle(seq[0], seq[i], seq[i + 1]);
    }
    visit(positions, triangles, prim.material);
  }
}

void append_node_triangles(const file& f, int node, const glm::dmat4& xf, triangle_mesh& out) {
  visit_node_primitives(
      f, node, xf,
      [&](const std::vector<glm::dvec3>& positions, const std::vector<std::uint32_t>& triangles, int material) {
        const std::size_t base = out.positions.size();
        if (base + positions.size() > std::size_t(UINT32_MAX)) throw input_error(f.path + ": more than 2^32 vertices");
        if ((out.indices.size() + triangles.size()) / 3 > max_triangles) {
          throw input_error(f.path + ": more than " + std::to_string(max_triangles) + " triangles");
        }
        out.positions.reserve(base + positions.size());
        for (const auto& p : positions) out.positions.emplace_back(p);
        const std::uint32_t mat = material_slot(f, material, node_label(f, node), out);
        for (std::uint32_t i : triangles) out.indices.push_back(std::uint32_t(base) + i);
        out.triangle_materials.insert(out.triangle_materials.end(), triangles.size() / 3, mat);
      });
}

void append_subtree(const file& f, int node, const glm::dmat4& xf, triangle_mesh& out) {
  std::vector<int> stack{node};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    append_node_triangles(f, k, xf * f.world[std::size_t(k)], out);
    for (int c : f.model.nodes[std::size_t(k)].children) {
      if (!is_part_role(node_role(f, c))) stack.push_back(c);
    }
  }
}

nlohmann::json airr_in_extras(const std::string& extras_json, const std::string& what) {
  if (extras_json.empty()) return nullptr;
  const nlohmann::json extras = parse_json(extras_json, what);
  if (!extras.is_object() || !extras.contains("airr")) return nullptr;
  nlohmann::json a = extras["airr"];
  if (a.is_string()) a = parse_json(a.get<std::string>(), what + " airr (a JSON string)");
  if (!a.is_object()) throw input_error(what + " airr must be a JSON object (or a string holding one)");
  return a;
}

static std::string mesh_label(const file& f, int mesh) {
  const std::string& name = f.model.meshes[std::size_t(mesh)].name;
  return "mesh " + (name.empty() ? std::string() : "'" + name + "' ") + "(#" + std::to_string(mesh) + ")";
}

nlohmann::json node_airr_extras(const file& f, int node) {
  return airr_in_extras(f.model.nodes[std::size_t(node)].extras_json_string,
                        f.path + ": " + node_label(f, node) + ": extras");
}

nlohmann::json mesh_airr_extras(const file& f, int node) {
  const int mesh = f.model.nodes[std::size_t(node)].mesh;
  if (mesh < 0 || std::size_t(mesh) >= f.model.meshes.size()) return nullptr;
  return airr_in_extras(f.model.meshes[std::size_t(mesh)].extras_json_string,
                        f.path + ": " + node_label(f, node) + ": " + mesh_label(f, mesh) + ": extras");
}

nlohmann::json airr_extras(const file& f, int node) {
  nlohmann::json a = node_airr_extras(f, node);
  return a.is_null() ? mesh_airr_extras(f, node) : a;
}

std::string airr_extras_name(const file& f, int node) {
  if (!node_airr_extras(f, node).is_null() || mesh_airr_extras(f, node).is_null()) return "extras airr";
  return mesh_label(f, f.model.nodes[std::size_t(node)].mesh) + ": extras airr";
}

bool is_part_role(const std::string& role) {
  return role == "display" || role == "half_mirror" || role == "retroreflector" || role == "observer";
}

std::string node_role(const file& f, int node) {
  const nlohmann::json a = airr_extras(f, node);
  if (a.is_object() && a.contains("role")) {
    const nlohmann::json& r = a["role"];
    if (!r.is_string() || !(is_part_role(r.get<std::string>()) || r.get<std::string>() == "prop")) {
      throw input_error(f.path + ": " + node_label(f, node) + ": " + airr_extras_name(f, node) +
                        ".role must be display, half_mirror, retroreflector, observer or prop");
    }
    return r.get<std::string>();
  }
  std::string name = f.model.nodes[std::size_t(node)].name;
  for (auto& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  for (const char* role : {"display", "half_mirror", "retroreflector", "observer"}) {
    if (name.rfind(std::string("airr_") + role, 0) == 0) return role;
  }
  return "";
}

glm::dmat4 world_mm(const file& f, int node) {
  return glm::dmat4(glm::dmat3(mm_per_metre)) * f.world[std::size_t(node)];
}

pose node_rigid_pose(const file& f, int node) {
  const rigid r = rigid_part(world_mm(f, node), f.path + ": " + node_label(f, node));
  return pose_from_rotation(r.rotation, r.translation);
}

rigid rigid_part(const glm::dmat4& m, const std::string& what) {
  const glm::dvec3 x(m[0]), y(m[1]);
  const double lx = glm::length(x);
  if (!(lx > 1e-12)) throw input_error(what + ": degenerate transform (its x axis has no length)");
  const glm::dvec3 ux = x / lx;
  const glm::dvec3 y_perp = y - glm::dot(y, ux) * ux;
  const double ly = glm::length(y_perp);
  if (!(ly > 1e-12 * std::max(1.0, glm::length(y))))
    throw input_error(what + ": degenerate transform (its y axis is parallel to x)");
  const glm::dvec3 uy = y_perp / ly;
  rigid r;
  r.rotation = glm::dmat3(ux, uy, glm::cross(ux, uy));
  r.translation = glm::dvec3(m[3]);
  return r;
}

}  // namespace airr::gltf
