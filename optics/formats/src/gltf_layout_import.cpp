#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "airr/core/error.hpp"
#include "airr/formats/gltf_layout.hpp"
#include "airr/layout/layout.hpp"
#include "gltf_layout_notes.hpp"
#include "gltf_read.hpp"

namespace airr {

using nlohmann::json;

bool is_gltf_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

namespace {

std::string where(const gltf::file& f, int node) { return f.path + ": " + gltf::node_label(f, node); }

// A flat part's rectangle from its node's own triangles, in world millimetres.
struct flat_part {
  pose p;
  double width = 0, height = 0;
};

flat_part flat_part_of(const gltf::file& f, int node, const std::string& role) {
  // Double precision throughout: a part's pose must survive a round trip to well under a micrometre.
  const glm::dmat4 world = gltf::world_mm(f, node);
  std::vector<glm::dvec3> points;
  glm::dvec3 sum(0.0);  // area-weighted normal, counter-clockwise seen from the front
  gltf::visit_node_primitives(f, node, world,
                              [&](const std::vector<glm::dvec3>& p, const std::vector<std::uint32_t>& t, int) {
                                for (std::size_t k = 0; k < t.size(); k += 3) {
                                  sum += glm::cross(p[t[k + 1]] - p[t[k]], p[t[k + 2]] - p[t[k]]);
                                  points.insert(points.end(), {p[t[k]], p[t[k + 1]], p[t[k + 2]]});
                                }
                              });
  if (points.empty()) throw input_error(where(f, node) + ": the " + role + " has no triangles");
  const double area2 = glm::length(sum);
  if (!(area2 > 1e-9)) throw input_error(where(f, node) + ": the " + role + " has no area (or faces both ways)");
  const glm::dvec3 n = sum / area2;
  const glm::dvec3 o = points.front();
  double extent = 0, off = 0;
  for (const auto& p : points) {
    extent = std::max(extent, glm::length(p - o));
    off = std::max(off, std::abs(glm::dot(p - o, n)));
  }
  if (off > 1e-3 + 1e-6 * extent) {
    char text[96];
    std::snprintf(text, sizeof text, "%.4g mm", off);
    throw input_error(where(f, node) + ": the " + role + " must be flat, but its vertices lie up to " + text +
                      " off their plane");
  }
  // The width axis: the node's x axis in the plane (its y axis when x is the normal).
  glm::dvec3 u = glm::dvec3(world[0]) - glm::dot(glm::dvec3(world[0]), n) * n;
  if (glm::length(u) < 1e-9 * glm::length(glm::dvec3(world[0]))) {
    u = glm::cross(glm::dvec3(world[1]), n);
  }
  if (!(glm::length(u) > 0)) throw input_error(where(f, node) + ": degenerate transform");
  u = glm::normalize(u);
  const glm::dvec3 v = glm::cross(n, u);
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& p : points) {
    const glm::dvec3 d = p - o;
    lo_u = std::min(lo_u, glm::dot(d, u));
    hi_u = std::max(hi_u, glm::dot(d, u));
    lo_v = std::min(lo_v, glm::dot(d, v));
    hi_v = std::max(hi_v, glm::dot(d, v));
  }
  flat_part out;
  out.width = hi_u - lo_u;
  out.height = hi_v - lo_v;
  out.p = pose_from_rotation(glm::dmat3(u, v, n), o + 0.5 * (lo_u + hi_u) * u + 0.5 * (lo_v + hi_v) * v);
  return out;
}

json pose_json(const pose& p) {
  return {{"center_mm", p.center_mm}, {"yaw_deg", p.yaw_deg}, {"pitch_deg", p.pitch_deg}, {"roll_deg", p.roll_deg}};
}

// The role's fields from extras (everything but the role), refusing geometry, which the mesh gives.
json fields_of(const gltf::file& f, int node) {
  json a = gltf::airr_extras(f, node);
  if (!a.is_object()) return json::object();
  a.erase("role");
  for (const char* key : {"width_mm", "height_mm", "pose", "mesh", "node"}) {
    if (a.contains(key)) {
      throw input_error(where(f, node) + ": " + gltf::airr_extras_name(f, node) + "." + key +
                        ": the geometry comes from the node's mesh");
    }
  }
  return a;
}

bool has_prop_geometry(const gltf::file& f, int node) {
  const auto& n = f.model.nodes[std::size_t(node)];
  if (n.mesh >= 0) return true;
  for (int c : n.children) {
    if (!gltf::is_part_role(gltf::node_role(f, c)) && has_prop_geometry(f, c)) return true;
  }
  return false;
}

// How a prop names its node: by name when that is unique, else by index.
std::string node_ref(const gltf::file& f, int node) {
  const std::string& name = f.model.nodes[std::size_t(node)].name;
  if (!name.empty() && name[0] != '#') {
    const auto& nodes = f.model.nodes;
    if (std::count_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.name == name; }) == 1) return name;
  }
  return "#" + std::to_string(node);
}

