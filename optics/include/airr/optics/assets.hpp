#pragma once
// Where the shipped assets are: $AIRR_ASSETS, else the source tree's assets/ (set at build time).
#include <cstdlib>
#include <string>

namespace airr {

inline std::string asset_dir() {
  if (const char* env = std::getenv("AIRR_ASSETS"); env && *env) return env;
  return AIRR_ASSET_DIR;
}
inline std::string default_scene_path() { return asset_dir() + "/scenes/default.json"; }

}  // namespace airr
