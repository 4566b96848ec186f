// The designer's window each frame: the panels and views side by side, the status bar, the
// prompts; then the frame's edits are applied.
#include <algorithm>

#include <imgui.h>

#include "airr/ui/panels/panels.hpp"
#include "airr/ui/views/views.hpp"
#include "airr/ui/window/window.hpp"
#include "window_private.hpp"

namespace airr::ui {

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
  draw_ghosts_window(st);

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

}  // namespace airr::ui