struct collected {
  std::vector<int> display, half_mirror, sheets, observer, props;
  std::vector<int> both_extras;  // nodes with airr extras of their own and on their mesh
};

void collect(const gltf::file& f, int node, bool inside_prop, collected& c, int depth) {
  if (depth > 256) throw input_error(where(f, node) + ": nodes nested too deep");
  const std::string role = gltf::node_role(f, node);
  if (!gltf::node_airr_extras(f, node).is_null() && !gltf::mesh_airr_extras(f, node).is_null()) {
    c.both_extras.push_back(node);
  }
  if (role == "display") c.display.push_back(node);
  if (role == "half_mirror") c.half_mirror.push_back(node);
  if (role == "retroreflector") c.sheets.push_back(node);
  if (role == "observer") c.observer.push_back(node);
  if (!gltf::is_part_role(role) && !inside_prop && (role == "prop" || has_prop_geometry(f, node))) {
    c.props.push_back(node);
    inside_prop = true;
  }
  if (gltf::is_part_role(role)) inside_prop = false;
  for (int child : f.model.nodes[std::size_t(node)].children) collect(f, child, inside_prop, c, depth + 1);
}

std::string labels(const gltf::file& f, const std::vector<int>& nodes) {
  std::string out;
  for (int k : nodes) out += (out.empty() ? "" : ", ") + gltf::node_label(f, k);
  return out;
}

// The default scene's airr extras (an object, or a string holding one), their keys checked.
json scene_airr(const gltf::file& f) {
  if (f.model.scenes.empty()) return json::object();
  const int sc =
      f.model.defaultScene >= 0 && std::size_t(f.model.defaultScene) < f.model.scenes.size() ? f.model.defaultScene : 0;
  json a = gltf::airr_in_extras(f.model.scenes[std::size_t(sc)].extras_json_string,
                                f.path + ": scene " + std::to_string(sc) + ": extras");
  if (a.is_null()) return json::object();
  for (const auto& [key, value] : a.items()) {
    if (key != "format" && key != "version" && key != "seed" && key != "observer" && key != "render" &&
        key != "observer_source") {
      throw input_error(f.path + ": scene extras airr." + key +
                        ": unknown key (seed, observer, observer_source, render)");
    }
  }
  const json source = a.value("observer_source", json("camera"));
  if (source != "camera" && source != "extras") {
    throw input_error(f.path + ": scene extras airr.observer_source: must be \"camera\" or \"extras\"");
  }
  return a;
}

void note_both_extras(const gltf::file& f, const std::vector<int>& nodes, std::vector<std::string>& notes) {
  for (int k : nodes) {
    notes.push_back("note: " + f.path + ": " + gltf::node_label(f, k) +
                    ": airr extras on both the node and its mesh: the node's are used, the mesh's ignored");
  }
}

}  // namespace

bool gltf_has_layout_roles(const std::string& path) {
  const gltf::file f = gltf::read(path);
  for (std::size_t k = 0; k < f.model.nodes.size(); ++k) {
    if (gltf::is_part_role(gltf::node_role(f, int(k)))) return true;
  }
  return false;
}

