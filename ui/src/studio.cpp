// The designer's state across frames: starting on a scene, applying edits, the frame's windows.
#include "airr/ui/studio.hpp"

#include <algorithm>
#include <filesystem>

#include <imgui.h>

#include "airr/core/assets.hpp"
#include "airr/formats/scene_json.hpp"
#include "studio_private.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

std::string suggested_scene_name(const std::string& doc_path) {
  if (doc_path.empty()) return "scene.airr.json";
  const fs::path p(doc_path);
  return p.extension() == ".json" ? p.filename().string() : p.stem().string() + ".airr.json";
}

std::string display_name(const studio& st) {
  return st.doc_path.empty() ? "untitled" : fs::path(st.doc_path).filename().string();
}

// Every prop's mesh (from the mesh cache, which check_scene filled) and its bounds, computed only
// for a mesh that was not there before (an edit that moves a prop keeps them).
static void keep_prop_meshes(studio& st, const scene& s) {
  std::vector<std::shared_ptr<const triangle_mesh>> meshes;
  std::vector<mesh_bounds> bounds;
  for (const auto& p : s.props) {
    std::shared_ptr<const triangle_mesh> m;
    try {
      m = cached_prop_mesh(resolve_scene_path(s, p.mesh), p.node);
    } catch (const std::exception&) {
    }
    const auto kept = std::find(st.prop_meshes.begin(), st.prop_meshes.end(), m);
    if (m && kept != st.prop_meshes.end())
      bounds.push_back(st.prop_bounds[std::size_t(kept - st.prop_meshes.begin())]);
    else
      bounds.push_back(m ? bounds_of(*m) : mesh_bounds{});
    meshes.push_back(std::move(m));
  }
  st.prop_meshes = std::move(meshes);
  st.prop_bounds = std::move(bounds);
}

// A shipped scene opens untitled, so that saving asks where: the assets are never written.
void studio_start(studio& st, const scene& s, const std::string& path) {
  keep_prop_meshes(st, s);
  st.view_3d.framed = false;
  st.doc = s;
  st.doc_path = is_shipped_asset(path) ? "" : path;
  st.saved = s;
  st.applied = s;
  st.doc_error.clear();
  if (!st.session) {
    st.session = std::make_unique<render_session>(s, st.session_options);
    st.generation = 0;
  } else {
    st.generation = st.session->edit(s);
  }
  st.analysis.submit_scene(s, st.generation, {});
  st.view.uploaded_generation = ~0ull;
  // Another scene: its own history, and no results of the last one's design runs.
  st.history.reset(s);
  st.design.job.reset();
  st.design.optimised.reset();
  st.design.tolerances.reset();
  st.design.ghost.reset();
  st.design.chosen = -1;
  st.design.spec_started = false;
  if (!st.doc_path.empty()) add_recent_file(st.settings, st.doc_path);
}

bool studio_dirty(const studio& st) { return !st.saved || !(st.doc == *st.saved); }

void studio_apply_edits(studio& st, double now) {
  if (st.doc == st.applied) return;
  st.applied = st.doc;
  try {
    // The models are built once per accepted edit and shared by the tracer and the plots.
    const retro_model_list models = check_scene(st.doc, "layout");
    keep_prop_meshes(st, st.doc);
    st.doc_error.clear();
    st.generation = st.session->edit(st.doc, models);
    st.analysis.submit_scene(st.doc, st.generation, models);
    st.edit_time = now;
  } catch (const std::exception& e) {
    st.doc_error = e.what();
  }
}

void studio_frame(studio& st, double now) {
  handle_shortcuts(st);
  draw_menu(st);
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  const float top = vp->WorkPos.y, w = vp->WorkSize.x, h = vp->WorkSize.y - ImGui::GetFrameHeight();
  const float left_w = std::min(0.26f * w, 30.0f * ImGui::GetFontSize()), right_w = 0.28f * w;
  const float mid_w = w - left_w - right_w, render_h = 0.56f * h;
  auto place = [&](float x, float y, float ww, float hh) {
    ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + x, top + y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(ww, hh), ImGuiCond_FirstUseEver);
  };
  place(0, 0, left_w, h);
  draw_layout_panel(st);
  place(left_w, 0, mid_w, render_h);
  draw_render_view(st, now);
  place(left_w, render_h, mid_w, h - render_h);
  draw_layout_view(st);
  place(left_w + mid_w, 0, right_w, h);
  draw_plots_panel(st);
  draw_fit_window(st);
  collect_design_job(st);
  draw_optimise_window(st);
  draw_tolerance_window(st);

  // Status bar.
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x, vp->WorkPos.y + vp->WorkSize.y - ImGui::GetFrameHeight()));
  ImGui::SetNextWindowSize(ImVec2(vp->WorkSize.x, ImGui::GetFrameHeight()));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  if (!st.doc_error.empty())
    ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", st.doc_error.c_str());
  else
    ImGui::TextUnformatted(st.status.c_str());
  ImGui::End();

  draw_save_prompt(st);
  draw_recovery_prompt(st);
  handle_dialog(st);
  st.history.settle(st.doc, ImGui::IsAnyItemActive());
  studio_apply_edits(st, now);
  studio_keep_recovery(st, now);
}

void studio_undo(studio& st) {
  if (st.history.undo(st.doc)) st.status = "undid " + st.history.redo_name();
}

void studio_redo(studio& st) {
  if (st.history.redo(st.doc)) st.status = "redid " + st.history.undo_name();
}

}  // namespace airr::ui
