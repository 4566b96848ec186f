#include "jpeg_iptc_check.hpp"

#include <algorithm>
#include <cstdint>
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
  if (p.size() < data_at) return "its Photoshop segment ends inside the IPTC header";
  std::size_t length = be16(p, data_at - 2);
  if (data_at + length > p.size()) {
    return "its IPTC block claims " + std::to_string(length) + " bytes, the segment holds " +
           std::to_string(p.size() - data_at);
  }
  for (std::size_t at = data_at; length >= 5 && p[at] == 0x1c && (p[at + 1] == 1 || p[at + 1] == 2);) {
    const std::size_t record = 5 + be16(p, at + 3);
    if (record > length) {
      return "an IPTC record claims " + std::to_string(record - 5) + " bytes, its block holds " +
             std::to_string(length - 5);
    }
    at += record;
    length -= record;
  }
  return std::nullopt;
}

std::optional<std::string> jpeg_iptc_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const auto byte = [&]() -> int { return in.get(); };
  if (byte() != 0xff || byte() != 0xd8) return std::nullopt;
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

}  // namespace airr
