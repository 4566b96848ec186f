// The designer's menu bar, its file dialogs, the unsaved-changes question and the shortcuts.
#include <filesystem>

#include <imgui.h>

#include "airr/core/assets.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/ui/panels/panels.hpp"
#include "airr/ui/views/views.hpp"
#include "window_private.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

static std::string start_dir(const studio& st) {
  if (!st.doc_path.empty()) return fs::path(st.doc_path).parent_path().string();
  return st.settings.last_dir;
}

static void request_save_as(studio& st) {
  st.dialog.request(file_purpose::save_scene, true, "Save scene as", start_dir(st), {".json"},
                    suggested_scene_name(st.doc_path));
}

// Save: to the scene's own file, unless it came from a glTF layout (saved as a scene file instead).
static void save_or_ask(studio& st) {
  if (st.doc_path.empty() || is_gltf_path(st.doc_path))
    request_save_as(st);
  else
    studio_save(st, st.doc_path);
}

// Continues whatever waited for the unsaved-changes question.
static void run_pending(studio& st) {
  const auto action = st.after_save_prompt;
  st.after_save_prompt = studio::pending_action::none;
  switch (action) {
    case studio::pending_action::quit:
      st.quit_requested = true;
      break;
    case studio::pending_action::open_file:
      st.dialog.request(file_purpose::open_scene, false, "Open scene or glTF layout", start_dir(st),
                        {".json", ".glb", ".gltf"});
      break;
    case studio::pending_action::open_path:
      studio_open(st, st.pending_path);
      break;
    case studio::pending_action::new_scene: {
      // The shipped default scene, untitled (its relative paths point into assets/).
      scene s;
      try {
        s = load_scene(default_scene_path());
      } catch (const std::exception& e) {
        s.base_dir = asset_dir() + "/scenes";
        s.source.image = "../charts/test_chart.png";
        st.status =
            std::string("the default scene does not load (") + e.what() + "); a new scene starts on the ideal bench";
      }
      studio_start(st, s, "");
      break;
    }
    case studio::pending_action::none:
      break;
  }
}

static void ask_or_run(studio& st, studio::pending_action action) {
  st.after_save_prompt = action;
  if (studio_dirty(st))
    st.show_save_prompt = true;
  else
    run_pending(st);
}

void draw_menu(studio& st) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New scene")) ask_or_run(st, studio::pending_action::new_scene);
    if (ImGui::MenuItem("Open scene...", "Ctrl+O")) ask_or_run(st, studio::pending_action::open_file);
    if (ImGui::BeginMenu("Open recent", !st.settings.recent_files.empty())) {
      for (const auto& f : st.settings.recent_files) {
        if (ImGui::MenuItem(f.c_str())) {
          st.pending_path = f;
          ask_or_run(st, studio::pending_action::open_path);
        }
      }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Save", "Ctrl+S")) save_or_ask(st);
    if (ImGui::MenuItem("Save as...")) request_save_as(st);
    ImGui::Separator();
    if (ImGui::MenuItem("Source image...")) {
      st.dialog.request(file_purpose::choose_source_image, false, "Source image", start_dir(st),
                        {".png", ".jpg", ".jpeg", ".exr", ".tif", ".tiff", ".hdr"});
    }
    if (ImGui::MenuItem("Export render...")) {
      st.dialog.request(file_purpose::export_render, true, "Export render (.exr or .png)", start_dir(st),
                        {".exr", ".png"}, "render.exr");
    }
    if (ImGui::MenuItem("Add prop (glTF, STEP)...")) {
      st.dialog.request(file_purpose::add_prop, false, "Add a glTF or STEP model as a prop", start_dir(st),
                        {".glb", ".gltf", ".step", ".stp"});
    }
    if (ImGui::MenuItem("Export layout (glTF)...")) {
      st.dialog.request(file_purpose::export_gltf, true, "Export the layout as glTF (.glb or .gltf)", start_dir(st),
                        {".glb", ".gltf"}, "layout.glb");
    }
    if (ImGui::MenuItem("Export plot data...")) {
      st.dialog.request(file_purpose::export_plots, true, "Export plot data (CSV)", start_dir(st), {".csv"},
                        "plots.csv");
    }
    if (ImGui::MenuItem("Export bokeh pictures...")) {
      st.dialog.request(file_purpose::export_bokeh, true, "Export the bokeh views (PNG; the others beside it)",
                        start_dir(st), {".png"}, "bokeh.png");
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Fit a sheet preset...")) st.show_fit = true;
    if (ImGui::MenuItem("Predict a preset from the sheet's model", nullptr, false,
                        st.doc.sheet().model.type != "sinc_shift" && !(st.fit_job_ && st.fit_job_->running()))) {
      st.show_fit = true;
      st.fit_error.clear();
      start_preset_prediction(st);
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) ask_or_run(st, studio::pending_action::quit);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo = "Undo " + st.history.undo_name(), redo = "Redo " + st.history.redo_name();
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, st.history.can_undo())) studio_undo(st);
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Y", false, st.history.can_redo())) studio_redo(st);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Design")) {
    if (ImGui::MenuItem("Optimise...")) st.design.show_optimise = true;
    if (ImGui::MenuItem("Tolerance...")) st.design.show_tolerance = true;
    if (ImGui::MenuItem("Ghosts...")) st.ghosts.show = true;
    ImGui::EndMenu();
  }
  ImGui::TextDisabled("  %s%s", display_name(st).c_str(), studio_dirty(st) ? " (unsaved changes)" : "");
  ImGui::EndMainMenuBar();
}

