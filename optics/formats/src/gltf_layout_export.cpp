#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include <glm/gtc/quaternion.hpp>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/prop_mesh.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_images.hpp"

namespace airr {

using nlohmann::json;

namespace {

constexpr double metres_per_mm = 1e-3;

std::string base64(const std::string& in) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const auto byte = [&](std::size_t k) {
      return k < in.size() ? std::uint32_t(static_cast<unsigned char>(in[k])) : 0u;
    };
    const std::uint32_t n = (byte(i) << 16) | (byte(i + 1) << 8) | byte(i + 2);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < in.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? table[n & 63] : '=';
  }
  return out;
}

// The document and its one binary buffer, filled as parts are added.
struct writer {
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "AIRR Studio"}}},
              {"scene", 0},
              {"scenes", json::array()},
              {"nodes", json::array()},
              {"meshes", json::array()},
              {"materials", json::array()},
              {"accessors", json::array()},
              {"bufferViews", json::array()}};
  std::string bin;
  std::set<std::string> names;

  // A buffer view; target 0: none (an image's).
  int view(const void* data, std::size_t bytes, int target) {
    while (bin.size() % 4) bin.push_back('\0');
    const std::size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), bytes);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size() - 1);
  }
  int positions(const std::vector<glm::vec3>& p) {
    glm::vec3 lo(p.front()), hi(p.front());
    for (const auto& v : p) lo = glm::min(lo, v), hi = glm::max(hi, v);
    doc["accessors"].push_back({{"bufferView", view(p.data(), p.size() * sizeof(glm::vec3), 34962)},
                                {"componentType", 5126},
                                {"count", p.size()},
                                {"type", "VEC3"},
                                {"min", {lo.x, lo.y, lo.z}},
                                {"max", {hi.x, hi.y, hi.z}}});
    return int(doc["accessors"].size() - 1);
  }
  int texcoords(const std::vector<glm::vec2>& uv) {
    doc["accessors"].push_back({{"bufferView", view(uv.data(), uv.size() * sizeof(glm::vec2), 34962)},
                                {"componentType", 5126},
                                {"count", uv.size()},
                                {"type", "VEC2"}});
    return int(doc["accessors"].size() - 1);
  }
  // An image as a texture (bilinear, clamped at the edges, as the tracer samples the display): in
  // the binary buffer for a GLB, else as a data URI.
  int texture(const gltf::embedded_image& img, const std::string& name, bool binary) {
    json image = {{"name", name}};
    if (binary) {
      image["bufferView"] = view(img.bytes.data(), img.bytes.size(), 0);
      image["mimeType"] = img.mime_type;
    } else {
      image["uri"] = "data:" + img.mime_type + ";base64," + base64(img.bytes);
    }
    doc["images"].push_back(image);
    doc["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9729}, {"wrapS", 33071}, {"wrapT", 33071}}};
    doc["textures"].push_back({{"sampler", 0}, {"source", doc["images"].size() - 1}});
    return int(doc["textures"].size() - 1);
  }
  int indices(const std::vector<std::uint32_t>& idx) {
    doc["accessors"].push_back({{"bufferView", view(idx.data(), idx.size() * 4, 34963)},
                                {"componentType", 5125},
                                {"count", idx.size()},
                                {"type", "SCALAR"}});
    return int(doc["accessors"].size() - 1);
  }
  int material(const json& m) {
    doc["materials"].push_back(m);
    return int(doc["materials"].size() - 1);
  }
  // Names are unique, so that a prop's node can be found by name again.
  std::string unique(std::string name) {
    if (name.empty() || name[0] == '#') name = "node " + name;
    std::string out = name;
    for (int k = 2; names.count(out); ++k) out = name + " (" + std::to_string(k) + ")";
    names.insert(out);
    return out;
  }
  int node(json n) {
    doc["nodes"].push_back(std::move(n));
    return int(doc["nodes"].size() - 1);
  }
};

