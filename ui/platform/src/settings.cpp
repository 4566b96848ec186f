#include "airr/ui/platform/settings.hpp"

#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "airr/formats/scene_json.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

std::string config_dir() { return xdg_app_dir("XDG_CONFIG_HOME", ".config"); }
std::string state_dir() { return xdg_app_dir("XDG_STATE_HOME", ".local/state"); }

studio_settings load_settings() {
  studio_settings s;
  const std::string path = config_dir() + "/settings.json";
  std::error_code ec;
  if (!fs::exists(path, ec)) return s;
  try {
    const auto j = read_json_file(path);
    s.recent_files = j.value("recent_files", s.recent_files);
    s.window_width = std::clamp(j.value("window_width", s.window_width), 320, 16384);
    s.window_height = std::clamp(j.value("window_height", s.window_height), 240, 16384);
    s.exposure_ev = std::clamp(j.value("exposure_ev", s.exposure_ev), -20.0f, 20.0f);
    s.last_dir = j.value("last_dir", s.last_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: %s: ignored (%s)\n", path.c_str(), e.what());
    return studio_settings{};
  }
  return s;
}

void save_settings(const studio_settings& s) {
  const nlohmann::json j = {{"recent_files", s.recent_files},
                            {"window_width", s.window_width},
                            {"window_height", s.window_height},
                            {"exposure_ev", s.exposure_ev},
                            {"last_dir", s.last_dir}};
  try {
    write_file_atomic(config_dir() + "/settings.json", j.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "warning: cannot save settings: %s\n", e.what());
  }
}

void add_recent_file(studio_settings& s, const std::string& path) {
  const std::string abs = absolute_path(path);
  std::erase(s.recent_files, abs);
  s.recent_files.insert(s.recent_files.begin(), abs);
  if (s.recent_files.size() > 10) s.recent_files.resize(10);
}

}  // namespace airr::ui
