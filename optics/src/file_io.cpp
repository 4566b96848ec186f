#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "airr/optics/error.hpp"
#include "airr/optics/files.hpp"
#include "airr/optics/json_reader.hpp"

namespace airr {

namespace fs = std::filesystem;

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw input_error(path + ": file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw input_error(path + ": cannot write (temporary file " + tmp + ")");
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw input_error(path + ": write failed");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw input_error(path + ": cannot replace file: " + ec.message());
  }
}

std::string resolve_path(const std::string& path, const std::string& base_dir) {
  if (path.empty() || fs::path(path).is_absolute() || base_dir.empty()) return path;
  return (fs::path(base_dir) / path).lexically_normal().string();
}

std::string rebase_path(const std::string& path, const std::string& old_base, const std::string& new_base) {
  if (path.empty() || fs::path(path).is_absolute() || old_base.empty()) return path;
  return fs::path(resolve_path(path, old_base)).lexically_relative(new_base).string();
}

std::optional<file_stamp> stamp_of(const std::string& path) {
  std::error_code ec_time, ec_size;
  const auto mtime = fs::last_write_time(path, ec_time);
  const auto size = fs::file_size(path, ec_size);
  if (ec_time || ec_size) return std::nullopt;
  return file_stamp{mtime, size};
}

std::string absolute_path(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

nlohmann::json parse_json(std::string_view text, const std::string& origin) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    std::string what = e.what();
    const auto p = what.find("] ");  // drop nlohmann's "[json.exception...]" tag
    throw input_error(origin + ": malformed JSON: " + (p == std::string::npos ? what : what.substr(p + 2)));
  }
}

nlohmann::json read_json_file(const std::string& path) { return parse_json(read_text_file(path), path); }

}  // namespace airr
