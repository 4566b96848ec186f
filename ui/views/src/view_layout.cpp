// The layout view: the device drawn to scale in two projections, side (y-z) and top (x-z), beside
// a 3D view (view_3d.cpp), with
// the props' boxes, the aerial image where it forms, the observer's sight lines and the chief ray, and handles that
// pose every part: move (centre), rotate (pitch in the side view, yaw in the top view), the
// floating distance (the aerial image's handle) and the observer (orbit or position).
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>

#include "airr/core/geometry.hpp"
#include "airr/layout/layout.hpp"
#include "airr/ui/views/layout_projection.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

namespace {

double round1(double v) { return std::round(v * 10) / 10; }

// A draggable circle; returns the mouse position (projection coordinates) while dragged.
std::optional<glm::dvec2> handle(const std::string& id, ImVec2 at, ImU32 colour, const view_map& m,
                                 const std::string& tip, bool& active_any) {
  const float r = handle_radius(ImGui::GetFontSize());
  ImGui::SetCursorScreenPos(ImVec2(at.x - r, at.y - r));
  ImGui::InvisibleButton(id.c_str(), ImVec2(2 * r, 2 * r));
  const bool active = ImGui::IsItemActive(), hovered = ImGui::IsItemHovered();
  active_any = active_any || active;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddCircleFilled(at, r * (hovered || active ? 1.3f : 1.0f), colour);
  dl->AddCircle(at, r * (hovered || active ? 1.3f : 1.0f), IM_COL32(255, 255, 255, 200));
  if (hovered || active) ImGui::SetTooltip("%s", tip.c_str());
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) return m.to_flat(ImGui::GetIO().MousePos);
  return std::nullopt;
}

// Moves a pose's centre to the dragged position in the projection's plane.
void move_center(pose& p, const view_map& m, const glm::dvec2& w) {
  p.center_mm[2] = round1(w.x);
  p.center_mm[m.proj == projection::side ? 1 : 0] = round1(w.y);
}

// Sets pitch (side) or yaw (top) from a handle dragged around the part's centre. The side handle
// sits on +v (the part's top edge), the top handle on +u (its right edge).
void rotate(pose& p, const view_map& m, const glm::dvec3& center, const glm::dvec2& w) {
  const glm::dvec2 c = m.flat(center);
  const double dz = w.x - c.x, dv = w.y - c.y;
  if (m.proj == projection::side) {
    p.pitch_deg = std::clamp(round1(degrees(std::atan2(-dz, dv))), -180.0, 180.0);  // v = (., cos p, -sin p)
  } else {
    p.yaw_deg = std::clamp(round1(degrees(std::atan2(-dz, dv))), -180.0, 180.0);  // u = (cos y, 0, -sin y)
  }
}