void draw_save_prompt(studio& st) {
  if (st.show_save_prompt) {
    ImGui::OpenPopup("Unsaved changes");
    st.show_save_prompt = false;
  }
  if (ImGui::BeginPopupModal("Unsaved changes", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s has unsaved changes.", display_name(st).c_str());
    if (ImGui::Button("Save")) {
      ImGui::CloseCurrentPopup();
      if (st.doc_path.empty() || is_gltf_path(st.doc_path))
        request_save_as(st);  // the pending action runs after the dialog
      else if (studio_save(st, st.doc_path))
        run_pending(st);
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      ImGui::CloseCurrentPopup();
      st.saved = st.doc;
      run_pending(st);
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      st.after_save_prompt = studio::pending_action::none;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void handle_dialog(studio& st) {
  const std::string path = st.dialog.draw();
  if (path.empty()) return;
  switch (st.dialog.purpose) {
    case file_purpose::open_scene:
      studio_open(st, path);
      break;
    case file_purpose::save_scene:
      if (studio_save(st, path)) run_pending(st);
      break;
    case file_purpose::export_render:
      studio_export_render(st, path);
      break;
    case file_purpose::export_plots:
      studio_export_plots(st, path);
      break;
    case file_purpose::export_bokeh:
      studio_export_bokeh(st, path);
      break;
    case file_purpose::choose_source_image:
      studio_drop_file(st, path);
      break;
    case file_purpose::choose_fit_data:
      st.fit_dir = fs::path(path).parent_path().string();
      break;
    case file_purpose::save_preset:
      save_fitted_preset(st, path);
      break;
    case file_purpose::add_prop:
      studio_add_prop(st, path);
      break;
    case file_purpose::export_gltf:
      studio_export_gltf(st, path);
      break;
  }
}

void handle_shortcuts(studio& st) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.KeyCtrl || io.WantTextInput) return;
  // ImGui 1.86 indexes keys by the backend's codes; GLFW's letter codes are their ASCII capitals.
  if (ImGui::IsKeyPressed('S')) save_or_ask(st);
  if (ImGui::IsKeyPressed('O')) ask_or_run(st, studio::pending_action::open_file);
  if (ImGui::IsKeyPressed('Z')) io.KeyShift ? studio_redo(st) : studio_undo(st);
  if (ImGui::IsKeyPressed('Y')) studio_redo(st);
}

}  // namespace airr::ui
