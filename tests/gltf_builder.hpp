#pragma once
// Builds glTF files for tests, written independently of the product's reader and writer: nodes
// with matrices or TRS, meshes with any index type, materials, extras, and the three ways to store
// a buffer (data URI, external .bin, GLB).
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace airr::test {

class gltf_builder {
 public:
  enum class storage { data_uri, external_bin, glb };

  nlohmann::json doc = {{"asset", {{"version", "2.0"}, {"generator", "airr tests"}}},
                        {"scenes", nlohmann::json::array({nlohmann::json{{"nodes", nlohmann::json::array()}}})},
                        {"scene", 0},
                        {"nodes", nlohmann::json::array()},
                        {"meshes", nlohmann::json::array()},
                        {"accessors", nlohmann::json::array()},
                        {"bufferViews", nlohmann::json::array()}};
  std::vector<unsigned char> bin;

  // Appends bytes as a buffer view (aligned to 4) and returns its index.
  int add_view(const void* data, std::size_t bytes) {
    while (bin.size() % 4) bin.push_back(0);
    const std::size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    return int(doc["bufferViews"].size() - 1);
  }
  int add_accessor(int view, int component_type, std::size_t count, const char* type) {
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
    return int(doc["accessors"].size() - 1);
  }
  int add_positions(const std::vector<float>& xyz) {
    const int a = add_accessor(add_view(xyz.data(), xyz.size() * 4), 5126, xyz.size() / 3, "VEC3");
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
    doc["accessors"][std::size_t(a)]["min"] = {lo[0], lo[1], lo[2]};
    doc["accessors"][std::size_t(a)]["max"] = {hi[0], hi[1], hi[2]};
    return a;
  }
  // component_type 5121 (u8), 5123 (u16) or 5125 (u32).
  int add_indices(const std::vector<std::uint32_t>& idx, int component_type) {
    std::vector<unsigned char> bytes;
    const std::size_t size = component_type == 5121 ? 1 : component_type == 5123 ? 2 : 4;
    for (std::uint32_t i : idx) {
      for (std::size_t b = 0; b < size; ++b) bytes.push_back((unsigned char)(i >> (8 * b)));
    }
    return add_accessor(add_view(bytes.data(), bytes.size()), component_type, idx.size(), "SCALAR");
  }
  int add_material(const std::string& name, const std::array<double, 4>& base, double metallic, double roughness) {
    doc["materials"].push_back(
        {{"name", name},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", base}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}});
    return int(doc["materials"].size() - 1);
  }
  // A mesh of one primitive per (positions, indices, material) triple; indices -1: none.
  int add_mesh(const std::vector<std::array<int, 3>>& primitives) {
    nlohmann::json prims = nlohmann::json::array();
    for (const auto& [pos, idx, mat] : primitives) {
      nlohmann::json p = {{"attributes", {{"POSITION", pos}}}};
      if (idx >= 0) p["indices"] = idx;
      if (mat >= 0) p["material"] = mat;
      prims.push_back(p);
    }
    doc["meshes"].push_back({{"primitives", prims}});
    return int(doc["meshes"].size() - 1);
  }
  // A node; `parent` -1 makes it a root of the scene.
  int add_node(const nlohmann::json& node, int parent = -1) {
    doc["nodes"].push_back(node);
    const int k = int(doc["nodes"].size() - 1);
    if (parent < 0) {
      doc["scenes"][0]["nodes"].push_back(k);
    } else {
      doc["nodes"][std::size_t(parent)]["children"].push_back(k);
    }
    return k;
  }

  void write(const std::string& path, storage how) const {
    nlohmann::json d = doc;
    if (d["meshes"].empty()) d.erase("meshes");
    if (d["accessors"].empty()) d.erase("accessors");
    if (d["bufferViews"].empty()) d.erase("bufferViews");
    std::ofstream out(path, std::ios::binary);
    if (how == storage::glb) {
      d["buffers"] = {{{"byteLength", bin.size()}}};
      std::string json = d.dump();
      while (json.size() % 4) json += ' ';
      std::vector<unsigned char> b = bin;
      while (b.size() % 4) b.push_back(0);
      const std::uint32_t total = std::uint32_t(12 + 8 + json.size() + 8 + b.size());
      auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
      u32(0x46546C67u);
      u32(2);
      u32(total);
      u32(std::uint32_t(json.size()));
      u32(0x4E4F534Au);
      out << json;
      u32(std::uint32_t(b.size()));
      u32(0x004E4942u);
      out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
      return;
    }
    if (how == storage::external_bin) {
      const std::string bin_name = path.substr(path.find_last_of('/') + 1) + ".bin";
      std::ofstream(path.substr(0, path.find_last_of('/') + 1) + bin_name, std::ios::binary)
          .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
      d["buffers"] = {{{"byteLength", bin.size()}, {"uri", bin_name}}};
    } else {
      d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    }
    out << d.dump(1);
  }

  static std::string base64(const std::vector<unsigned char>& in) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
      const std::uint32_t n = (std::uint32_t(in[i]) << 16) | (i + 1 < in.size() ? std::uint32_t(in[i + 1]) << 8 : 0) |
                              (i + 2 < in.size() ? std::uint32_t(in[i + 2]) : 0);
      out += table[(n >> 18) & 63];
      out += table[(n >> 12) & 63];
      out += i + 1 < in.size() ? table[(n >> 6) & 63] : '=';
      out += i + 2 < in.size() ? table[n & 63] : '=';
    }
    return out;
  }
};

}  // namespace airr::test