void draw_projection(studio& st, projection proj, ImVec2 canvas0, ImVec2 canvas, bool& active_any,
                     std::optional<view_map>& frozen) {
  scene& s = st.doc;
  const projection_view v = compute_projection(
      s, st.prop_bounds, proj, canvas0, canvas, ImGui::GetFontSize(),
      [](const std::string& t) {
        const ImVec2 z = ImGui::CalcTextSize(t.c_str());
        return glm::vec2(z.x, z.y);
      },
      frozen);
  const view_map& m = v.map;
  const part_frame &hm = v.parts[0].first, &src = v.parts[1].first, &aerial = v.aerial;
  const glm::dvec3 eye = v.eye;

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(canvas0, ImVec2(canvas0.x + canvas.x, canvas0.y + canvas.y), true);
  dl->AddRectFilled(canvas0, ImVec2(canvas0.x + canvas.x, canvas0.y + canvas.y), IM_COL32(24, 26, 30, 255));
  const float lw = v.line_width;
  auto seg = [&](const glm::dvec3& p, const glm::dvec3& q, ImU32 c, float w) {
    dl->AddLine(m.to_screen(p), m.to_screen(q), c, w);
  };
  auto outline = [&](const part_frame& f, ImU32 c, float w) {
    const auto k = corners(f);
    dl->AddQuad(m.to_screen(k[0]), m.to_screen(k[1]), m.to_screen(k[2]), m.to_screen(k[3]), c, w);
  };

  // Sight lines from the observer to the aerial image's corners, then the chief ray's ideal path.
  for (const auto& c : corners(aerial)) seg(eye, c, IM_COL32(150, 150, 150, 110), 0.7f * lw);
  const auto path = ideal_light_path(s, aerial.center);
  for (std::size_t i = 1; i < path.size(); ++i) seg(path[i - 1], path[i], IM_COL32(255, 210, 90, 220), lw);

  const ImU32 prop_colour = IM_COL32(230, 160, 80, 200);
  for (const auto& [i, k] : v.boxes) {
    for (int a = 0; a < 8; ++a) {
      for (int bit : {1, 2, 4}) {
        if (!(a & bit)) seg(k[std::size_t(a)], k[std::size_t(a | bit)], prop_colour, 0.8f * lw);
      }
    }
  }
  for (const auto& [f, style] : v.parts) outline(f, style.colour, style.width * lw);
  // The luminaires (Environment), where the view reaches them: a disc as a polygon.
  for (const luminaire_params& l : s.environment.luminaires) {
    const std::vector<glm::dvec3> edge = luminaire_outline(l);
    for (std::size_t k = 0; k < edge.size(); ++k)
      seg(edge[k], edge[(k + 1) % edge.size()], IM_COL32(255, 240, 150, 230), lw);
  }
  outline(v.emitting, IM_COL32(255, 255, 255, 255), 3 * lw);  // the emitting area inside the bezel
  outline(aerial, IM_COL32(255, 120, 200, 255), 2 * lw);
  if (const std::optional<scene>& g = st.design.ghost) {
    // The optimiser's best layout so far, or the one chosen to apply, over the scene's own.
    const ImU32 ghost = IM_COL32(255, 200, 60, 190);
    outline(half_mirror_frame(*g), ghost, 1.5f * lw);
    outline(source_panel_frame(*g), ghost, 1.5f * lw);
    for (std::size_t i = 0; i < g->retroreflectors.size(); ++i) outline(retroreflector_frame(*g, i), ghost, 1.5f * lw);
    outline(aerial_image_frame(*g), ghost, 1.5f * lw);
  }
  if (const auto* paths = st.ghosts.shown_paths()) {
    // The Ghosts window's class: a few of its traced paths, display to eye.
    const ImU32 c = ImGui::ColorConvertFloat4ToU32(
        ImVec4(ghost_path_colour.r, ghost_path_colour.g, ghost_path_colour.b, ghost_path_colour.a));
    for (const auto& line : *paths)
      for (std::size_t i = 1; i < line.size(); ++i) seg(glm::dvec3(line[i - 1]), glm::dvec3(line[i]), c, lw);
  }
  const ImVec2 es = m.to_screen(eye);
  dl->AddCircleFilled(es, 4 * lw, IM_COL32(200, 200, 200, 255));

  // Labels where compute_projection placed them; one set away from its point gets a leader line.
  const ImU32 text = IM_COL32(220, 220, 220, 255);
  for (const view_text& t : v.labels) {
    const screen_rect& b = t.place.box;
    if (!t.place.near) {
      const ImVec2 to(std::clamp(t.anchor.x, b.x0, b.x1), std::clamp(t.anchor.y, b.y0, b.y1));
      dl->AddLine(ImVec2(t.anchor.x, t.anchor.y), to, IM_COL32(220, 220, 220, 110), 0.7f * lw);
    }
    dl->AddText(ImVec2(b.x0, b.y0), text, t.text.c_str());
  }
  st.layout_views[proj == projection::side ? "side" : "top"] = std::make_shared<const projection_view>(v);

  // Scale bar of 50 mm, the axes, and the numbers a designer reads off.
  const ImVec2 sb(v.scale_bar.x, v.scale_bar.y);
  dl->AddLine(sb, ImVec2(sb.x + 50 * m.scale, sb.y), text, lw);
  dl->AddText(ImVec2(sb.x + 50 * m.scale + 4, sb.y - ImGui::GetFontSize() / 2), text, v.scale_text.c_str());
  dl->PopClipRect();

  // Handles: the view that is not being dragged keeps its own map.
  const std::string p = proj == projection::side ? "side:" : "top:";
  const char* turn = proj == projection::side ? "pitch" : "yaw";
  char tip[160];
  auto pose_handles = [&](const std::string& id, const char* name, pose& ps, const part_frame& f, ImU32 colour) {
    std::snprintf(tip, sizeof tip, "%s centre (%.1f, %.1f, %.1f) mm: drag to move", name, ps.center_mm[0],
                  ps.center_mm[1], ps.center_mm[2]);
    if (auto w = handle(p + id + ":move", m.to_screen(f.center), colour, m, tip, active_any)) move_center(ps, m, *w);
    const glm::dvec3 edge = turn_handle_point(proj, f);
    std::snprintf(tip, sizeof tip, "%s %s %.1f deg: drag to rotate", name, turn,
                  proj == projection::side ? ps.pitch_deg : ps.yaw_deg);
    if (auto w = handle(p + id + ":turn", m.to_screen(edge), colour, m, tip, active_any)) rotate(ps, m, f.center, *w);
  };
  pose_handles("display", "display", s.source.pose, src, IM_COL32(255, 255, 255, 255));
  pose_handles("mirror", "half mirror", s.half_mirror.pose, hm, IM_COL32(140, 200, 255, 255));
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    const std::string name = "sheet " + std::to_string(i);
    pose_handles(name, name.c_str(), s.retroreflectors[i].pose, retroreflector_frame(s, i),
                 IM_COL32(120, 230, 140, 255));
  }
  for (const auto& [i, k] : v.boxes) {
    prop_params& pr = s.props[i];
    std::snprintf(tip, sizeof tip, "prop %s at (%.1f, %.1f, %.1f) mm: drag to move", pr.name.c_str(),
                  pr.pose.center_mm[0], pr.pose.center_mm[1], pr.pose.center_mm[2]);
    const glm::dvec3 c(pr.pose.center_mm[0], pr.pose.center_mm[1], pr.pose.center_mm[2]);
    if (auto w = handle(p + "prop" + std::to_string(i), m.to_screen(c), prop_colour, m, tip, active_any)) {
      move_center(pr.pose, m, *w);
    }
  }
  // The aerial image moves along the line from the half mirror's centre: that is the floating distance.
  std::snprintf(tip, sizeof tip, "floating distance D %.1f mm: drag to change", floating_distance(s));
  if (auto w = handle(p + "aerial", m.to_screen(aerial.center), IM_COL32(255, 120, 200, 255), m, tip, active_any)) {
    const glm::dvec2 c = m.flat(hm.center), a = m.flat(aerial.center);
    const glm::dvec2 axis = a - c;
    if (glm::length(axis) > 1e-6) {
      const double along = glm::dot(*w - c, axis) / glm::length(axis);
      const double d = floating_distance(s) * along / glm::length(axis);
      try {
        set_floating_distance(s, std::clamp(round1(d), 10.0, 5000.0));
      } catch (const std::exception&) {
      }
    }
  }
  // The observer: orbit (angle and distance about the aerial image) or a free position.
  observer_params& o = s.observer;
  std::snprintf(tip, sizeof tip,
                o.placement == observer_placement::orbit
                    ? "observer: azimuth %.1f, elevation %.1f deg, %.0f mm: drag to orbit"
                    : "observer at (%.1f, %.1f, %.1f) mm: drag to move",
                o.placement == observer_placement::orbit ? o.azimuth_deg : o.position_mm[0],
                o.placement == observer_placement::orbit ? o.elevation_deg : o.position_mm[1],
                o.placement == observer_placement::orbit ? o.distance_mm : o.position_mm[2]);
  if (auto w = handle(p + "observer", es, IM_COL32(200, 200, 200, 255), m, tip, active_any)) {
    if (o.placement == observer_placement::look_at) {
      o.position_mm[2] = round1(w->x);
      o.position_mm[proj == projection::side ? 1 : 0] = round1(w->y);
    } else {
      const glm::dvec2 d = *w - m.flat(aerial.center);
      o.distance_mm = std::clamp(round1(glm::length(d)), 20.0, 5000.0);
      const double angle = round1(degrees(std::atan2(d.y, d.x)));
      if (proj == projection::side) {
        o.elevation_deg = std::clamp(angle, -89.0, 89.0);
      } else {
        o.azimuth_deg = std::clamp(angle, -180.0, 180.0);
      }
    }
  }
  if (active_any) frozen = m;
}

}  // namespace

