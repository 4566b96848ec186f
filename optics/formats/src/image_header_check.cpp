#include "image_header_check.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace airr {

static unsigned be16(std::string_view s, std::size_t at) {
  return (unsigned(std::uint8_t(s[at])) << 8) | std::uint8_t(s[at + 1]);
}

// The APP13 payload as OpenImageIO reads it: "Photoshop 3.0\0", "8BIM", resource 0x0404, four
// bytes it skips, a 16-bit block size, then IIM records (1C, record, dataset, 16-bit length, data).
static std::optional<std::string> photoshop_problem(std::string_view p) {
  constexpr std::string_view header(
      "Photoshop 3.0\0"
      "8BIM\x04\x04",
      20);
  constexpr std::size_t data_at = 26;
  const std::size_t compared = std::min(p.size(), header.size());
  if (p.substr(0, compared) != header.substr(0, compared)) return std::nullopt;
  if (p.size() < data_at) return "cannot read image: its Photoshop segment ends inside the IPTC header";
  std::size_t length = be16(p, data_at - 2);
  if (data_at + length > p.size()) {
    return "cannot read image: its IPTC block claims " + std::to_string(length) + " bytes, the segment holds " +
           std::to_string(p.size() - data_at);
  }
  for (std::size_t at = data_at; length >= 5 && p[at] == 0x1c && (p[at + 1] == 1 || p[at + 1] == 2);) {
    const std::size_t record = 5 + be16(p, at + 3);
    if (record > length) {
      return "cannot read image: an IPTC record claims " + std::to_string(record - 5) + " bytes, its block holds " +
             std::to_string(length - 5);
    }
    at += record;
    length -= record;
  }
  return std::nullopt;
}

// Walks the JPEG segments up to the pixel data (the stream is past the start marker).
static std::optional<std::string> jpeg_iptc_problem(std::ifstream& in) {
  const auto byte = [&]() -> int { return in.get(); };
  while (in) {
    int marker = byte();
    while (marker >= 0 && marker != 0xff) marker = byte();  // libjpeg skips stray bytes between segments
    while (marker == 0xff) marker = byte();
    if (marker < 0 || marker == 0xda || marker == 0xd9) return std::nullopt;  // pixel data or end
    if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) continue;       // markers without a length
    const int hi = byte(), lo = byte();
    if (hi < 0 || lo < 0 || ((hi << 8) | lo) < 2) return std::nullopt;
    std::string payload(std::size_t(((hi << 8) | lo) - 2), '\0');
    if (!in.read(payload.data(), std::streamsize(payload.size()))) return std::nullopt;
    if (marker == 0xed)
      if (auto problem = photoshop_problem(payload)) return problem;
  }
  return std::nullopt;
}

static std::int64_t le32(const char* s) {
  const auto b = [&](int i) { return std::uint32_t(std::uint8_t(s[i])) << (8 * i); };
  return std::int32_t(b(0) | b(1) | b(2) | b(3));
}

// A null-terminated name of at most max_length characters, or nothing if the file has none there.
static std::optional<std::string> exr_name(std::ifstream& in, std::size_t max_length) {
  std::string name;
  for (int c = in.get(); c != 0; c = in.get()) {
    if (c < 0 || name.size() == max_length) return std::nullopt;
    name += char(c);
  }
  return name;
}

// What an attribute's value holds against what its type makes the library allocate: a string list
// is strings each led by its length; a preview is its width and height, then 4 bytes per pixel.
static std::optional<std::string> exr_value_problem(const std::string& name, const std::string& type,
                                                    const std::string& value) {
  if (type == "stringvector") {
    for (std::size_t at = 0; at < value.size();) {
      const std::int64_t left = std::int64_t(value.size() - at) - 4;
      const std::int64_t length = left < 0 ? -1 : le32(value.data() + at);
      if (length < 0 || length > left) {
        return "cannot read image: a string in its header attribute '" + name + "' claims " + std::to_string(length) +
               " bytes, the attribute holds " + std::to_string(std::max<std::int64_t>(left, 0));
      }
      at += 4 + std::size_t(length);
    }
  }
  if (type == "preview") {
    const std::uint64_t pixels =
        value.size() < 8 ? 0 : std::uint64_t(std::uint32_t(le32(value.data()))) * std::uint32_t(le32(value.data() + 4));
    if (value.size() < 8 || (value.size() - 8) % 4 != 0 || (value.size() - 8) / 4 != pixels) {
      return "cannot read image: its preview image '" + name + "' declares " + std::to_string(pixels) + " pixels in " +
             std::to_string(value.size()) + " bytes";
    }
  }
  return std::nullopt;
}

// Walks an OpenEXR file's header attributes (name, type, 32-bit size, value), every part's in a
// multi-part file, checking each declared size against the bytes the file holds (the stream is
// past the magic number).
static std::optional<std::string> exr_header_problem(std::ifstream& in, std::int64_t file_size,
                                                     std::int64_t pixel_limit) {
  char version[4];
  if (!in.read(version, 4)) return std::nullopt;
  const std::int64_t flags = le32(version);
  constexpr std::size_t max_name = 255;  // what OpenEXR reads, whatever the long-names flag says
  const bool multipart = flags & 0x1000;
  for (;;) {
    for (;;) {
      const auto name = exr_name(in, max_name);
      if (!name) return std::nullopt;
      if (name->empty()) break;  // the header's end
      const auto type = exr_name(in, max_name);
      char size_bytes[4];
      if (!type || !in.read(size_bytes, 4)) return std::nullopt;
      const std::int64_t size = le32(size_bytes);
      const std::int64_t left = file_size - std::int64_t(in.tellg());
      if (size < 0 || size > left) {
        return "cannot read image: its header attribute '" + *name + "' (" + *type + ") claims " +
               std::to_string(size) + " bytes, the file holds " + std::to_string(left) + " after it";
      }
      if (*name == "dataWindow" && *type == "box2i" && size == 16) {
        char box[16];
        if (!in.read(box, 16)) return std::nullopt;
        const std::int64_t width = le32(box + 8) - le32(box) + 1, height = le32(box + 12) - le32(box + 4) + 1;
        // The library allocates a buffer of several whole lines as it opens a file, before the
        // loader's own size check, so the size is checked here.
        if (width > 0 && height > 0 && width > pixel_limit / height) {
          return "image too large (" + std::to_string(width) + "x" + std::to_string(height) + "; the limit is " +
                 std::to_string(pixel_limit) + " pixels)";
        }
        continue;
      }
      if (*type != "stringvector" && *type != "preview") {
        in.seekg(size, std::ios::cur);
        continue;
      }
      std::string value(std::size_t(size), '\0');
      if (!in.read(value.data(), std::streamsize(size))) return std::nullopt;
      if (auto problem = exr_value_problem(*name, *type, value)) return problem;
    }
    if (!multipart || in.peek() == 0 || in.peek() < 0) return std::nullopt;  // an empty header ends the parts
  }
}

std::optional<std::string> image_header_problem(const std::string& path, std::int64_t pixel_limit) {
  std::error_code ec;
  const auto file_size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  const std::string_view start(magic, std::size_t(in.gcount()));
  in.clear();
  if (start.substr(0, 2) == "\xff\xd8") {
    in.seekg(2);
    return jpeg_iptc_problem(in);
  }
  if (start == std::string_view("v/1\x01", 4) && !ec)
    return exr_header_problem(in, std::int64_t(file_size), pixel_limit);
  return std::nullopt;
}

}  // namespace airr
