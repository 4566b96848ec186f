#pragma once
// A small file chooser drawn with ImGui: a directory listing filtered by extension, a path field
// and OK/Cancel. One instance serves open and save requests in turn.
#include <string>
#include <vector>

namespace airr::ui {

enum class file_purpose {
  open_scene,
  save_scene,
  export_render,
  export_plots,
  export_bokeh,
  choose_source_image,
  choose_fit_data,
  save_preset,
  add_prop,
  export_gltf
};

struct file_dialog {
  bool visible = false;
  bool saving = false;
  file_purpose purpose = file_purpose::open_scene;
  std::string title;
  std::string dir;
  std::string name;
  std::vector<std::string> extensions;  // lower case with the dot; empty: all files
  std::string error;

  void request(file_purpose p, bool save, const std::string& title, const std::string& start_dir,
               std::vector<std::string> exts, const std::string& default_name = "");
  // Draws the dialog when visible; returns the chosen path once, when the user confirms.
  std::string draw();
};

}  // namespace airr::ui
