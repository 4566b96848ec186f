#include "scene_json_polarization.hpp"

#include <array>
#include <string>

#include "json_enum.hpp"

namespace airr {

using nlohmann::json;

namespace {
constexpr std::array light_state_names{"unpolarized", "linear", "circular_positive", "circular_negative"};
constexpr std::array film_kind_names{"retarder", "polarizer"};
constexpr std::array part_face_names{"front", "back"};
constexpr std::array coating_kind_names{"uncoated", "partial_mirror", "anti_reflection"};

json coating_to_json(const coating_params& c) {
  json j = {{"coating", coating_kind_names[int(c.kind)]}};
  if (c.kind == coating_kind::partial_mirror) {
    j.update({{"rs", c.rs}, {"rp", c.rp}, {"ts", c.ts}, {"tp", c.tp}, {"phase_deg", c.phase_deg}});
  } else if (c.kind == coating_kind::anti_reflection) {
    j["residual"] = c.residual;
  }
  return j;
}

void read_coating(json_reader r, coating_params& c) {
  read_enum(r, "coating", c.kind, coating_kind_names);
  r.number("rs", c.rs);
  r.number("rp", c.rp);
  r.number("ts", c.ts);
  r.number("tp", c.tp);
  r.number("phase_deg", c.phase_deg);
  r.number("residual", c.residual);
  r.finish();
}
}  // namespace

json polarization_to_json(const source_polarization& p) {
  return {{"state", light_state_names[int(p.state)]}, {"angle_deg", p.angle_deg}};
}

void read_polarization(json_reader r, source_polarization& p) {
  read_enum(r, "state", p.state, light_state_names);
  r.number("angle_deg", p.angle_deg);
  r.finish();
}

json films_to_json(const std::vector<film_params>& films) {
  json list = json::array();
  for (const film_params& f : films) {
    json j = {{"kind", film_kind_names[int(f.kind)]}, {"face", part_face_names[int(f.face)]}, {"axis_deg", f.axis_deg}};
    if (f.kind == film_kind::retarder) {
      j["retardance_waves"] = f.retardance_waves;
      j["wavelength_nm"] = f.wavelength_nm;
    } else {
      j["pass_transmittance"] = f.pass_transmittance;
      j["block_transmittance"] = f.block_transmittance;
    }
    list.push_back(j);
  }
  return list;
}

void read_films(json_reader& part, std::vector<film_params>& films) {
  if (!part.has("films")) return;
  const json& list = part.raw("films");
  const std::string where = part.field("films");
  if (!list.is_array() || list.size() > std::size_t(max_films_per_part)) {
    part.fail(where, "must be an array of at most " + std::to_string(max_films_per_part) + " films");
  }
  films.assign(list.size(), film_params{});
  for (std::size_t i = 0; i < list.size(); ++i) {
    json_reader r(list[i], part.origin(), where + "[" + std::to_string(i) + "]");
    film_params& f = films[i];
    read_enum(r, "kind", f.kind, film_kind_names);
    read_enum(r, "face", f.face, part_face_names);
    f.axis_deg = r.number("axis_deg");  // a film without an axis is a slip, not a default
    r.number("retardance_waves", f.retardance_waves);
    r.number("wavelength_nm", f.wavelength_nm);
    r.number("pass_transmittance", f.pass_transmittance);
    r.number("block_transmittance", f.block_transmittance);
    r.finish();
  }
}

json reflective_polarizer_to_json(const reflective_polarizer_params& p) {
  return {{"axis_deg", p.axis_deg},
          {"pass_transmittance", p.pass_transmittance},
          {"pass_reflectance", p.pass_reflectance},
          {"block_reflectance", p.block_reflectance},
          {"block_transmittance", p.block_transmittance}};
}

void read_reflective_polarizer(json_reader r, reflective_polarizer_params& p) {
  p.axis_deg = r.number("axis_deg");
  r.number("pass_transmittance", p.pass_transmittance);
  r.number("pass_reflectance", p.pass_reflectance);
  r.number("block_reflectance", p.block_reflectance);
  r.number("block_transmittance", p.block_transmittance);
  r.finish();
}

json plate_to_json(const plate_params& p) {
  return {{"thickness_mm", p.thickness_mm},
          {"index", p.index},
          {"front", coating_to_json(p.front)},
          {"back", coating_to_json(p.back)}};
}

void read_plate(json_reader r, plate_params& p) {
  r.number("thickness_mm", p.thickness_mm);
  r.number("index", p.index);
  if (r.has("front")) read_coating(r.child("front"), p.front);
  if (r.has("back")) read_coating(r.child("back"), p.back);
  r.finish();
}

}  // namespace airr