json pbr(const glm::dvec3& base, double metallic, double roughness, double alpha = 1) {
  return {{"baseColorFactor", {base.x, base.y, base.z, alpha}},
          {"metallicFactor", metallic},
          {"roughnessFactor", roughness}};
}

// A node's translation and rotation for a pose, in metres.
void place(json& n, const pose& p) {
  const glm::dquat q = glm::normalize(glm::quat_cast(pose_rotation(p)));
  n["translation"] = {p.center_mm[0] * metres_per_mm, p.center_mm[1] * metres_per_mm, p.center_mm[2] * metres_per_mm};
  n["rotation"] = {q.x, q.y, q.z, q.w};
}

// A flat part: its rectangle in its own xy plane (front +z), in metres.
int rectangle_mesh(writer& w, double width_mm, double height_mm, int material) {
  const float x = float(0.5 * width_mm * metres_per_mm), y = float(0.5 * height_mm * metres_per_mm);
  const std::vector<glm::vec3> p = {{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}};
  const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  w.doc["meshes"].push_back(
      {{"primitives",
        {{{"attributes", {{"POSITION", w.positions(p)}}}, {"indices", w.indices(idx)}, {"material", material}}}}});
  return int(w.doc["meshes"].size() - 1);
}

// The display's whole panel in its own xy plane (front +z), in metres: the emitting area (its image
// as texture -1: none; texel row 0 at the top, +y) and, with a bezel, the black frame around it,
// each a primitive of its own, so that the mesh's extent is the panel and the image covers only
// the emitting area.
int display_mesh(writer& w, const source_params& src, int texture) {
  const float x = float(0.5 * src.width_mm * metres_per_mm), y = float(0.5 * src.height_mm * metres_per_mm);
  const float bx = float(0.5 * (src.width_mm + 2 * src.bezel_mm) * metres_per_mm);
  const float by = float(0.5 * (src.height_mm + 2 * src.bezel_mm) * metres_per_mm);
  json glow = {{"name", "display"},
               {"pbrMetallicRoughness", pbr(glm::dvec3(0.05), 0, 0.5)},
               {"emissiveFactor", {1.0, 1.0, 1.0}}};
  json area = {{"attributes", {{"POSITION", w.positions({{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}})}}},
               {"indices", w.indices({0, 1, 2, 0, 2, 3})}};
  if (texture >= 0) {
    glow["pbrMetallicRoughness"] = pbr(glm::dvec3(1), 0, 0.5);
    glow["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture}};
    glow["emissiveTexture"] = {{"index", texture}};
    area["attributes"]["TEXCOORD_0"] = w.texcoords({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  }
  area["material"] = w.material(glow);
  json prims = json::array({area});
  if (src.bezel_mm > 0) {
    const std::vector<glm::vec3> p = {{-bx, -by, 0}, {bx, -by, 0}, {bx, by, 0}, {-bx, by, 0},
                                      {-x, -y, 0},   {x, -y, 0},   {x, y, 0},   {-x, y, 0}};
    // Four trapezoids between the outer corners 0-3 and the inner ones 4-7.
    std::vector<std::uint32_t> idx;
    for (std::uint32_t k = 0; k < 4; ++k) {
      const std::uint32_t a = k, b = (k + 1) % 4, c = 4 + (k + 1) % 4, d = 4 + k;
      idx.insert(idx.end(), {a, b, c, a, c, d});
    }
    prims.push_back(
        {{"attributes", {{"POSITION", w.positions(p)}}},
         {"indices", w.indices(idx)},
         {"material", w.material({{"name", "bezel"}, {"pbrMetallicRoughness", pbr(glm::dvec3(0.02), 0, 0.5)}})}});
  }
  w.doc["meshes"].push_back({{"name", "Display"}, {"primitives", prims}});
  return int(w.doc["meshes"].size() - 1);
}

// The display's image as a texture (-1 for a uniform display).
int display_texture(writer& w, const scene& s, bool binary) {
  if (s.source.image.empty()) return -1;
  const std::string path = resolve_scene_path(s, s.source.image);
  return w.texture(gltf::image_to_embed(path), std::filesystem::path(path).filename().string(), binary);
}

// A prop's triangles in metres, one primitive per material.
int prop_mesh(writer& w, const triangle_mesh& m, const prop_params& p) {
  std::vector<glm::vec3> pos(m.positions.size());
  for (std::size_t i = 0; i < pos.size(); ++i) pos[i] = m.positions[i] * float(metres_per_mm);
  const int position_accessor = w.positions(pos);
  const glm::dvec3 albedo(p.albedo[0], p.albedo[1], p.albedo[2]);
  json prims = json::array();
  const bool by_material = p.surface == prop_surface::material && !m.materials.empty();
  const std::size_t groups = by_material ? m.materials.size() : 1;
  for (std::size_t g = 0; g < groups; ++g) {
    std::vector<std::uint32_t> idx;
    for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
      if (by_material && (t >= m.triangle_materials.size() ? 0 : m.triangle_materials[t]) != g) continue;
      idx.insert(idx.end(), {m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]});
    }
    if (idx.empty()) continue;
    json mat;
    if (by_material) {
      const mesh_material& mm = m.materials[g];
      mat = {{"name", mm.name.empty() ? "material " + std::to_string(g) : mm.name},
             {"pbrMetallicRoughness", pbr(glm::dvec3(mm.base_color), mm.metallic, mm.roughness)}};
    } else if (p.surface == prop_surface::material) {
      mat = {{"name", "default"}, {"pbrMetallicRoughness", pbr(glm::dvec3(1), 1, 1)}};  // glTF's default
    } else if (p.surface == prop_surface::mirror) {
      mat = {{"name", "mirror"}, {"pbrMetallicRoughness", pbr(albedo, 1, 0)}};
    } else if (p.surface == prop_surface::diffuse) {
      mat = {{"name", "diffuse"}, {"pbrMetallicRoughness", pbr(albedo, 0, 1)}};
    } else {
      mat = {{"name", "absorber"}, {"pbrMetallicRoughness", pbr(glm::dvec3(0.02), 0, 1)}};
    }
    prims.push_back({{"attributes", {{"POSITION", position_accessor}}},
                     {"indices", w.indices(idx)},
                     {"material", w.material(mat)}});
  }
  w.doc["meshes"].push_back({{"name", p.name}, {"primitives", prims}});
  return int(w.doc["meshes"].size() - 1);
}

std::string glb(const json& doc, std::string bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text.push_back(' ');
  while (bin.size() % 4) bin.push_back('\0');
  std::string out;
  auto u32 = [&](std::uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);
    out.append(b, 4);
  };
  u32(0x46546C67u);  // "glTF"
  u32(2);
  u32(std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(std::uint32_t(text.size()));
  u32(0x4E4F534Au);  // "JSON"
  out += text;
  u32(std::uint32_t(bin.size()));
  u32(0x004E4942u);  // "BIN\0"
  out += bin;
  return out;
}

}  // namespace

