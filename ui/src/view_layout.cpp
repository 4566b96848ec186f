// The layout view: the device drawn to scale in two projections, side (y-z) and top (x-z), beside
// a 3D view (view_3d.cpp), with
// the props' boxes, the aerial image where it forms, the observer's sight lines and the chief ray, and handles that
// pose every part: move (centre), rotate (pitch in the side view, yaw in the top view), the
// floating distance (the aerial image's handle) and the observer (orbit or position).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>

#include "airr/optics/geometry.hpp"
#include "airr/optics/layout.hpp"
#include "airr/ui/studio.hpp"

namespace airr::ui {

namespace {

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

double round1(double v) { return std::round(v * 10) / 10; }

// A draggable circle; returns the mouse position (projection coordinates) while dragged.
std::optional<glm::dvec2> handle(const std::string& id, ImVec2 at, ImU32 colour, const view_map& m,
                                 const std::string& tip, bool& active_any) {
  const float r = 0.42f * ImGui::GetFontSize();
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

struct part_style {
  const char* name;
  ImU32 colour;
  float width;
};

void draw_projection(studio& st, projection proj, ImVec2 canvas0, ImVec2 canvas, bool& active_any,
                     std::optional<view_map>& frozen) {
  scene& s = st.doc;
  const part_frame hm = half_mirror_frame(s), src = source_panel_frame(s), aerial = aerial_image_frame(s);
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 eye = cam.position;

  std::vector<std::pair<part_frame, part_style>> parts = {{hm, {"half mirror", IM_COL32(140, 200, 255, 255), 2}},
                                                          {src, {"display", IM_COL32(255, 255, 255, 255), 3}}};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    parts.push_back({retroreflector_frame(s, i), {"sheet", IM_COL32(120, 230, 140, 255), 3}});
  }

  // Every visible prop's box: its mesh's bounds, placed.
  std::vector<std::pair<std::size_t, std::array<glm::dvec3, 8>>> boxes;
  for (std::size_t i = 0; i < s.props.size() && i < st.prop_bounds.size(); ++i) {
    const mesh_bounds& b = st.prop_bounds[i];
    if (!s.props[i].visible || b.lo == b.hi) continue;
    const glm::dmat4 xf = prop_transform(s.props[i]);
    std::array<glm::dvec3, 8> k;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 local(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
      k[std::size_t(c)] = glm::dvec3(xf * glm::dvec4(local, 1.0));
    }
    boxes.push_back({i, k});
  }

  // Fit every part, the props, the aerial image and the observer into the canvas.
  view_map m;
  m.proj = proj;
  glm::dvec2 lo(1e30), hi(-1e30);
  auto grow = [&](const glm::dvec3& p) {
    lo = glm::min(lo, m.flat(p));
    hi = glm::max(hi, m.flat(p));
  };
  for (const auto& [f, style] : parts) {
    for (const auto& c : corners(f)) grow(c);
  }
  for (const auto& c : corners(aerial)) grow(c);
  for (const auto& [i, k] : boxes) {
    for (const auto& c : k) grow(c);
  }
  grow(eye);
  const float margin = 1.6f * ImGui::GetFontSize();
  const glm::dvec2 span = glm::max(hi - lo, glm::dvec2(1.0));
  m.scale = std::min((canvas.x - 2 * margin) / float(span.x), (canvas.y - 2 * margin) / float(span.y));
  m.origin =
      ImVec2(canvas0.x + margin - float(lo.x) * m.scale + 0.5f * (canvas.x - 2 * margin - float(span.x) * m.scale),
             canvas0.y + margin + float(hi.y) * m.scale + 0.5f * (canvas.y - 2 * margin - float(span.y) * m.scale));
  // While a handle is dragged the view keeps its scale, so the part follows the mouse steadily.
  if (frozen) m = *frozen;

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(canvas0, ImVec2(canvas0.x + canvas.x, canvas0.y + canvas.y), true);
  dl->AddRectFilled(canvas0, ImVec2(canvas0.x + canvas.x, canvas0.y + canvas.y), IM_COL32(24, 26, 30, 255));
  const float lw = std::max(1.0f, ImGui::GetFontSize() / 7.0f);
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
  for (const auto& [i, k] : boxes) {
    for (int a = 0; a < 8; ++a) {
      for (int bit : {1, 2, 4}) {
        if (!(a & bit)) seg(k[std::size_t(a)], k[std::size_t(a | bit)], prop_colour, 0.8f * lw);
      }
    }
  }
  for (const auto& [f, style] : parts) outline(f, style.colour, style.width * lw);
  outline(source_frame(s), IM_COL32(255, 255, 255, 255), 3 * lw);  // the emitting area inside the bezel
  outline(aerial, IM_COL32(255, 120, 200, 255), 2 * lw);
  const ImVec2 es = m.to_screen(eye);
  dl->AddCircleFilled(es, 4 * lw, IM_COL32(200, 200, 200, 255));

  const ImU32 text = IM_COL32(220, 220, 220, 255);
  // Labels step down a line while they would overlap one already drawn (parts seen edge-on in
  // one projection often share a spot).
  std::vector<ImVec4> placed;
  auto label = [&](const glm::dvec3& p, const char* t) {
    const ImVec2 q = m.to_screen(p), size = ImGui::CalcTextSize(t);
    ImVec2 at(q.x + 6, q.y + 4);
    if (at.x + size.x > canvas0.x + canvas.x) at.x = q.x - 6 - size.x;  // left of the point at the right edge
    auto overlaps = [&](const ImVec4& r) {
      return at.x < r.z && r.x < at.x + size.x && at.y < r.w && r.y < at.y + size.y;
    };
    for (int tries = 0; tries < 8 && std::any_of(placed.begin(), placed.end(), overlaps); ++tries) at.y += size.y;
    placed.emplace_back(at.x, at.y, at.x + size.x, at.y + size.y);
    dl->AddText(at, text, t);
  };
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string name = i >= 2 && s.retroreflectors.size() > 1 ? "sheet " + std::to_string(i - 2)
                             : i >= 2                               ? std::string("retroreflector")
                                                                    : std::string(parts[i].second.name);
    label(parts[i].first.center + 0.5 * parts[i].first.height * parts[i].first.v, name.c_str());
  }
  label(aerial.center + 0.5 * aerial.height * aerial.v, "aerial image");
  for (const auto& [i, k] : boxes) {
    const std::string& name = s.props[i].name;
    label(k[7], name.empty() ? "prop" : name.c_str());
  }
  label(eye, s.observer.lens == observer_lens::thin_lens ? "observer (lens)" : "observer");

