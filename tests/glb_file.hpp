#pragma once
// A GLB's JSON and binary chunks, read and written by the container's layout (glTF 2.0, 4.4), for
// tests that rewrite an exported layout as another program would.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

namespace airr::test {

struct glb_file {
  nlohmann::json doc;
  std::string bin;  // the BIN chunk's data (padding included); empty: no BIN chunk

  explicit glb_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::uint32_t json_len = 0, bin_len = 0;
    std::memcpy(&json_len, b.data() + 12, 4);
    doc = nlohmann::json::parse(b.substr(20, json_len));
    if (b.size() >= 28 + std::size_t(json_len)) {
      std::memcpy(&bin_len, b.data() + 20 + json_len, 4);
      bin = b.substr(28 + json_len, bin_len);
    }
  }

  void write(const std::string& path) const {
    std::string text = doc.dump();
    while (text.size() % 4) text += ' ';
    std::string out;
    const auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    const std::size_t bin_chunk = bin.empty() ? 0 : 8 + bin.size();
    for (std::uint32_t v : {0x46546C67u, 2u, std::uint32_t(20 + text.size() + bin_chunk)}) u32(v);
    u32(std::uint32_t(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    out += text;
    if (!bin.empty()) {
      u32(std::uint32_t(bin.size()));
      u32(0x004E4942u);  // "BIN\0"
      out += bin;
    }
    std::ofstream(path, std::ios::binary) << out;
  }

  // The bytes of image i (in a buffer view).
  std::string image(std::size_t i) const {
    const nlohmann::json& view = doc["bufferViews"][doc["images"][i]["bufferView"].get<std::size_t>()];
    return bin.substr(view.value("byteOffset", std::size_t(0)), view["byteLength"].get<std::size_t>());
  }
};

// `from` with its JSON rewritten by `edit`, written to `to`.
inline void rewrite_glb(const std::string& from, const std::string& to,
                        const std::function<void(nlohmann::json&)>& edit) {
  glb_file g(from);
  edit(g.doc);
  g.write(to);
}

}  // namespace airr::test
