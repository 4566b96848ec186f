#include "airr/core/assets.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace airr {

namespace fs = std::filesystem;

static fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

static bool is_within(const fs::path& path, const fs::path& dir) {
  const fs::path p = path.lexically_normal(), d = dir.lexically_normal();
  return std::mismatch(d.begin(), d.end(), p.begin(), p.end()).first == d.end();
}

static std::string installed_or_build_tree_assets() {
  const fs::path exe = executable_dir();
  if (exe.empty()) return AIRR_SOURCE_ASSET_DIR;
  const fs::path installed = (exe / ".." / "share" / "airr-studio").lexically_normal();
  std::error_code ec;
  if (fs::is_directory(installed / "scenes", ec)) return installed.string();
  if (is_within(exe, AIRR_BUILD_DIR)) return AIRR_SOURCE_ASSET_DIR;
  return installed.string();  // missing: errors then name where the assets were looked for
}

// Set once, when a host program loads the library, before any asset is looked for.
static std::string& set_dir() {
  static std::string dir;
  return dir;
}

void set_asset_dir(const std::string& dir) { set_dir() = dir; }

std::string asset_dir() {
  if (const char* env = std::getenv("AIRR_ASSETS"); env && *env) return env;
  if (!set_dir().empty()) return set_dir();
  static const std::string dir = installed_or_build_tree_assets();
  return dir;
}

std::string default_scene_path() { return asset_dir() + "/scenes/default.json"; }
std::string ideal_bench_scene_path() { return asset_dir() + "/scenes/ideal_bench.json"; }

bool is_shipped_asset(const std::string& path) {
  if (path.empty()) return false;
  std::error_code ec;
  const fs::path file = fs::weakly_canonical(path, ec);
  if (ec) return false;
  const fs::path assets = fs::weakly_canonical(asset_dir(), ec);
  return !ec && is_within(file, assets);
}

std::vector<std::string> shipped_json_names(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(asset_dir() + "/" + folder, ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace airr
