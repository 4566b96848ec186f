#include "airr/ui/platform/file_dialog.hpp"

#include "airr/core/files.hpp"

#include <algorithm>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

namespace airr::ui {

namespace fs = std::filesystem;

void file_dialog::request(file_purpose p, bool save, const std::string& t, const std::string& start_dir,
                          std::vector<std::string> exts, const std::string& default_name) {
  purpose = p;
  saving = save;
  title = t;
  std::error_code ec;
  dir = fs::is_directory(start_dir, ec) ? start_dir : fs::current_path(ec).string();
  name = default_name;
  extensions = std::move(exts);
  error.clear();
  visible = true;
}

static bool has_extension(const fs::path& p, const std::vector<std::string>& exts) {
  if (exts.empty()) return true;
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return std::find(exts.begin(), exts.end(), e) != exts.end();
}

std::string file_dialog::draw() {
  if (!visible) return "";
  const std::string popup = title + "###file_dialog";
  if (!ImGui::IsPopupOpen(popup.c_str())) ImGui::OpenPopup(popup.c_str());
  const float em = ImGui::GetFontSize();
  ImGui::SetNextWindowSize(ImVec2(40 * em, 28 * em), ImGuiCond_Appearing);
  std::string chosen;
  if (ImGui::BeginPopupModal(popup.c_str(), nullptr)) {
    ImGui::TextUnformatted(dir.c_str());
    if (ImGui::Button("Up")) dir = fs::path(dir).parent_path().string();
    ImGui::SameLine();
    std::string ext_list;
    for (const auto& e : extensions) ext_list += (ext_list.empty() ? "" : " ") + e;
    ImGui::TextDisabled("%s", ext_list.empty() ? "all files" : ext_list.c_str());

    std::vector<fs::directory_entry> dirs, files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec)) {
      const auto& e = *it;
      if (e.path().filename().string().starts_with(".")) continue;
      if (e.is_directory(ec))
        dirs.push_back(e);
      else if (has_extension(e.path(), extensions))
        files.push_back(e);
    }
    auto by_name = [](const auto& a, const auto& b) { return a.path().filename() < b.path().filename(); };
    std::sort(dirs.begin(), dirs.end(), by_name);
    std::sort(files.begin(), files.end(), by_name);

    ImGui::BeginChild("listing", ImVec2(0, -4.5f * em), true);
    for (const auto& d : dirs) {
      if (ImGui::Selectable(("[" + d.path().filename().string() + "]").c_str(), false,
                            ImGuiSelectableFlags_AllowDoubleClick) &&
          ImGui::IsMouseDoubleClicked(0)) {
        dir = d.path().string();
      }
    }
    for (const auto& f : files) {
      const std::string fname = f.path().filename().string();
      if (ImGui::Selectable(fname.c_str(), fname == name, ImGuiSelectableFlags_AllowDoubleClick)) {
        name = fname;
        if (ImGui::IsMouseDoubleClicked(0)) chosen = (fs::path(dir) / name).string();
      }
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-1);
    const bool enter = ImGui::InputText("##name", &name, ImGuiInputTextFlags_EnterReturnsTrue);
    if (!error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error.c_str());
    if (ImGui::Button(saving ? "Save" : "Open") || enter) {
      const fs::path p = resolve_path(name, dir);
      if (name.empty())
        error = "type a file name";
      else if (!saving && !fs::is_regular_file(p, ec))
        error = "no such file: " + p.string();
      else
        chosen = p.string();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
      visible = false;
      ImGui::CloseCurrentPopup();
    }
    if (!chosen.empty()) {
      visible = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  return chosen;
}

}  // namespace airr::ui
