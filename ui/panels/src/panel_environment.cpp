// The Layout panel's Environment section: the room around the device, the sun and the
// luminaires (spec section 11).
#include <numbers>
#include <optional>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "airr/ui/panels/panels.hpp"
#include "layout_rows.hpp"

namespace airr::ui {

namespace {

void sun_rows(sun_params& sun) {
  edit_number("sun", sun.illuminance_lux, 0, 100000, "lux", "%.0f",
              "the illuminance the sun makes on a plane facing it (clear noon about 100,000); 0: no sun",
              "environment.sun.illuminance_lux");
  if (sun.illuminance_lux <= 0) return;
  edit_number("sun azimuth", sun.azimuth_deg, -180, 180, "deg", "%.1f",
              "from +z (towards the observer) turning towards +x", "environment.sun.azimuth_deg");
  edit_number("sun elevation", sun.elevation_deg, 0.5, 90, "deg", "%.1f", "above the horizon",
              "environment.sun.elevation_deg");
  ImGui::Text("a %.2f deg disc of %.3g cd/m2", sun_angular_diameter_deg, sun_luminance(sun));
}

void luminaire_rows(std::vector<luminaire_params>& luminaires) {
  std::optional<std::size_t> remove;
  for (std::size_t i = 0; i < luminaires.size(); ++i) {
    luminaire_params& l = luminaires[i];
    const std::string key = "environment.luminaires." + std::to_string(i);
    ImGui::PushID(int(i));
    const std::string title = (l.name.empty() ? "luminaire " + std::to_string(i) : l.name) + "###luminaire";
    if (ImGui::TreeNode(title.c_str())) {
      ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
      ImGui::InputText("name", &l.name);
      int shape = int(l.shape);
      ImGui::SetNextItemWidth(-5.0f * ImGui::GetFontSize());
      if (ImGui::Combo("shape", &shape, "rectangle\0disc\0")) l.shape = luminaire_shape(shape);
      edit_number(l.shape == luminaire_shape::disc ? "diameter" : "width", l.width_mm, 10, 2000, "mm", "%.0f", nullptr,
                  key + ".width_mm");
      if (l.shape == luminaire_shape::rectangle)
        edit_number("height", l.height_mm, 10, 2000, "mm", "%.0f", nullptr, key + ".height_mm");
      // Given one way at a time: by its luminance, or by its flux.
      int by = l.flux_lm > 0 ? 1 : 0;
      ImGui::SetNextItemWidth(-8.0f * ImGui::GetFontSize());
      if (ImGui::Combo("given by", &by, "luminance\0luminous flux\0")) {
        const double luminance = luminaire_luminance(l);
        l.luminance_cd_m2 = l.flux_lm = 0;
        if (by == 1) {
          l.flux_lm = luminance * std::numbers::pi * luminaire_area_mm2(l) * 1e-6;
        } else {
          l.luminance_cd_m2 = luminance;
        }
      }
      if (by == 1) {
        edit_number("flux", l.flux_lm, 0, 10000, "lm", "%.0f", "emitted from its front, Lambertian", key + ".flux_lm");
      } else {
        edit_number("luminance", l.luminance_cd_m2, 0, 20000, "cd/m2", "%.0f", nullptr, key + ".luminance_cd_m2");
      }
      ImGui::Text("%.0f cd/m2 over %.0f cm2", luminaire_luminance(l), luminaire_area_mm2(l) / 100);
      edit_pose(l.pose, 3000, key);
      if (ImGui::Button("remove this luminaire")) remove = i;
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (remove) luminaires.erase(luminaires.begin() + std::ptrdiff_t(*remove));
  if (luminaires.size() < std::size_t(max_luminaires) && ImGui::Button("add a ceiling panel")) {
    // A 600 mm square panel 1 m above the aerial image, facing down.
    luminaire_params l;
    l.name = "ceiling panel " + std::to_string(luminaires.size());
    l.pose = {.center_mm = {0, 1000, 150}, .pitch_deg = -90};
    l.luminance_cd_m2 = 3000;
    luminaires.push_back(l);
  }
}

}  // namespace

void environment_section(studio& st) {
  scene& s = st.doc;
  room_params& room = s.environment.room;
  if (!in_cd_m2(s.source)) {
    ImGui::TextWrapped("Ambient light is in cd/m2 and lux: give the display's luminance (Display) first.");
  }
  ImGui::BeginDisabled(!in_cd_m2(s.source));
  // The room is given one way at a time: by lux, or by its own luminance.
  int by = room.illuminance_lux > 0 ? 1 : 0;
  ImGui::SetNextItemWidth(-8.0f * ImGui::GetFontSize());
  if (ImGui::Combo("room given by", &by, "luminance\0illuminance\0")) {
    if (by == 1 && room.luminance_cd_m2 > 0) {
      room.illuminance_lux = room.luminance_cd_m2 * std::numbers::pi;
      room.luminance_cd_m2 = 0;
    } else if (by == 0 && room.illuminance_lux > 0) {
      room.luminance_cd_m2 = room.illuminance_lux / std::numbers::pi;
      room.illuminance_lux = 0;
    }
  }
  if (by == 1) {
    edit_number("room", room.illuminance_lux, 0, 10000, "lux", "%.0f",
                "the illuminance the room makes on a horizontal plane (500 office, 10,000 shaded daylight); "
                "its surround's luminance is lux / pi. 0: a dark room",
                "environment.room.illuminance_lux");
  } else {
    edit_number("room", room.luminance_cd_m2, 0, 3000, "cd/m2", "%.0f",
                "the luminance of the uniform surround around the device. 0: a dark room",
                "environment.room.luminance_cd_m2");
  }
  if (room_luminance(room) > 0) {
    ImGui::Text("surround %.1f cd/m2, %.0f lux", room_luminance(room), room_luminance(room) * std::numbers::pi);
  }
  sun_rows(s.environment.sun);
  luminaire_rows(s.environment.luminaires);
  ImGui::EndDisabled();
}

}  // namespace airr::ui