gltf_layout read_gltf_layout(const std::string& path) {
  const gltf::file f = gltf::read(path);
  collected c;
  for (int root : gltf::scene_roots(f)) collect(f, root, false, c, 0);
  auto need_one = [&](const std::vector<int>& nodes, const char* role) {
    if (nodes.empty()) {
      throw input_error(path + ": no node is the " + std::string(role) + " (extras {\"airr\": {\"role\": \"" + role +
                        "\"}} or a name beginning airr_" + role + ")");
    }
    if (nodes.size() > 1) throw input_error(path + ": more than one " + std::string(role) + ": " + labels(f, nodes));
  };
  need_one(c.display, "display");
  need_one(c.half_mirror, "half_mirror");
  if (c.sheets.empty()) {
    throw input_error(path +
                      ": no node is a retroreflector (extras {\"airr\": {\"role\": \"retroreflector\"}} or a "
                      "name beginning airr_retroreflector)");
  }
  if (c.observer.size() > 1) throw input_error(path + ": more than one observer: " + labels(f, c.observer));

  gltf_layout out;
  out.path = path;
  json& doc = out.document;
  doc = {{"format", "airr-scene"}, {"version", 2}};
  const json extras = scene_airr(f);
  for (const char* key : {"seed", "observer", "render"}) {
    if (extras.contains(key)) doc[key] = extras[key];
  }
  auto part = [&](int node, const char* role, const std::string& field) {
    const flat_part fp = flat_part_of(f, node, role);
    json j = fields_of(f, node);
    j["width_mm"] = fp.width;
    j["height_mm"] = fp.height;
    j["pose"] = pose_json(fp.p);
    out.part_nodes.emplace_back(field, gltf::node_label(f, node));
    return j;
  };
  json display = part(c.display.front(), "display", "source");
  if (display.contains("bezel_mm") && display["bezel_mm"].is_number()) {
    // The mesh is the whole panel; the scene's size is its emitting area.
    const double b = 2 * display["bezel_mm"].get<double>();
    const double w = display["width_mm"].get<double>() - b, h = display["height_mm"].get<double>() - b;
    if (!(w > 0) || !(h > 0)) {
      throw input_error(where(f, c.display.front()) + ": extras airr.bezel_mm leaves no emitting area");
    }
    display["width_mm"] = w;
    display["height_mm"] = h;
  }
  gltf::choose_display_image(f, c.display.front(), display, out.notes);
  doc["source"] = display;
  doc["half_mirror"] = part(c.half_mirror.front(), "half_mirror", "half_mirror");
  doc["retroreflectors"] = json::array();
  for (std::size_t i = 0; i < c.sheets.size(); ++i) {
    doc["retroreflectors"].push_back(part(c.sheets[i], "retroreflector", "retroreflectors[" + std::to_string(i) + "]"));
  }
  const std::string file_name = std::filesystem::path(path).filename().string();
  if (!c.props.empty()) {
    doc["props"] = json::array();
    for (int k : c.props) {
      json p = fields_of(f, k);
      if (!p.contains("name")) p["name"] = f.model.nodes[std::size_t(k)].name;
      if (!p.contains("surface")) p["surface"] = "material";
      p["mesh"] = file_name;
      p["node"] = node_ref(f, k);
      p["pose"] = pose_json(gltf::node_rigid_pose(f, k));
      out.part_nodes.emplace_back("props[" + std::to_string(doc["props"].size()) + "]", gltf::node_label(f, k));
      doc["props"].push_back(p);
    }
  }
  note_both_extras(f, c.both_extras, out.notes);
  gltf::place_observer(f, c.observer.empty() ? -1 : c.observer.front(), extras.value("observer_source", "camera"), out);
  out.scale_warning = gltf::scale_warning(doc);
  if (!out.scale_warning.empty()) out.notes.push_back("warning: " + path + ": " + out.scale_warning);
  return out;
}

json gltf_layout_document(const std::string& path) { return read_gltf_layout(path).document; }

std::string gltf_layout_error(const gltf_layout& layout, const std::string& message) {
  const std::string head = layout.path + ": ";
  std::string out = message;
  if (message.rfind(head, 0) == 0) {
    const std::string rest = message.substr(head.size());
    for (const auto& [field, node] : layout.part_nodes) {
      // The whole field name: "source" then "." or ":", never a longer name.
      const char next = rest.size() > field.size() ? rest[field.size()] : '\0';
      if (rest.rfind(field, 0) == 0 && !std::isalnum(static_cast<unsigned char>(next)) && next != '_') {
        out = head + node + ": " + rest;
        break;
      }
    }
  }
  if (!layout.scale_warning.empty()) out += "; " + layout.scale_warning;
  return out;
}

}  // namespace airr
