#pragma once

#include <filesystem>
#include <string_view>

namespace airr::analysis {

// Writes bytes to path.tmp, then renames it over path, so readers never see a partial file.
// Throws std::runtime_error naming the file on failure.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);

}  // namespace airr::analysis
