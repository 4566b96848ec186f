// The layout panel: every parameter of the scene as a slider plus a typed value, with units.
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/optics/assets.hpp"
#include "airr/optics/preset.hpp"
#include "airr/optics/retro_sinc_shift.hpp"
#include "airr/ui/studio.hpp"

namespace airr::ui {

namespace {

// One row: slider over [lo, hi], a typed field (may go beyond the slider), label with unit.
bool edit_number(const char* label, double& v, double lo, double hi, const char* unit, const char* fmt = "%.2f") {
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
  ImGui::Text("%s (%s)", label, unit);
  ImGui::PopID();
  return changed;
}

bool edit_int(const char* label, int& v, int lo, int hi, const char* unit) {
  double d = v;
  if (!edit_number(label, d, lo, hi, unit, "%.0f")) return false;
  v = int(std::lround(d));
  return true;
}

// A value that is either taken from the preset (unchecked) or set here.
void edit_optional(const char* label, std::optional<double>& v, double from_preset, double lo, double hi,
                   const char* unit, const char* fmt) {
  ImGui::PushID(label);
  bool set = v.has_value();
  if (ImGui::Checkbox("##set", &set)) v = set ? std::optional<double>(from_preset) : std::nullopt;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("checked: override the preset's value");
  ImGui::SameLine();
  if (v) {
    edit_number(label, *v, lo, hi, unit, fmt);
  } else {
    ImGui::TextDisabled("%s: from preset (%g %s at the chief ray)", label, from_preset, unit);
  }
  ImGui::PopID();
}

std::vector<std::string> shipped_presets() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(asset_dir() + "/presets", ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void model_section(studio& st) {
  auto& m = st.doc.retroreflector.model;
  int type = int(m.type);
  if (ImGui::BeginCombo("model", retro_model_type_names[type])) {
    for (int i = 0; i < int(retro_model_type_names.size()); ++i) {
      if (ImGui::Selectable(retro_model_type_names[i], i == type)) m.type = retro_model_type(i);
    }
    ImGui::EndCombo();
  }
  if (m.type == retro_model_type::ideal) {
    double mu = m.mu.value_or(1.0);
    if (edit_number("mu", mu, 0, 1, "reflectance", "%.3f")) m.mu = mu;
    return;
  }
  if (m.type == retro_model_type::sinc_shift) {
    static const std::vector<std::string> presets = shipped_presets();
    if (ImGui::BeginCombo("preset", m.preset.empty() ? "(none)" : m.preset.c_str())) {
      if (ImGui::Selectable("(none)", m.preset.empty())) m.preset.clear();
      for (const auto& p : presets) {
        if (ImGui::Selectable(p.c_str(), p == m.preset)) m.preset = p;
      }
      ImGui::EndCombo();
    }
    // The preset's values at the chief ray's incidence angle (= tilt), shown when not overridden.
    sinc_shift_params base;
    try {
      retro_model_params probe = m;
      probe.mu.reset();
      probe.a_per_mm.reset();
      probe.c_mm.reset();
      probe.reference_distance_mm.reset();
      if (!probe.preset.empty()) base = resolve_sinc_shift_params(probe, st.doc.base_dir);
    } catch (const std::exception&) {
    }
    const double tilt = std::abs(st.doc.retroreflector.tilt_deg);
    edit_optional("a", m.a_per_mm, interpolate_by_angle(base.theta_deg, base.a_per_mm, tilt), 0.1, 20, "1/mm", "%.4f");
    edit_optional("c", m.c_mm, base.c_mm, 0, 3, "mm", "%.4f");
    edit_optional("mu", m.mu, interpolate_by_angle(base.theta_deg, base.mu, tilt), 0, 1, "reflectance", "%.4f");
    edit_optional("R", m.reference_distance_mm, base.reference_distance_mm, 50, 1000, "mm", "%.0f");
    return;
  }
  edit_number("alpha surface", m.alpha_surface, 0, 0.5, "roughness", "%.4f");
  edit_number("alpha internal", m.alpha_internal, 0, 0.05, "roughness", "%.5f");
  edit_number("internal reflectance", m.internal_reflectance, 0, 1, "fraction", "%.3f");
  edit_number("eta", m.eta, 1, 2, "index", "%.4f");
  double mu = m.mu.value_or(1.0);
  if (edit_number("mu", mu, 0, 1, "weight", "%.3f")) m.mu = mu;
}

}  // namespace

void draw_layout_panel(studio& st) {
  ImGui::Begin("Layout");
  scene& s = st.doc;
  if (ImGui::CollapsingHeader("Arrangement", ImGuiTreeNodeFlags_DefaultOpen)) {
    edit_number("floating distance D", s.floating_distance_mm, 30, 400, "mm", "%.1f");
    edit_number("retroreflector tilt", s.retroreflector.tilt_deg, -45, 60, "deg", "%.1f");
    edit_number("retroreflector distance", s.retroreflector.distance_mm, 50, 400, "mm", "%.1f");
  }
  if (ImGui::CollapsingHeader("Source", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
    ImGui::InputText("image", &s.source.image);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("empty: uniform white; drop an image file on the window to use it");
    edit_number("width", s.source.width_mm, 1, 200, "mm", "%.1f");
    edit_number("height", s.source.height_mm, 1, 200, "mm", "%.1f");
    edit_number("intensity", s.source.intensity, 0, 100, "radiance", "%.2f");
    edit_number("offset x", s.source.offset_mm[0], -50, 50, "mm", "%.1f");
    edit_number("offset y", s.source.offset_mm[1], -50, 50, "mm", "%.1f");
    edit_number("offset z", s.source.offset_mm[2], -50, 50, "mm", "%.1f");
  }
  if (ImGui::CollapsingHeader("Half mirror", ImGuiTreeNodeFlags_DefaultOpen)) {
    edit_number("reflectance R", s.half_mirror.reflectance, 0, 1, "fraction", "%.3f");
    edit_number("transmittance T", s.half_mirror.transmittance, 0, 1, "fraction", "%.3f");
    edit_number("mirror width", s.half_mirror.width_mm, 10, 600, "mm", "%.0f");
    edit_number("mirror height", s.half_mirror.height_mm, 10, 600, "mm", "%.0f");
  }
  if (ImGui::CollapsingHeader("Retroreflector", ImGuiTreeNodeFlags_DefaultOpen)) {
    edit_number("sheet width", s.retroreflector.width_mm, 10, 600, "mm", "%.0f");
    edit_number("sheet height", s.retroreflector.height_mm, 10, 600, "mm", "%.0f");
    model_section(st);
  }
  if (ImGui::CollapsingHeader("Camera")) {
    edit_number("camera distance", s.camera.distance_mm, 50, 1000, "mm", "%.0f");
    edit_number("field of view", s.camera.fov_deg, 1, 60, "deg", "%.2f");
    edit_int("image width", s.camera.width, 16, 2048, "px");
    edit_int("image height", s.camera.height, 16, 2048, "px");
    double seed = double(s.seed);
    if (edit_number("seed", seed, 0, 1000, "", "%.0f")) s.seed = std::uint64_t(std::max(0.0, seed));
  }
  ImGui::End();
}

}  // namespace airr::ui