  // Scale bar of 50 mm, the axes, and the numbers a designer reads off.
  const ImVec2 sb(canvas0.x + margin, canvas0.y + 0.6f * margin);
  dl->AddLine(sb, ImVec2(sb.x + 50 * m.scale, sb.y), text, lw);
  dl->AddText(ImVec2(sb.x + 50 * m.scale + 4, sb.y - ImGui::GetFontSize() / 2), text,
              proj == projection::side ? "50 mm   side: z right, y up" : "50 mm   top: z right, x up");
  dl->PopClipRect();

  // Handles: the view that is not being dragged keeps its own map.
  const std::string p = proj == projection::side ? "side:" : "top:";
  const char* turn = proj == projection::side ? "pitch" : "yaw";
  char tip[160];
  auto pose_handles = [&](const std::string& id, const char* name, pose& ps, const part_frame& f, ImU32 colour) {
    std::snprintf(tip, sizeof tip, "%s centre (%.1f, %.1f, %.1f) mm: drag to move", name, ps.center_mm[0],
                  ps.center_mm[1], ps.center_mm[2]);
    if (auto w = handle(p + id + ":move", m.to_screen(f.center), colour, m, tip, active_any)) move_center(ps, m, *w);
    const glm::dvec3 edge = proj == projection::side ? f.center + 0.5 * f.height * f.v : f.center + 0.5 * f.width * f.u;
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
  for (const auto& [i, k] : boxes) {
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
  const ImVec2 canvas(std::max(avail.x, 60.0f), std::max(avail.y, 60.0f));
  // Side, top and 3D side by side when the window is wide, one above the other when it is tall.
  const bool wide = canvas.x >= canvas.y;
  const float gap = 4.0f;
  const ImVec2 half = wide ? ImVec2((canvas.x - 2 * gap) / 3, canvas.y) : ImVec2(canvas.x, (canvas.y - 2 * gap) / 3);
  const ImVec2 second =
      wide ? ImVec2(canvas0.x + half.x + gap, canvas0.y) : ImVec2(canvas0.x, canvas0.y + half.y + gap);
  const ImVec2 third = wide ? ImVec2(second.x + half.x + gap, canvas0.y) : ImVec2(canvas0.x, second.y + half.y + gap);

  bool side_active = false, top_active = false;
  std::optional<view_map> side_map = frozen_side, top_map = frozen_top;
  draw_projection(st, projection::side, canvas0, half, side_active, side_map);
  draw_projection(st, projection::top, second, half, top_active, top_map);
  frozen_side = side_active ? side_map : std::nullopt;
  frozen_top = top_active ? top_map : std::nullopt;
  draw_view_3d(st, third, half);
  st.regions["layout_side"] = {canvas0.x, canvas0.y, canvas0.x + half.x, canvas0.y + half.y};
  st.regions["layout_top"] = {second.x, second.y, second.x + half.x, second.y + half.y};
  st.regions["layout_3d"] = {third.x, third.y, third.x + half.x, third.y + half.y};

  char info[200];
  const glm::dvec3 a = aerial_image_center(st.doc);
  std::snprintf(info, sizeof info, "D %.1f mm   aerial image at (%.1f, %.1f, %.1f) mm   %.4f mm/px",
                floating_distance(st.doc), a.x + 0.0, a.y + 0.0, a.z + 0.0, make_camera(st.doc).mm_per_pixel);
  ImGui::GetWindowDrawList()->AddText(
      ImVec2(canvas0.x + 0.5f * ImGui::GetFontSize(), canvas0.y + canvas.y - 1.3f * ImGui::GetFontSize()),
      IM_COL32(220, 220, 220, 255), info);
  ImGui::SetCursorScreenPos(ImVec2(canvas0.x, canvas0.y + canvas.y));
  ImGui::End();
}

}  // namespace airr::ui
