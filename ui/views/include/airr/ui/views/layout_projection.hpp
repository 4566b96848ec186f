#pragma once
// What the layout view's side and top projections show, worked out apart from drawing so that a
// test can measure it: the map that fits the device into a canvas, the parts' outlines and drag
// handles on screen, and where each label goes (clear of the other labels, the outlines, the
// handles and the scale bar).
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <imgui.h>

#include "airr/core/geometry.hpp"
#include "airr/core/mesh.hpp"
#include "airr/layout/scene.hpp"
#include "airr/ui/views/label_placement.hpp"

namespace airr::ui {

enum class projection { side, top };

// World (mm) to screen for one projection: z runs right; y (side) or x (top) runs up.
struct view_map {
  projection proj = projection::side;
  ImVec2 origin;  // screen position of the world origin
  float scale;    // pixels per mm
  glm::dvec2 flat(const glm::dvec3& p) const { return {p.z, proj == projection::side ? p.y : p.x}; }
  ImVec2 to_screen(const glm::dvec3& p) const {
    const glm::dvec2 f = flat(p);
    return ImVec2(origin.x + float(f.x) * scale, origin.y - float(f.y) * scale);
  }
  // The mouse position as (horizontal, vertical) world coordinates of the projection.
  glm::dvec2 to_flat(ImVec2 q) const { return {(q.x - origin.x) / scale, (origin.y - q.y) / scale}; }
};

// Where a part's turning handle sits: its top edge's middle in the side view (pitch), its right
// edge's middle in the top view (yaw).
inline glm::dvec3 turn_handle_point(projection proj, const part_frame& f) {
  return proj == projection::side ? f.center + 0.5 * f.height * f.v : f.center + 0.5 * f.width * f.u;
}
// A handle's radius, drawn 1.3 times as large while hovered or dragged.
inline float handle_radius(float font_size) { return 0.42f * font_size; }

struct part_style {
  const char* name;
  ImU32 colour;
  float width;  // in line widths
};

struct view_text {
  std::string text;
  glm::vec2 anchor{0.0f};
  placed_label place;
};

struct projection_view {
  view_map map;
  float line_width = 1;
  std::vector<std::pair<part_frame, part_style>> parts;  // the display's panel, the half mirror, the sheets
  std::vector<std::pair<std::size_t, std::array<glm::dvec3, 8>>> boxes;  // visible props' boxes, by index
  part_frame aerial, emitting;                                           // the aerial image, the display's area
  glm::dvec3 eye{0.0};
  std::vector<screen_segment> outlines;  // every part's, prop box's and the aerial image's edges
  std::vector<view_text> labels;
  std::vector<screen_rect> handles;  // the drag handles' squares, at their largest
  glm::vec2 scale_bar{0.0f};         // where the 50 mm bar starts; its text follows it
  std::string scale_text;
  screen_rect scale_box;  // the bar and its text
};

using text_size_fn = std::function<glm::vec2(const std::string&)>;

// `frozen`: the map a drag keeps (the view then does not refit).
projection_view compute_projection(const scene& s, const std::vector<mesh_bounds>& prop_bounds, projection proj,
                                   ImVec2 canvas0, ImVec2 canvas, float font_size, const text_size_fn& text_size,
                                   const std::optional<view_map>& frozen = std::nullopt);

}  // namespace airr::ui
