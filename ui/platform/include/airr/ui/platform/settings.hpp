#pragma once
// What the designer keeps between sessions, in $XDG_CONFIG_HOME/airr-studio/ (default
// ~/.config/airr-studio/): settings.json (recent files, window size, view options), imgui.ini
// (window layout) and the user's presets; the crash-recovery copy is state, in
// $XDG_STATE_HOME/airr-studio/ (default ~/.local/state/airr-studio/). Nothing is written beside the
// program or into its install prefix.
#include <string>
#include <vector>

namespace airr::ui {

struct studio_settings {
  std::vector<std::string> recent_files;  // most recent first
  int window_width = 1600;
  int window_height = 1000;
  float exposure_ev = 0.0f;
  std::string last_dir;
};

std::string config_dir();                      // created on demand
std::string state_dir();                       // created on demand
studio_settings load_settings();               // defaults when missing or unreadable (a warning on stderr)
void save_settings(const studio_settings& s);  // atomic
void add_recent_file(studio_settings& s, const std::string& path);

}  // namespace airr::ui
