// Unsaved changes kept where the next start offers them back.
#include <filesystem>

#include <imgui.h>

#include "airr/core/files.hpp"
#include "airr/core/json_reader.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/ui/settings.hpp"
#include "studio_private.hpp"

namespace airr::ui {

namespace fs = std::filesystem;

std::string recovery_path() { return state_dir() + "/recovery.json"; }

std::optional<std::string> write_recovery_copy(const studio& st) {
  const nlohmann::json j = {{"path", st.doc_path}, {"base_dir", st.doc.base_dir}, {"scene", scene_to_json(st.doc)}};
  try {
    write_file_atomic(recovery_path(), j.dump(2) + "\n");
    return std::nullopt;
  } catch (const std::exception& e) {
    return e.what();
  }
}

void studio_keep_recovery(studio& st, double now) {
  if (!st.keep_recovery) return;
  if (!studio_dirty(st)) {
    if (st.last_recovery_write >= 0) studio_clear_recovery();
    st.last_recovery_write = -1;
    return;
  }
  if (st.last_recovery_write >= 0 && now - st.last_recovery_write < 10.0) return;
  st.last_recovery_write = now;
  if (const auto failed = write_recovery_copy(st)) st.status = "cannot write the recovery copy: " + *failed;
}

void studio_clear_recovery() {
  std::error_code ec;
  fs::remove(recovery_path(), ec);
}

void studio_check_recovery(studio& st) {
  std::error_code ec;
  if (!fs::exists(recovery_path(), ec)) return;
  try {
    st.recovery_text = read_text_file(recovery_path());
  } catch (const std::exception&) {
    st.recovery_text.clear();
  }
}

void draw_recovery_prompt(studio& st) {
  if (st.recovery_text.empty()) return;
  if (!st.recovery_offered) {
    ImGui::OpenPopup("Recover unsaved changes?");
    st.recovery_offered = true;
  }
  if (ImGui::BeginPopupModal("Recover unsaved changes?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted("A previous session ended with unsaved changes.");
    if (ImGui::Button("Recover")) {
      try {
        const auto j = parse_json(st.recovery_text, recovery_path());
        scene s = scene_from_json(j.at("scene"), recovery_path());
        s.base_dir = j.value("base_dir", std::string());
        st.doc = s;
        st.doc_path = j.value("path", std::string());
        st.saved.reset();  // recovered edits are unsaved
        st.status = "recovered unsaved changes" + (st.doc_path.empty() ? std::string() : " of " + st.doc_path);
      } catch (const std::exception& e) {
        st.status = std::string("cannot recover: ") + e.what();
      }
      st.recovery_text.clear();
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
