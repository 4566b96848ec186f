#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "airr/core/error.hpp"
#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"

namespace airr {

namespace fs = std::filesystem;

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw input_error(path + ": file not found");
  if (fs::file_size(path, ec) > max_text_file_bytes)
    throw input_error(path + ": larger than the limit of " + std::to_string(max_text_file_bytes >> 20) +
                      " MiB for a text file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
  const std::string tmp = path + ".tmp" + std::to_string(::getpid());
  // Closes the temporary file (if open), removes it, and says what failed with errno's reason.
  int fd = -1;
  const auto fail = [&](const std::string& what) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw input_error(path + ": " + what + ": " + why);
  };
  fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot write (temporary file " + tmp + ")");
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = EIO;
    if (n <= 0) fail("write failed");
    done += std::size_t(n);
  }
  // On disk before the rename makes it the file: a crash leaves the old file or the new one.
  if (::fsync(fd) != 0) fail("write failed");
  const int closing = fd;
  fd = -1;
  if (::close(closing) != 0) fail("write failed");
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot replace file");
}

std::string reason_cannot_create(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return errno == EEXIST ? std::string() : std::strerror(errno);
  ::close(fd);
  ::unlink(path.c_str());
  return {};
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

std::string xdg_app_dir(const char* variable, const char* fallback) {
  fs::path base;
  if (const char* xdg = std::getenv(variable); xdg && *xdg && fs::path(xdg).is_absolute()) {
    base = xdg;
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    base = fs::path(home) / fallback;
  } else {
    base = fs::temp_directory_path();
  }
  const fs::path dir = base / "airr-studio";
  std::error_code ec;
  fs::create_directories(dir, ec);
  return dir.string();
}

void copy_file_atomic(const std::string& from, const std::string& to) {
  if (absolute_path(from) == absolute_path(to)) return;
  write_file_atomic(to, read_text_file(from));
}

static std::string too_deep_message(const std::string& origin) {
  return origin + ": malformed JSON: nested deeper than " + std::to_string(max_json_depth) + " levels";
}

void check_json_depth(std::string_view text, const std::string& origin) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_json_depth) throw input_error(too_deep_message(origin));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

nlohmann::json parse_json(std::string_view text, const std::string& origin) {
  check_json_depth(text, origin);
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
