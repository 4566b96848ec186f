// The question a start asks when a previous session left unsaved changes.
#include <imgui.h>

#include "window_private.hpp"

namespace airr::ui {

void draw_recovery_prompt(studio& st) {
  if (st.recovery_text.empty()) return;
  if (!st.recovery_offered) {
    ImGui::OpenPopup("Recover unsaved changes?");
    st.recovery_offered = true;
  }
  if (ImGui::BeginPopupModal("Recover unsaved changes?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("A previous session ended with unsaved changes.");
    if (ImGui::Button("Recover")) {
      studio_recover(st);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      studio_clear_recovery();
      st.recovery_text.clear();
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace airr::ui
