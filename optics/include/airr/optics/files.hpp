#pragma once
// Files and paths: reading text, atomic writes, and resolving the relative paths that scene,
// preset and measurement files hold.
#include <string>
#include <string_view>

namespace airr {

// Throws input_error "<path>: file not found" / "cannot open for reading".
std::string read_text_file(const std::string& path);

// Writes bytes to a temporary file beside `path`, then renames it over `path`, so a reader sees
// the old or the new file, never a torn one. Throws input_error naming the path.
void write_file_atomic(const std::string& path, std::string_view bytes);

// `path` as written in a file whose relative paths count from `base_dir`: empty stays empty, an
// absolute path (or an empty base) is returned as it is, anything else is joined and normalised.
std::string resolve_path(const std::string& path, const std::string& base_dir);

// A relative path that counts from `old_base` rewritten to count from `new_base` (same file);
// empty and absolute paths stay as they are.
std::string rebase_path(const std::string& path, const std::string& old_base, const std::string& new_base);

// The absolute, normalised form of a path (for recent-file lists and dropped files).
std::string absolute_path(const std::string& path);

}  // namespace airr
