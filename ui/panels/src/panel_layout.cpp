// The layout panel: every field of the scene as a slider plus a typed value, with units. The
// retroreflector models' rows come from their field tables.
#include <algorithm>
#include <filesystem>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/core/assets.hpp"
#include "airr/formats/mesh_step.hpp"
#include "airr/formats/sheet_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/models/retro_model.hpp"
#include "airr/ui/panels/panels.hpp"
#include "layout_rows.hpp"
#include "polarization_rows.hpp"

namespace airr::ui {

namespace {

void edit_part_size(part_params& p, double max_mm, const std::string& part) {
  edit_number("width", p.width_mm, 1, max_mm, "mm", "%.1f", nullptr, part + ".width_mm");
  edit_number("height", p.height_mm, 1, max_mm, "mm", "%.1f", nullptr, part + ".height_mm");
}

std::vector<std::string> shipped_presets() { return shipped_json_names("presets"); }

// One model field as a row, driven by its description.
void edit_model_field(const model_field& f, retro_model_params& m, const model_values& v, const retro_model_kind& kind,
                      const studio& st, double theta_deg, const std::string& key) {
  ImGui::PushID(f.key.c_str());
  const double hi = f.slider_hi > 0 ? std::min(f.slider_hi, f.hi) : f.hi;
  switch (f.kind) {
    case field_kind::number: {
      double x = v.number(f.key);
      if (edit_number(f.key.c_str(), x, f.lo, hi, f.unit.c_str(), "%.4f", f.help.c_str(), key))
        set_model_value(m, f.key, x);
      break;
    }
    case field_kind::optional_number: {
      const std::optional<double> x = v.optional_number(f.key);
      // What the model makes of the value when unset (a preset's value at this angle), if it says.
      double derived = 0;
      bool has_derived = false;
      if (kind.derived) {
        if (const auto d = kind.derived(v, f.key, st.doc.base_dir, theta_deg)) {
          derived = *d;
          has_derived = true;
        }
      }
      bool set = x.has_value();
      if (ImGui::Checkbox("##set", &set)) {
        const double start = has_derived ? derived : (f.lo_open ? hi : f.lo);
        set_model_value(m, f.key, set ? std::optional<param_value>(start) : std::nullopt);
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("checked: set here; unchecked: %s", f.help.c_str());
      ImGui::SameLine();
      if (x) {
        double y = *x;
        if (edit_number(f.key.c_str(), y, f.lo, hi, f.unit.c_str(), "%.4f", f.help.c_str(), key))
          set_model_value(m, f.key, y);
      } else if (has_derived) {
        ImGui::TextDisabled("%s: unset (%g %s at the chief ray)", f.key.c_str(), derived, f.unit.c_str());
      } else {
        ImGui::TextDisabled("%s: unset", f.key.c_str());
      }
      break;
    }
    case field_kind::preset: {
      static const std::vector<std::string> presets = shipped_presets();
      const std::string now = v.text(f.key);
      if (ImGui::BeginCombo(f.key.c_str(), now.empty() ? "(none)" : now.c_str())) {
        if (ImGui::Selectable("(none)", now.empty())) set_model_value(m, f.key, std::nullopt);
        for (const auto& p : presets) {
          if (ImGui::Selectable(p.c_str(), p == now)) set_model_value(m, f.key, p);
        }
        ImGui::EndCombo();
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.help.c_str());
      break;
    }
    case field_kind::choice: {
      const std::string now = v.text(f.key);
      if (ImGui::BeginCombo(f.key.c_str(), now.c_str())) {
        for (const auto& c : f.choices) {
          if (ImGui::Selectable(c.c_str(), c == now)) set_model_value(m, f.key, c);
        }
        ImGui::EndCombo();
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.help.c_str());
      break;
    }
    case field_kind::text:
    case field_kind::path: {
      std::string text = v.text(f.key);
      ImGui::SetNextItemWidth(-8.0f * ImGui::GetFontSize());
      if (ImGui::InputText(f.key.c_str(), &text, ImGuiInputTextFlags_EnterReturnsTrue)) set_model_value(m, f.key, text);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", f.help.c_str());
      break;
    }
  }
  ImGui::PopID();
}

void model_section(studio& st, retroreflector_params& sheet, double theta_deg, const std::string& part) {
  retro_model_params& m = sheet.model;
  if (ImGui::BeginCombo("model", m.type.c_str())) {
    for (const retro_model_kind* k : retro_model_kinds()) {
      if (ImGui::Selectable(k->name.c_str(), k->name == m.type)) m = with_model_type(m, k->name);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", k->help.c_str());
    }
    ImGui::EndCombo();
  }
  // The explicit sheets that stand for real ones, their geometry at once (not the generic defaults).
  if (ImGui::BeginCombo("named sheet", "choose...")) {
    for (const std::string& name : shipped_sheet_names()) {
      if (!ImGui::Selectable(name.c_str(), false)) continue;
      try {
        const sheet_description named = load_named_sheet(name);
        use_sheet_model(sheet, named, st.doc.base_dir);
        st.status = part + ": the model of " + named.name;
      } catch (const std::exception& e) {
        st.status = e.what();
      }
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "the model of a shipped sheet (assets/sheets): RF-Ay-like and RF-AN-like prism sheets, a bead "
        "sheet, a tile sheet; --set %s.sheet=NAME",
        part.c_str());
  }
  const retro_model_kind& kind = find_retro_model_kind(m.type);
  const retro_model_params before = m;  // the rows read the values as they were this frame
  const model_values v(before, kind.fields, "model");
  for (const auto& f : kind.fields) edit_model_field(f, m, v, kind, st, theta_deg, part + ".model." + f.key);
}

void observer_section(scene& s) {
  observer_params& o = s.observer;
  int placement = int(o.placement);
  ImGui::RadioButton("orbit the aerial image", &placement, 0);
  ImGui::SameLine();
  ImGui::RadioButton("position and look-at", &placement, 1);
  if (placement != int(o.placement)) {
    // Keep the observer where it is when switching.
    const glm::dvec3 p = observer_position(s), t = observer_target(s), a = aerial_image_center(s);
    o.position_mm = {p.x, p.y, p.z};
    o.look_at_mm = {t.x, t.y, t.z};
    if (placement == 0) {
      const glm::dvec3 d = p - a;
      o.distance_mm = glm::length(d);
      o.elevation_deg = degrees(std::asin(std::clamp(d.y / o.distance_mm, -1.0, 1.0)));
      o.azimuth_deg = degrees(std::atan2(d.x, d.z));
    }
    o.placement = observer_placement(placement);
  }
  if (o.placement == observer_placement::orbit) {
    edit_number("azimuth", o.azimuth_deg, -90, 90, "deg", "%.1f", "from +z towards +x, about the aerial image",
                "observer.azimuth_deg");
    edit_number("elevation", o.elevation_deg, -60, 60, "deg", "%.1f", "towards +y, about the aerial image",
                "observer.elevation_deg");
    edit_number("distance", o.distance_mm, 50, 2000, "mm", "%.0f", "from the aerial image's centre",
                "observer.distance_mm");
  } else {
    static const char* p[3] = {"position x", "position y", "position z"};
    static const char* t[3] = {"look at x", "look at y", "look at z"};
    for (int i = 0; i < 3; ++i) edit_number(p[i], o.position_mm[i], -2000, 2000, "mm", "%.1f");
    for (int i = 0; i < 3; ++i) edit_number(t[i], o.look_at_mm[i], -2000, 2000, "mm", "%.1f");
  }
  int lens = int(o.lens);
  ImGui::RadioButton("pinhole", &lens, 0);
  ImGui::SameLine();
  ImGui::RadioButton("thin lens", &lens, 1);
  o.lens = observer_lens(lens);
  if (o.lens == observer_lens::thin_lens) {
    edit_number("focal length", o.focal_length_mm, 4, 300, "mm", "%.1f");
    edit_number("f-number", o.f_number, 0.5, 32, "", "%.2f", "aperture diameter = focal length / f-number");
    bool on_image = !o.focus_distance_mm;
    if (ImGui::Checkbox("focus on the aerial image", &on_image)) {
      o.focus_distance_mm = on_image ? std::nullopt : std::optional<double>(make_camera(s).target_distance);
    }
    if (o.focus_distance_mm) edit_number("focus distance", *o.focus_distance_mm, 10, 3000, "mm", "%.0f");
  }
  if (ImGui::Button("camera of the paper")) apply_observer_preset(s, observer_preset::paper_camera);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("50 mm lens at f/4, 300 mm from the aerial image, focused on it");
  ImGui::SameLine();
  if (ImGui::Button("eye")) apply_observer_preset(s, observer_preset::eye);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a 4 mm pupil focused on the aerial image");
  edit_number("field of view", o.fov_deg, 1, 120, "deg", "%.2f", "vertical");
  if (ImGui::Button("frame the aerial image")) o.fov_deg = std::round(fov_for_aerial_image(s) * 100) / 100;
  ImGui::SameLine();
  if (ImGui::Button("frame the whole device")) o.fov_deg = std::round(fov_for_whole_device(s) * 100) / 100;
  edit_int("image width", o.width, 16, 2048, "px");
  edit_int("image height", o.height, 16, 2048, "px");
  ImGui::Text("%.4f mm per pixel on the aerial image", make_camera(s).mm_per_pixel);
}

// The props: each with its visibility, name, surface, albedo, scale and pose; add and remove.
void props_section(studio& st) {
  scene& s = st.doc;
  if (s.props.empty()) ImGui::TextDisabled("none: drop a glTF or STEP model on the window, or add one");
  std::optional<std::size_t> remove;
  for (std::size_t i = 0; i < s.props.size(); ++i) {
    prop_params& p = s.props[i];
    ImGui::PushID(int(i));
    ImGui::Checkbox("##visible", &p.visible);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("visible: a hidden prop takes no part in renders or analyses");
    ImGui::SameLine();
    const std::string title = (p.name.empty() ? "prop " + std::to_string(i) : p.name) + "###prop";
    if (ImGui::TreeNode(title.c_str())) {
      ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
      ImGui::InputText("name", &p.name);
      ImGui::TextDisabled("%s%s%s", std::filesystem::path(p.mesh).filename().string().c_str(),
                          p.node.empty() ? "" : ", node ", p.node.c_str());
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.mesh.c_str());
      int surface = int(p.surface);
      ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
      if (ImGui::Combo("surface", &surface, prop_surface_names, IM_ARRAYSIZE(prop_surface_names))) {
        p.surface = prop_surface(surface);
      }
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("absorber: black; diffuse: Lambertian; mirror: specular; material: the glTF materials");
      }
      if (p.surface == prop_surface::diffuse || p.surface == prop_surface::mirror) {
        float c[3] = {float(p.albedo[0]), float(p.albedo[1]), float(p.albedo[2])};
        if (ImGui::ColorEdit3(p.surface == prop_surface::mirror ? "reflectance" : "albedo", c,
                              ImGuiColorEditFlags_Float)) {
          for (int k = 0; k < 3; ++k) p.albedo[std::size_t(k)] = std::clamp(double(c[k]), 0.0, 1.0);
        }
      }
      edit_number("scale", p.scale, 0.01, 10, "", "%.3f", "on top of the file's unit to millimetres");
      if (is_step_path(p.mesh)) {
        edit_number("tessellation", p.tessellation_mm, 0.001, 5, "mm", "%.3f",
                    "the farthest a triangle may stray from the CAD surface it stands for");
      }
      edit_pose(p.pose, 1000, "props." + std::to_string(i));
      if (ImGui::Button("remove this prop")) remove = i;
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (remove) s.props.erase(s.props.begin() + std::ptrdiff_t(*remove));
  if (s.props.size() < std::size_t(max_props) && ImGui::Button("add a prop (glTF, STEP)...")) {
    st.dialog.request(file_purpose::add_prop, false, "Add a glTF or STEP model as a prop", st.settings.last_dir,
                      {".glb", ".gltf", ".step", ".stp"});
  }
}

}  // namespace

void draw_layout_panel(studio& st) {
  ImGui::Begin("Layout");
  scene& s = st.doc;
  st.regions.erase("button_add_second_sheet");  // drawn again below when it is offered
  if (ImGui::CollapsingHeader("Arrangement", ImGuiTreeNodeFlags_DefaultOpen)) {
    double d = floating_distance(s);
    if (edit_number("floating distance D", d, 30, 400, "mm", "%.1f",
                    "half mirror centre to aerial image centre; moves the display", "floating_distance_mm") &&
        d > 0) {
      try {
        set_floating_distance(s, d);
      } catch (const std::exception&) {
      }
    }
    edit_number("retroreflector tilt", s.sheet().pose.pitch_deg, -45, 60, "deg", "%.1f", "the first sheet's pitch",
                "tilt_deg");
    const glm::dvec3 a = aerial_image_center(s);
    ImGui::Text("aerial image at (%.1f, %.1f, %.1f) mm", a.x + 0.0, a.y + 0.0, a.z + 0.0);  // + 0: no "-0.0"
  }
  if (ImGui::CollapsingHeader("Display")) {
    ImGui::PushID("display");
    ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
    ImGui::InputText("image", &s.source.image);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("empty: uniform white; drop an image file on the window to use it");
    edit_part_size(s.source, 300, "source");
    edit_number("luminance", s.source.luminance_cd_m2, 0, 2000, "cd/m2", "%.0f",
                "the display's white, face on; images and readouts in cd/m2. 0: relative units (intensity)",
                "source.luminance_cd_m2");
    ImGui::BeginDisabled(in_cd_m2(s.source));
    edit_number("intensity", s.source.intensity, 0, 100, "radiance", "%.2f", "relative units, without a luminance");
    ImGui::EndDisabled();
    edit_number("bezel", s.source.bezel_mm, 0, 50, "mm", "%.1f", "black border around the emitting area");
    ImGui::SetNextItemWidth(-8.0f * ImGui::GetFontSize());
    ImGui::InputText("emission profile", &s.source.emission_profile);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("CSV angle_deg,relative_luminance; empty: Lambertian (assets/displays/lcd_typical.csv)");
    }
    edit_pose(s.source.pose, 500, "source");
    display_light_rows(s.source.polarization);
    if (ImGui::TreeNode("films on the display")) {
      film_rows(s.source.films, "source");
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (ImGui::CollapsingHeader("Half mirror")) {
    ImGui::PushID("mirror");
    half_mirror_rows(s.half_mirror);
    edit_part_size(s.half_mirror, 1000, "half_mirror");
    edit_pose(s.half_mirror.pose, 500, "half_mirror");
    if (ImGui::TreeNode("films on the half mirror")) {
      film_rows(s.half_mirror.films, "half_mirror");
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (ImGui::CollapsingHeader("Retroreflectors", ImGuiTreeNodeFlags_DefaultOpen)) {
    std::optional<std::size_t> remove;
    for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
      ImGui::PushID(int(i));
      const std::string title = "sheet " + std::to_string(i) + (i == 0 ? " (tilt, PSF, sweeps, fit)" : "");
      if (ImGui::TreeNodeEx(title.c_str(), i == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
        retroreflector_params& r = s.retroreflectors[i];
        const double theta = polar_angle_deg(to_local(
            retroreflector_frame(s, i), glm::normalize(aerial_image_center(s) - retroreflector_frame(s, i).center)));
        const std::string part = "retroreflectors." + std::to_string(i);
        model_section(st, r, theta, part);
        edit_part_size(r, 1000, part);
        edit_pose(r.pose, 500, part);
        if (ImGui::TreeNodeEx("films on the sheet", r.films.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen)) {
          film_rows(r.films, part);
          ImGui::TreePop();
        }
        if (s.retroreflectors.size() > 1 && ImGui::Button("remove this sheet")) remove = i;
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    if (remove) s.retroreflectors.erase(s.retroreflectors.begin() + std::ptrdiff_t(*remove));
    // Offered while the layout has one sheet (a second one goes across the half mirror).
    bool add_second = false;
    if (s.retroreflectors.size() == 1) {
      add_second = ImGui::Button("add the second sheet");
      const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
      st.regions["button_add_second_sheet"] = {a.x, a.y, b.x, b.y};
    }
    if (add_second) {
      // The common second sheet: across the half mirror from the display, facing it, so that the
      // display's light reaches it through the half mirror and returns by reflection.
      retroreflector_params r = s.sheet();
      const glm::dvec3 hm = half_mirror_frame(s).center, src = source_frame(s).center;
      const glm::dvec3 dir = glm::normalize(hm - src);
      const glm::dvec3 c = hm + dir * glm::length(retroreflector_frame(s).center - hm);
      r.pose = {};
      r.pose.center_mm = {c.x, c.y, c.z};
      r.pose.pitch_deg = degrees(std::asin(std::clamp(-dir.y, -1.0, 1.0)));
      r.pose.yaw_deg = std::hypot(dir.x, dir.z) < 1e-9 ? 0.0 : degrees(std::atan2(-dir.x, -dir.z));
      s.retroreflectors.push_back(r);
    }
  }
  if (ImGui::CollapsingHeader("Props")) {
    ImGui::PushID("props");
    props_section(st);
    ImGui::PopID();
  }
  // Open from the start when the layout has ambient light, so that it is seen.
  if (ImGui::CollapsingHeader("Environment",
                              has_ambient_light(st.doc.environment) ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    ImGui::PushID("environment");
    environment_section(st);
    ImGui::PopID();
  }
  if (ImGui::CollapsingHeader("Observer")) {
    ImGui::PushID("observer");
    observer_section(s);
    analyzer_row(s.observer);
    double seed = double(s.seed);
    if (edit_number("seed", seed, 0, 1000, "", "%.0f")) s.seed = std::uint64_t(std::max(0.0, seed));
    ImGui::PopID();
  }
  ImGui::End();
  if (const std::optional<design_pick> pick = take_design_pick()) add_design_pick(st, pick->key, pick->tolerance);
}

}  // namespace airr::ui
