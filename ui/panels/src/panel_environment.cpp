// The Layout panel's Environment section: the room around the device (spec section 11).
#include <numbers>

#include <imgui.h>

#include "airr/ui/panels/panels.hpp"
#include "layout_rows.hpp"

namespace airr::ui {

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
  if (has_ambient_light(s.environment)) {
    ImGui::Text("surround %.1f cd/m2, %.0f lux", room_luminance(room), room_luminance(room) * std::numbers::pi);
  }
  ImGui::EndDisabled();
}

}  // namespace airr::ui
