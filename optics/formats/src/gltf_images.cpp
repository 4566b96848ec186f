#include "gltf_images.hpp"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string_view>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/formats/image.hpp"

namespace airr::gltf {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view png_magic("\x89PNG\r\n\x1a\n", 8);
constexpr std::string_view jpeg_magic("\xff\xd8\xff", 3);

bool starts_with(std::string_view bytes, std::string_view magic) { return bytes.substr(0, magic.size()) == magic; }

// 64-bit FNV-1a: names a cache file (its bytes are compared before it is reused).
std::uint64_t content_hash(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

// The bytes of a buffer view, its range checked against its buffer.
std::string_view buffer_view_bytes(const file& f, int index) {
  const auto& m = f.model;
  if (index < 0 || std::size_t(index) >= m.bufferViews.size()) {
    throw input_error("buffer view " + std::to_string(index) + " does not exist");
  }
  const tinygltf::BufferView& v = m.bufferViews[std::size_t(index)];
  if (v.buffer < 0 || std::size_t(v.buffer) >= m.buffers.size()) {
    throw input_error("buffer view " + std::to_string(index) + " has no valid buffer");
  }
  const auto& data = m.buffers[std::size_t(v.buffer)].data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset) {
    throw input_error("buffer view " + std::to_string(index) + " reaches past the end of its buffer");
  }
  return {reinterpret_cast<const char*>(data.data()) + v.byteOffset, v.byteLength};
}

// A copy of embedded bytes in the cache, named by their content.
std::string cached_copy(std::string_view bytes) {
  const char* ext = starts_with(bytes, png_magic) ? ".png" : starts_with(bytes, jpeg_magic) ? ".jpg" : nullptr;
  if (!ext) throw input_error("the embedded image is neither PNG nor JPEG");
  char name[64];
  std::snprintf(name, sizeof name, "%016llx-%zu%s", static_cast<unsigned long long>(content_hash(bytes)), bytes.size(),
                ext);
  const std::string path = (fs::path(embedded_image_dir()) / name).string();
  // One writer at a time: write_file_atomic's temporary name is per process, not per thread.
  static std::mutex writing;
  const std::lock_guard lock(writing);
  std::error_code ec;
  if (fs::file_size(path, ec) == bytes.size() && !ec && read_text_file(path) == bytes) return path;
  write_file_atomic(path, bytes);
  return path;
}

// %XX escapes decoded (glTF URIs are URI references).
std::string decode_uri(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The file holding the image, and whether it is a copy in the cache.
std::pair<std::string, bool> image_path(const file& f, int image) {
  if (image < 0 || std::size_t(image) >= f.model.images.size()) throw input_error("does not exist");
  const tinygltf::Image& img = f.model.images[std::size_t(image)];
  if (!is_embedded_image(f, image)) {
    return {resolve_path(decode_uri(img.uri), fs::path(f.path).parent_path().string()), false};
  }
  if (img.bufferView >= 0) return {cached_copy(buffer_view_bytes(f, img.bufferView)), true};
  return {cached_copy(std::string_view(reinterpret_cast<const char*>(img.image.data()), img.image.size())), true};
}

}  // namespace

std::string embedded_image_dir() {
  const fs::path dir = fs::path(xdg_app_dir("XDG_CACHE_HOME", ".cache")) / "embedded";
  std::error_code ec;
  fs::create_directories(dir, ec);
  return dir.string();
}

int texture_image(const file& f, int texture, const std::string& what) {
  const std::string head = f.path + ": " + what + ": texture " + std::to_string(texture);
  if (texture < 0 || std::size_t(texture) >= f.model.textures.size()) throw input_error(head + " does not exist");
  const int image = f.model.textures[std::size_t(texture)].source;
  if (image < 0 || std::size_t(image) >= f.model.images.size()) {
    throw input_error(head + ": image " + std::to_string(image) + " does not exist");
  }
  return image;
}

bool is_embedded_image(const file& f, int image) {
  const tinygltf::Image& img = f.model.images[std::size_t(image)];
  return img.bufferView >= 0 || img.uri.empty();
}

void read_image_file(const file& f, int image, const std::string& what,
                     const std::function<void(const std::string& path)>& read) {
  const std::string head = f.path + ": " + what + ": image " + std::to_string(image) + ": ";
  std::pair<std::string, bool> found;
  try {
    found = image_path(f, image);
    read(found.first);
  } catch (const input_error& e) {
    std::string why = e.what();
    const auto& [path, cached] = found;
    if (cached) {
      std::error_code ec;
      fs::remove(path, ec);
      // The loader names the file it read: for a cache copy, name the glTF instead.
      if (why.rfind(path + ": ", 0) == 0) why = why.substr(path.size() + 2);
    }
    throw input_error(head + why);
  }
}

embedded_image image_to_embed(const std::string& path) {
  const loaded_image img = load_image(path);  // refuses a damaged file before it is embedded
  const std::string bytes = read_text_file(path);
  if (starts_with(bytes, png_magic)) return {bytes, "image/png"};
  if (starts_with(bytes, jpeg_magic)) return {bytes, "image/jpeg"};
  const bool eight_bit = img.format == "uint8" || img.format == "int8";
  return {encode_png(img.pixels, !eight_bit, path), "image/png"};
}

}  // namespace airr::gltf
