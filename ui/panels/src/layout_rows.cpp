#include "layout_rows.hpp"

#include <algorithm>
#include <cmath>

#include <imgui.h>

namespace airr::ui {

namespace {
std::optional<design_pick> picked;
}  // namespace

bool edit_number(const char* label, double& v, double lo, double hi, const char* unit, const char* fmt,
                 const char* help, const std::string& key) {
  ImGui::PushID(label);
  const float w = ImGui::GetContentRegionAvail().x;
  bool changed = false;
  ImGui::SetNextItemWidth(0.36f * w);
  double clamped = std::clamp(v, lo, hi);
  if (ImGui::SliderScalar("##slider", ImGuiDataType_Double, &clamped, &lo, &hi, fmt)) {
    v = clamped;
    changed = true;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(0.20f * w);
  double typed = v;
  if (ImGui::InputDouble("##typed", &typed, 0, 0, fmt, ImGuiInputTextFlags_EnterReturnsTrue) && std::isfinite(typed)) {
    v = typed;
    changed = true;
  }
  ImGui::SameLine();
  if (unit && *unit) {
    ImGui::Text("%s (%s)", label, unit);
  } else {
    ImGui::TextUnformatted(label);
  }
  if (ImGui::IsItemHovered() && (help || !key.empty())) {
    const std::string menu = key.empty() ? "" : "right-click: optimise over " + key + " or add it as a tolerance";
    ImGui::SetTooltip("%s%s%s", help ? help : "", help && !menu.empty() ? "\n" : "", menu.c_str());
  }
  if (!key.empty() && ImGui::BeginPopupContextItem("##design")) {
    if (ImGui::MenuItem("Optimise over this value")) picked = design_pick{key, false};
    if (ImGui::MenuItem("Add as an assembly tolerance")) picked = design_pick{key, true};
    ImGui::EndPopup();
  }
  ImGui::PopID();
  return changed;
}

bool edit_int(const char* label, int& v, int lo, int hi, const char* unit) {
  double d = v;
  if (!edit_number(label, d, lo, hi, unit, "%.0f")) return false;
  v = int(std::lround(d));
  return true;
}

std::optional<design_pick> take_design_pick() {
  std::optional<design_pick> p = picked;
  picked.reset();
  return p;
}

// The pose rows of a part: centre and the three angles.
void edit_pose(pose& p, double reach_mm, const std::string& part) {
  static const char* axes[3] = {"centre x", "centre y", "centre z"};
  for (int i = 0; i < 3; ++i) {
    edit_number(axes[i], p.center_mm[i], -reach_mm, reach_mm, "mm", "%.1f", nullptr,
                part + ".pose.center_mm." + std::to_string(i));
  }
  edit_number("yaw", p.yaw_deg, -180, 180, "deg", "%.1f", "turns the part about the world's y axis",
              part + ".pose.yaw_deg");
  edit_number("pitch", p.pitch_deg, -180, 180, "deg", "%.1f", "raises the part's normal towards +y",
              part + ".pose.pitch_deg");
  edit_number("roll", p.roll_deg, -180, 180, "deg", "%.1f", "turns the part about its own normal",
              part + ".pose.roll_deg");
}

}  // namespace airr::ui
