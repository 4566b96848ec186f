#include "polarization_rows.hpp"

#include <imgui.h>

#include "layout_rows.hpp"

namespace airr::ui {

namespace {

// An enumeration as a combo over its names; true when changed.
template <class Enum, std::size_t N>
bool edit_choice(const char* label, Enum& value, const char* const (&names)[N]) {
  int i = int(value);
  if (!ImGui::Combo(label, &i, names, int(N))) return false;
  value = Enum(i);
  return true;
}

void coating_rows(const char* face, coating_params& c, const std::string& key) {
  ImGui::PushID(face);
  static const char* const kinds[] = {"uncoated (Fresnel)", "partial mirror", "anti-reflection"};
  edit_choice((std::string(face) + " face").c_str(), c.kind, kinds);
  if (c.kind == coating_kind::partial_mirror) {
    edit_number("R of s light", c.rs, 0, 1, "", "%.3f", nullptr, key + ".rs");
    edit_number("R of p light", c.rp, 0, 1, "", "%.3f", nullptr, key + ".rp");
    edit_number("T of s light", c.ts, 0, 1, "", "%.3f", nullptr, key + ".ts");
    edit_number("T of p light", c.tp, 0, 1, "", "%.3f", nullptr, key + ".tp");
    edit_number("phase of p against s", c.phase_deg, -180, 180, "deg", "%.1f", "beyond an ideal mirror's",
                key + ".phase_deg");
  } else if (c.kind == coating_kind::anti_reflection) {
    edit_number("residual reflectance", c.residual, 0, 0.05, "", "%.4f", nullptr, key + ".residual");
  }
  ImGui::PopID();
}

}  // namespace

void display_light_rows(source_polarization& light) {
  static const char* const states[] = {"unpolarized", "linear (LCD)", "circular, S3 > 0 (OLED)",
                                       "circular, S3 < 0 (OLED)"};
  edit_choice("light", light.state, states);
  if (light.state == light_state::linear) {
    edit_number("polarization angle", light.angle_deg, -90, 90, "deg", "%.1f",
                "the field's axis, from the display's width towards its height", "source.polarization.angle_deg");
  }
}

void half_mirror_rows(half_mirror_params& hm) {
  static const char* const kinds[] = {"half mirror (thin)", "reflective polarizer", "glass plate"};
  edit_choice("kind", hm.kind, kinds);
  if (hm.kind == half_mirror_kind::half_mirror) {
    edit_number("reflectance R", hm.reflectance, 0, 1, "fraction", "%.3f", nullptr, "half_mirror.reflectance");
    edit_number("transmittance T", hm.transmittance, 0, 1, "fraction", "%.3f", nullptr, "half_mirror.transmittance");
    return;
  }
  if (hm.kind == half_mirror_kind::reflective_polarizer) {
    reflective_polarizer_params& p = hm.polarizer;
    edit_number("pass axis", p.axis_deg, -90, 90, "deg", "%.1f", "from the mirror's width towards its height",
                "half_mirror.polarizer.axis_deg");
    edit_number("pass: transmitted", p.pass_transmittance, 0, 1, "", "%.3f", nullptr,
                "half_mirror.polarizer.pass_transmittance");
    edit_number("pass: reflected", p.pass_reflectance, 0, 1, "", "%.3f", nullptr,
                "half_mirror.polarizer.pass_reflectance");
    edit_number("block: reflected", p.block_reflectance, 0, 1, "", "%.3f", nullptr,
                "half_mirror.polarizer.block_reflectance");
    edit_number("block: transmitted", p.block_transmittance, 0, 1, "", "%.3f", nullptr,
                "half_mirror.polarizer.block_transmittance");
  } else {
    plate_params& p = hm.plate;
    edit_number("thickness", p.thickness_mm, 0.1, 20, "mm", "%.2f", "its pose is its mid-plane's",
                "half_mirror.plate.thickness_mm");
    edit_number("index", p.index, 1, 2.5, "", "%.3f", nullptr, "half_mirror.plate.index");
    coating_rows("front", p.front, "half_mirror.plate.front");
    coating_rows("back", p.back, "half_mirror.plate.back");
  }
  derive_half_mirror_light(hm);
  ImGui::Text("unpolarized light: R %.3f, T %.3f%s", hm.reflectance, hm.transmittance,
              hm.kind == half_mirror_kind::plate ? " (main image, 45 deg on the back face)" : "");
}

void film_rows(std::vector<film_params>& films, const std::string& part) {
  std::size_t remove = films.size();
  for (std::size_t i = 0; i < films.size(); ++i) {
    film_params& f = films[i];
    ImGui::PushID(int(i));
    const std::string key = part + ".films." + std::to_string(i);
    static const char* const kinds[] = {"retarder film", "polarizer film"};
    static const char* const faces[] = {"front face", "back face"};
    edit_choice("film", f.kind, kinds);
    edit_choice("on", f.face, faces);
    edit_number(f.kind == film_kind::retarder ? "fast axis" : "pass axis", f.axis_deg, -90, 90, "deg", "%.1f",
                "from the part's width towards its height", key + ".axis_deg");
    if (f.kind == film_kind::retarder) {
      edit_number("retardance", f.retardance_waves, 0, 1, "waves", "%.3f", "0.25: a quarter-wave film",
                  key + ".retardance_waves");
      edit_number("design wavelength", f.wavelength_nm, 400, 700, "nm", "%.0f", nullptr, key + ".wavelength_nm");
    } else {
      edit_number("passed along the axis", f.pass_transmittance, 0, 1, "", "%.3f", nullptr,
                  key + ".pass_transmittance");
      edit_number("passed across it", f.block_transmittance, 0, 0.1, "", "%.4f", nullptr, key + ".block_transmittance");
    }
    if (ImGui::SmallButton("take the film off")) remove = i;
    ImGui::Separator();
    ImGui::PopID();
  }
  if (remove < films.size()) films.erase(films.begin() + std::ptrdiff_t(remove));
  if (films.size() < std::size_t(max_films_per_part)) {
    if (ImGui::SmallButton("lay a quarter-wave film")) films.push_back(film_params{});
    ImGui::SameLine();
    if (ImGui::SmallButton("lay a polarizer film")) films.push_back(film_params{.kind = film_kind::polarizer});
  }
}

void analyzer_row(observer_params& o) {
  bool on = o.analyzer_deg.has_value();
  if (ImGui::Checkbox("polarizer before the observer", &on)) o.analyzer_deg = on ? std::optional(0.0) : std::nullopt;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a camera's polarizer, or polarized sunglasses");
  if (o.analyzer_deg) {
    edit_number("its pass axis", *o.analyzer_deg, -90, 90, "deg", "%.1f", "from the image's right towards its up",
                "observer.analyzer_deg");
  }
}

}  // namespace airr::ui
