#include "scene_json_environment.hpp"

#include <array>
#include <string>

#include "json_enum.hpp"

namespace airr {

using nlohmann::json;

inline constexpr std::array luminaire_shape_names{"rectangle", "disc"};

json pose_to_json(const pose& p) {
  return {{"center_mm", p.center_mm}, {"yaw_deg", p.yaw_deg}, {"pitch_deg", p.pitch_deg}, {"roll_deg", p.roll_deg}};
}

void read_pose(json_reader r, pose& p) {
  r.numbers("center_mm", p.center_mm);
  r.number("yaw_deg", p.yaw_deg);
  r.number("pitch_deg", p.pitch_deg);
  r.number("roll_deg", p.roll_deg);
  r.finish();
}

bool environment_written(const environment_params& e, json_form form) {
  return form == json_form::complete || e != environment_params{};
}

json environment_to_json(const environment_params& e) {
  json luminaires = json::array();
  for (const auto& l : e.luminaires) {
    luminaires.push_back({{"name", l.name},
                          {"shape", luminaire_shape_names[int(l.shape)]},
                          {"pose", pose_to_json(l.pose)},
                          {"width_mm", l.width_mm},
                          {"height_mm", l.height_mm},
                          {"luminance_cd_m2", l.luminance_cd_m2},
                          {"flux_lm", l.flux_lm}});
  }
  return {{"room", {{"luminance_cd_m2", e.room.luminance_cd_m2}, {"illuminance_lux", e.room.illuminance_lux}}},
          {"sun",
           {{"azimuth_deg", e.sun.azimuth_deg},
            {"elevation_deg", e.sun.elevation_deg},
            {"illuminance_lux", e.sun.illuminance_lux}}},
          {"luminaires", luminaires}};
}

static void read_luminaire(json_reader r, luminaire_params& l) {
  r.string("name", l.name);
  read_enum(r, "shape", l.shape, luminaire_shape_names);
  if (r.has("pose")) read_pose(r.child("pose"), l.pose);
  r.number("width_mm", l.width_mm);
  r.number("height_mm", l.height_mm);
  r.number("luminance_cd_m2", l.luminance_cd_m2);
  r.number("flux_lm", l.flux_lm);
  r.finish();
}

void read_environment(json_reader r, environment_params& e) {
  if (r.has("room")) {
    auto room = r.child("room");
    room.number("luminance_cd_m2", e.room.luminance_cd_m2);
    room.number("illuminance_lux", e.room.illuminance_lux);
    room.finish();
  }
  if (r.has("sun")) {
    auto sun = r.child("sun");
    sun.number("azimuth_deg", e.sun.azimuth_deg);
    sun.number("elevation_deg", e.sun.elevation_deg);
    sun.number("illuminance_lux", e.sun.illuminance_lux);
    sun.finish();
  }
  if (r.has("luminaires")) {
    const json& list = r.raw("luminaires");
    if (!list.is_array() || list.size() > std::size_t(max_luminaires)) {
      r.fail(r.field("luminaires"), "must be an array of at most " + std::to_string(max_luminaires) + " luminaires");
    }
    e.luminaires.assign(list.size(), luminaire_params{});
    for (std::size_t i = 0; i < list.size(); ++i) {
      read_luminaire(json_reader(list[i], r.origin(), r.field("luminaires") + "[" + std::to_string(i) + "]"),
                     e.luminaires[i]);
    }
  }
  r.finish();
}

}  // namespace airr
