#include "gltf_layout_notes.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"

namespace airr::gltf {

using nlohmann::json;

namespace {

// Where an observer stands and looks, and how far ahead it aims.
struct view {
  glm::dvec3 position{0.0}, forward{0.0, 0.0, -1.0};
  double aim_mm = 300;
};

// A glTF camera looks along its node's -z.
view camera_view(const file& f, int node) {
  const glm::dmat4& w = f.world[std::size_t(node)];
  const glm::dvec3 back(w[2]);
  if (!(glm::length(back) > 0)) throw input_error(f.path + ": " + node_label(f, node) + ": degenerate transform");
  return {mm_per_metre * glm::dvec3(w[3]), -glm::normalize(back)};
}

// The scene extras' observer as placed in the layout (an orbit centres on the aerial image).
view extras_view(const json& doc, const std::string& path) {
  const json parts = {{"source", {{"pose", doc.at("source").at("pose")}}},
                      {"half_mirror", {{"pose", doc.at("half_mirror").at("pose")}}},
                      {"observer", doc.at("observer")}};
  const pinhole_camera c = make_camera(scene_from_json(parts, path));
  return {c.position, c.forward, c.target_distance};
}

// Unmoved: float precision (a round trip through Blender) moves a camera by far less than this.
bool same_view(const view& a, const view& b) {
  return glm::length(a.position - b.position) <= 0.01 && glm::length(a.forward - b.forward) <= 1e-5;
}

json look_at(const view& cam, json observer, double aim_mm) {
  const glm::dvec3 target = cam.position + aim_mm * cam.forward;
  observer["placement"] = "look_at";
  observer["position_mm"] = {cam.position.x, cam.position.y, cam.position.z};
  observer["look_at_mm"] = {target.x, target.y, target.z};
  return observer;
}

std::string length_text(double mm) {
  char text[32];
  if (mm >= 1000) {
    std::snprintf(text, sizeof text, "%.3g m", mm / 1000);
  } else {
    std::snprintf(text, sizeof text, "%.3g mm", mm);
  }
  return text;
}

// What a file k powers of ten too large (k < 0: too small) looks like.
std::string scale_reason(int k) {
  if (k == 3) return "the file looks drawn in millimetres";
  if (k == 2) return "the file looks drawn in centimetres";
  if (k == 1) return "the file looks ten times too large";
  char text[64];
  std::snprintf(text, sizeof text, "the file looks %.0f times too %s", std::pow(10.0, std::abs(k)),
                k > 0 ? "large" : "small");
  return text;
}

}  // namespace

void place_observer(const file& f, int node, const std::string& observer_source, gltf_layout& out) {
  json& doc = out.document;
  const std::string note = "note: " + f.path + ": observer: ";
  const bool in_extras = doc.contains("observer");
  if (node < 0) {
    out.notes.push_back(note + (in_extras ? "the scene extras' airr.observer (no node has the observer role)"
                                          : "the default (no observer node, none in the scene extras)"));
    return;
  }
  const std::string camera = node_label(f, node);
  if (observer_source == "extras") {
    if (!in_extras)
      throw input_error(f.path + ": scene extras airr.observer_source is \"extras\" but they hold no observer");
    out.notes.push_back(note + "the scene extras' airr.observer (their observer_source is \"extras\"); the " + camera +
                        " is not used");
    return;
  }
  const view cam = camera_view(f, node);
  if (in_extras) {
    const view was = extras_view(doc, f.path);
    if (same_view(cam, was)) {
      out.notes.push_back(note + "the scene extras' airr.observer, where the " + camera + " stands");
      return;
    }
    doc["observer"] = look_at(cam, doc["observer"], std::isfinite(was.aim_mm) && was.aim_mm > 0 ? was.aim_mm : 300);
    out.notes.push_back(note + "the " + camera +
                        ", moved from the scene extras' airr.observer (scene extras \"observer_source\": \"extras\" "
                        "would use those)");
  } else {
    doc["observer"] = look_at(cam, json::object(), 300);
    out.notes.push_back(note + "the " + camera + " (looking at a point 300 mm ahead)");
  }
  for (const char* field : {"observer.position_mm", "observer.look_at_mm", "observer:"}) {
    out.part_nodes.emplace_back(field, camera);
  }
}

std::string scale_warning(const json& doc) {
  constexpr double smallest_mm = 2, largest_mm = 2000, typical_mm = 300;
  double side = 0;
  std::string what;
  auto consider = [&](const json& part, const std::string& name) {
    const double w = part.value("width_mm", 0.0), h = part.value("height_mm", 0.0);
    if (std::max(w, h) <= side) return;
    side = std::max(w, h);
    what = name + " is " + length_text(side) + (w >= h ? " wide" : " high");
  };
  consider(doc.at("source"), "the display");
  consider(doc.at("half_mirror"), "the half mirror");
  for (const auto& sheet : doc.at("retroreflectors")) consider(sheet, "a retroreflector");
  if (side >= smallest_mm && side <= largest_mm) return "";
  // The power of ten that brings the largest side nearest a typical bench's.
  const int k = side > largest_mm ? std::max(1, int(std::lround(std::log10(side / typical_mm))))
                                  : std::min(-1, int(std::lround(std::log10(side / typical_mm))));
  char factor[32];
  std::snprintf(factor, sizeof factor, "%.10g", std::pow(10.0, -k));
  return what + " (glTF lengths are metres; a device's largest part measures 2 mm to 2 m): " + scale_reason(k) +
         "; scale it by " + factor + " (in Blender, which exports no unit scale: scale everything by " + factor +
         " about the origin, apply the scale, export again)";
}

}  // namespace airr::gltf
