#pragma once
// Files and paths: reading text, atomic writes, and resolving the relative paths that scene,
// preset and measurement files hold.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace airr {

// Largest text file read (scenes, presets, shift tables, measurements are kilobytes to megabytes).
inline constexpr std::uintmax_t max_text_file_bytes = std::uintmax_t(512) << 20;

// Throws input_error "<path>: file not found" / "cannot open for reading" / over the size limit.
std::string read_text_file(const std::string& path);

// Writes bytes to a temporary file beside `path`, flushes it to disk, then renames it over `path`,
// so a reader (or a crash at any moment) sees the old or the new file, never a torn one. Throws
// input_error naming the path and the system's reason (e.g. "No space left on device").
void write_file_atomic(const std::string& path, std::string_view bytes);

// The operating system's reason a file cannot be created at `path` (e.g. "Not a directory",
// "Permission denied"), found by creating it and removing it again; empty when it can be created.
// For writers whose library says no reason of its own.
std::string reason_cannot_create(const std::string& path);

// `path` as written in a file whose relative paths count from `base_dir`: empty stays empty, an
// absolute path (or an empty base) is returned as it is, anything else is joined and normalised.
std::string resolve_path(const std::string& path, const std::string& base_dir);

// A relative path that counts from `old_base` rewritten to count from `new_base` (same file);
// empty and absolute paths stay as they are.
std::string rebase_path(const std::string& path, const std::string& old_base, const std::string& new_base);

// The absolute, normalised form of a path (for recent-file lists and dropped files).
std::string absolute_path(const std::string& path);

// Copies the file `from` to `to` atomically (write_file_atomic), unless both name the same file.
void copy_file_atomic(const std::string& from, const std::string& to);

// The programs' folder in an XDG base directory, created: $<variable>/airr-studio when the
// variable holds an absolute path, else ~/<fallback>/airr-studio, else <temp>/airr-studio; e.g.
// ("XDG_CACHE_HOME", ".cache"). The designer's settings, recovery copies and the cache live there.
std::string xdg_app_dir(const char* variable, const char* fallback);

// What a file was when it was read: a changed modification time or size means it changed.
struct file_stamp {
  std::filesystem::file_time_type mtime{};
  std::uintmax_t size = 0;
  bool operator==(const file_stamp&) const = default;
};
// The file's stamp, or nothing when it cannot be read.
std::optional<file_stamp> stamp_of(const std::string& path);

// Values read from files, kept while their file is unchanged (so the designer's frame loop and
// repeated analyses do not read a file again). `key` names the value (the path, perhaps with more);
// `load` reads it and may throw; a file whose stamp cannot be read is loaded and not kept.
template <class T>
class file_cache {
 public:
  std::shared_ptr<const T> get(const std::string& key, const std::string& path,
                               const std::function<std::shared_ptr<const T>()>& load) {
    const std::optional<file_stamp> stamp = stamp_of(path);
    if (stamp) {
      const std::lock_guard lock(mutex_);
      const auto it = entries_.find(key);
      if (it != entries_.end() && it->second.first == *stamp) return it->second.second;
    }
    std::shared_ptr<const T> value = load();
    if (stamp) {
      const std::lock_guard lock(mutex_);
      entries_[key] = {*stamp, value};
    }
    return value;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::pair<file_stamp, std::shared_ptr<const T>>> entries_;
};

}  // namespace airr