void draw_layout_view(studio& st) {
  ImGui::Begin("Layout view", nullptr, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  static std::optional<view_map> frozen_side, frozen_top;
  const ImVec2 canvas0 = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  // A line at the bottom for the numbers a designer reads off; the views above it.
  const float info_h = 1.4f * ImGui::GetFontSize();
  const ImVec2 canvas(std::max(avail.x, 60.0f), std::max(avail.y - info_h, 60.0f));
  // The 3D view takes half the room; side and top share the other half. In a wide window the
  // 3D view is on the right and the projections are stacked on the left; in a tall one it is
  // below them and they stand side by side.
  const bool wide = canvas.x >= canvas.y;
  const float gap = 4.0f;
  const ImVec2 big = wide ? ImVec2((canvas.x - gap) / 2, canvas.y) : ImVec2(canvas.x, (canvas.y - gap) / 2);
  const ImVec2 small = wide ? ImVec2(big.x, (canvas.y - gap) / 2) : ImVec2((canvas.x - gap) / 2, big.y);
  const ImVec2 second =
      wide ? ImVec2(canvas0.x, canvas0.y + small.y + gap) : ImVec2(canvas0.x + small.x + gap, canvas0.y);
  const ImVec2 third = wide ? ImVec2(canvas0.x + big.x + gap, canvas0.y) : ImVec2(canvas0.x, canvas0.y + big.y + gap);

  bool side_active = false, top_active = false;
  std::optional<view_map> side_map = frozen_side, top_map = frozen_top;
  draw_projection(st, projection::side, canvas0, small, side_active, side_map);
  draw_projection(st, projection::top, second, small, top_active, top_map);
  frozen_side = side_active ? side_map : std::nullopt;
  frozen_top = top_active ? top_map : std::nullopt;
  draw_view_3d(st, third, big);
  st.regions["layout_side"] = {canvas0.x, canvas0.y, canvas0.x + small.x, canvas0.y + small.y};
  st.regions["layout_top"] = {second.x, second.y, second.x + small.x, second.y + small.y};
  st.regions["layout_3d"] = {third.x, third.y, third.x + big.x, third.y + big.y};

  char info[200];
  const glm::dvec3 a = aerial_image_center(st.doc);
  std::snprintf(info, sizeof info, "D %.1f mm   aerial image at (%.1f, %.1f, %.1f) mm   %.4f mm/px%s",
                floating_distance(st.doc), a.x + 0.0, a.y + 0.0, a.z + 0.0, make_camera(st.doc).mm_per_pixel,
                st.design.ghost ? "   amber: the optimiser's layout" : "");
  ImGui::GetWindowDrawList()->AddText(
      ImVec2(canvas0.x + 0.5f * ImGui::GetFontSize(), canvas0.y + canvas.y + 0.2f * ImGui::GetFontSize()),
      IM_COL32(220, 220, 220, 255), info);
  ImGui::SetCursorScreenPos(ImVec2(canvas0.x, canvas0.y + canvas.y + info_h));
  ImGui::End();
}

}  // namespace airr::ui