void export_gltf_layout(const scene& original, const std::string& path) {
  if (!is_gltf_path(path)) throw input_error(path + ": a glTF layout is written as .glb or .gltf");
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool binary = ext == ".glb" || ext == ".GLB";
  // Paths in extras count from the new file's folder.
  const scene s = rebase_scene_paths(original, dir);
  const json form = scene_to_json(s);
  writer w;
  json roots = json::array();

  // The display: its whole panel (the bezel included), glowing with its image.
  json src = form["source"];
  json display = {{"name", w.unique("Display")}, {"mesh", display_mesh(w, s.source, display_texture(w, s, binary))}};
  place(display, s.source.pose);
  for (const char* key : {"width_mm", "height_mm", "pose", "mesh"}) src.erase(key);
  src["role"] = "display";
  display["extras"] = {{"airr", src}};
  roots.push_back(w.node(display));

  json hm_fields = form["half_mirror"];
  for (const char* key : {"width_mm", "height_mm", "pose", "mesh"}) hm_fields.erase(key);
  hm_fields["role"] = "half_mirror";
  const int hm_mat = w.material({{"name", "half mirror"},
                                 {"pbrMetallicRoughness", pbr(glm::dvec3(0.9), 1, 0.05, 0.5)},
                                 {"alphaMode", "BLEND"},
                                 {"doubleSided", true}});
  json hm = {{"name", w.unique("Half mirror")},
             {"mesh", rectangle_mesh(w, s.half_mirror.width_mm, s.half_mirror.height_mm, hm_mat)},
             {"extras", {{"airr", hm_fields}}}};
  place(hm, s.half_mirror.pose);
  roots.push_back(w.node(hm));

  const int sheet_mat =
      w.material({{"name", "retroreflector"}, {"pbrMetallicRoughness", pbr(glm::dvec3(0.6), 0, 0.4)}});
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    json fields = form["retroreflectors"][i];
    for (const char* key : {"width_mm", "height_mm", "pose", "mesh"}) fields.erase(key);
    fields["role"] = "retroreflector";
    const auto& r = s.retroreflectors[i];
    json n = {{"name", w.unique("Retroreflector " + std::to_string(i + 1))},
              {"mesh", rectangle_mesh(w, r.width_mm, r.height_mm, sheet_mat)},
              {"extras", {{"airr", fields}}}};
    place(n, r.pose);
    roots.push_back(w.node(n));
  }

  for (std::size_t i = 0; i < s.props.size(); ++i) {
    const prop_params& p = s.props[i];
    const auto mesh = prop_mesh(s, p);
    json fields = {{"role", "prop"},
                   {"name", p.name},
                   {"surface", prop_surface_names[int(p.surface)]},
                   {"albedo", p.albedo},
                   {"visible", p.visible}};
    json n = {{"name", w.unique(p.name.empty() ? "Prop " + std::to_string(i + 1) : p.name)},
              {"mesh", prop_mesh(w, *mesh, p)},
              {"extras", {{"airr", fields}}}};
    place(n, p.pose);
    if (p.scale != 1) n["scale"] = {p.scale, p.scale, p.scale};
    roots.push_back(w.node(n));
  }

  // The observer as a camera (glTF cameras look along their -z, y up), for viewers.
  const pinhole_camera cam = make_camera(s);
  glm::dmat3 r(cam.right, cam.up, -cam.forward);
  const glm::dquat q = glm::normalize(glm::quat_cast(r));
  w.doc["cameras"] = {{{"type", "perspective"},
                       {"name", "observer"},
                       {"perspective",
                        {{"yfov", radians(s.observer.fov_deg)},
                         {"aspectRatio", double(s.observer.width) / s.observer.height},
                         {"znear", 0.001}}}}};
  roots.push_back(
      w.node({{"name", w.unique("Observer")},
              {"camera", 0},
              {"translation",
               {cam.position.x * metres_per_mm, cam.position.y * metres_per_mm, cam.position.z * metres_per_mm}},
              {"rotation", {q.x, q.y, q.z, q.w}},
              {"extras", {{"airr", {{"role", "observer"}}}}}}));

  w.doc["scenes"].push_back({{"name", "AIRR layout"},
                             {"nodes", roots},
                             {"extras",
                              {{"airr",
                                {{"format", "airr-scene"},
                                 {"version", form["version"]},
                                 {"seed", form["seed"]},
                                 {"observer", form["observer"]},
                                 {"render", form["render"]}}}}}});
  if (w.doc["materials"].empty()) w.doc.erase("materials");
  if (binary) {
    w.doc["buffers"] = {{{"byteLength", w.bin.size()}}};
    write_file_atomic(path, glb(w.doc, w.bin));
  } else {
    w.doc["buffers"] = {
        {{"byteLength", w.bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(w.bin)}}};
    write_file_atomic(path, w.doc.dump(1) + "\n");
  }
}

}  // namespace airr
