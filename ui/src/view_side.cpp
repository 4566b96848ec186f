// The side view: the layout in the y-z plane drawn to scale (z to the right, y up), the chief and
// marginal rays, and drag handles for tilt, floating distance and source position that edit the
// same fields as the layout panel.
#include <cmath>
#include <numbers>
#include <optional>

#include <imgui.h>
#include <imgui_internal.h>

#include "airr/optics/geometry.hpp"
#include "airr/optics/layout.hpp"
#include "airr/ui/studio.hpp"

namespace airr::ui {

namespace {

struct view_map {
  ImVec2 origin;  // screen position of world (y, z) = (0, 0)
  float scale;    // pixels per mm
  ImVec2 to_screen(double y, double z) const {
    return ImVec2(origin.x + float(z) * scale, origin.y - float(y) * scale);
  }
  glm::dvec2 to_world(ImVec2 p) const { return {(origin.y - p.y) / scale, (p.x - origin.x) / scale}; }  // (y, z)
};

// The ideal light path through an aerial-image point, as a polyline from the camera.
std::vector<glm::dvec3> ray_path(const scene& s, const glm::dvec3& aerial_point) {
  const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s), src = source_frame(s);
  const glm::dvec3 cam = make_camera(s).position;
  std::vector<glm::dvec3> path{cam};
  const glm::dvec3 d = glm::normalize(aerial_point - cam);
  const auto p1 = hit_part(hm, cam, d, false);
  if (!p1) return path;
  const auto p2 = hit_part(rr, *p1, d, false);
  if (!p2) return path;
  const glm::dvec3 down = reflect(-d, hm.n);
  const auto p3 = hit_part(src, *p1, down, false);
  path.insert(path.end(), {*p1, *p2, *p1});
  if (p3) path.push_back(*p3);
  return path;
}

// A draggable circle; returns the mouse position in world (y, z) while dragged.
std::optional<glm::dvec2> handle(const char* id, ImVec2 at, ImU32 colour, const view_map& m, const char* tip) {
  const float r = 0.45f * ImGui::GetFontSize();
  ImGui::SetCursorScreenPos(ImVec2(at.x - r, at.y - r));
  ImGui::InvisibleButton(id, ImVec2(2 * r, 2 * r));
  const bool active = ImGui::IsItemActive(), hovered = ImGui::IsItemHovered();
  ImGui::GetWindowDrawList()->AddCircleFilled(at, r * (hovered || active ? 1.3f : 1.0f), colour);
  ImGui::GetWindowDrawList()->AddCircle(at, r * (hovered || active ? 1.3f : 1.0f), IM_COL32(255, 255, 255, 200));
  if (hovered || active) ImGui::SetTooltip("%s", tip);
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) return m.to_world(ImGui::GetIO().MousePos);
  return std::nullopt;
}

}  // namespace

void draw_side_view(studio& st) {
  ImGui::Begin("Side view (y-z plane)", nullptr, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  scene& s = st.doc;
  const part_frame hm = half_mirror_frame(s), rr = retroreflector_frame(s), src = source_frame(s);
  const pinhole_camera cam = make_camera(s);
  const glm::dvec3 aerial = aerial_image_center(s);
  auto ends = [](const part_frame& f) {
    return std::pair{f.center - 0.5 * f.height * f.v, f.center + 0.5 * f.height * f.v};
  };
  auto mirror = [&](const glm::dvec3& p) { return mirror_point(p, hm.center, hm.n); };
  const auto [hm0, hm1] = ends(hm);
  const auto [rr0, rr1] = ends(rr);
  const auto [s0, s1] = ends(src);
  const glm::dvec3 a0 = mirror(s0), a1 = mirror(s1);

  // Fit everything (parts and camera) into the canvas.
  double ymin = 1e30, ymax = -1e30, zmin = 1e30, zmax = -1e30;
  for (const glm::dvec3& p : {hm0, hm1, rr0, rr1, s0, s1, a0, a1, cam.position}) {
    ymin = std::min(ymin, p.y);
    ymax = std::max(ymax, p.y);
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  const ImVec2 canvas0 = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 canvas(std::max(avail.x, 50.0f), std::max(avail.y, 50.0f));
  const float margin = 1.5f * ImGui::GetFontSize();
  const float scale =
      std::min((canvas.x - 2 * margin) / float(zmax - zmin), (canvas.y - 2 * margin) / float(ymax - ymin));
  // While a handle is dragged the view keeps its scale, so the part follows the mouse steadily.
  static view_map frozen;
  static bool dragging = false;
  view_map m;
  m.scale = scale;
  m.origin =
      ImVec2(canvas0.x + margin + float(-zmin) * scale + 0.5f * (canvas.x - 2 * margin - float(zmax - zmin) * scale),
             canvas0.y + margin + float(ymax) * scale + 0.5f * (canvas.y - 2 * margin - float(ymax - ymin) * scale));
  if (dragging) m = frozen;
  frozen = m;
  bool any_active = false;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(canvas0, ImVec2(canvas0.x + canvas.x, canvas0.y + canvas.y), IM_COL32(24, 26, 30, 255));
  auto seg = [&](const glm::dvec3& p, const glm::dvec3& q, ImU32 c, float w) {
    dl->AddLine(m.to_screen(p.y, p.z), m.to_screen(q.y, q.z), c, w);
  };
  const float lw = std::max(1.0f, ImGui::GetFontSize() / 7.0f);

  // Rays first, parts on top.
  const double half_image = 0.5 * s.source.height_mm;
  const ImU32 chief = IM_COL32(255, 210, 90, 230), marginal = IM_COL32(255, 210, 90, 110);
  for (double yy : {0.0, -half_image, half_image}) {
    const auto path = ray_path(s, aerial + glm::dvec3(0, yy, 0));
    for (std::size_t i = 1; i < path.size(); ++i)
      seg(path[i - 1], path[i], yy == 0 ? chief : marginal, yy == 0 ? lw : 0.7f * lw);
  }
  // Camera field of view to the aerial-image plane.
  const double half_view = cam.tan_half_fov * s.camera.distance_mm;
  seg(cam.position, glm::dvec3(0, half_view, s.floating_distance_mm), IM_COL32(150, 150, 150, 120), 0.7f * lw);
  seg(cam.position, glm::dvec3(0, -half_view, s.floating_distance_mm), IM_COL32(150, 150, 150, 120), 0.7f * lw);

  seg(hm0, hm1, IM_COL32(140, 200, 255, 255), 2 * lw);
  seg(rr0, rr1, IM_COL32(120, 230, 140, 255), 3 * lw);
  seg(s0, s1, IM_COL32(255, 255, 255, 255), 3 * lw);
  seg(a0, a1, IM_COL32(255, 120, 200, 255), 2 * lw);
  const ImVec2 cs = m.to_screen(cam.position.y, cam.position.z);
  dl->AddTriangleFilled(ImVec2(cs.x - 6 * lw, cs.y), ImVec2(cs.x + 6 * lw, cs.y - 5 * lw),
                        ImVec2(cs.x + 6 * lw, cs.y + 5 * lw), IM_COL32(200, 200, 200, 255));
  const ImU32 text = IM_COL32(220, 220, 220, 255);
  auto label = [&](const glm::dvec3& p, const char* t, float dx = 4, float dy = 2) {
    const ImVec2 q = m.to_screen(p.y, p.z);
    dl->AddText(ImVec2(q.x + dx, q.y + dy), text, t);
  };
  label(hm1, "half mirror");
  label(rr.center + 0.5 * rr.height * rr.v, "retroreflector");
  label(s1, "source");
  label(a1, "aerial image");
  label(cam.position, "camera", -20, 6 * lw);

  // Scale bar of 50 mm and the axes' directions.
  const ImVec2 sb(canvas0.x + margin, canvas0.y + 0.6f * margin);
  dl->AddLine(sb, ImVec2(sb.x + 50 * scale, sb.y), text, lw);
  dl->AddText(ImVec2(sb.x + 50 * scale + 4, sb.y - ImGui::GetFontSize() / 2), text, "50 mm   (z to the right, y up)");
  char info[160];
  std::snprintf(info, sizeof info, "D %.1f mm   tilt %.1f deg   retroreflector to image %.1f mm",
                s.floating_distance_mm, s.retroreflector.tilt_deg, glm::length(aerial - rr.center));
  const float info_w = ImGui::CalcTextSize(info).x;
  dl->AddText(ImVec2(canvas0.x + canvas.x - info_w - 0.5f * margin, canvas0.y + canvas.y - 1.1f * margin), text, info);

  // Handles.
  char tip[96];
  std::snprintf(tip, sizeof tip, "tilt %.1f deg: drag to rotate the retroreflector", s.retroreflector.tilt_deg);
  const glm::dvec3 top = rr.center + 0.5 * rr.height * rr.v;
  if (auto w = handle("tilt", m.to_screen(top.y, top.z), IM_COL32(120, 230, 140, 255), m, tip)) {
    // v = (0, cos t, -sin t): the angle of the handle around the sheet centre is the tilt.
    const double dy = w->x - rr.center.y, dz = w->y - rr.center.z;
    s.retroreflector.tilt_deg =
        std::clamp(std::round(std::atan2(-dz, dy) * 180 / std::numbers::pi * 10) / 10, -80.0, 80.0);
  }
  std::snprintf(tip, sizeof tip, "floating distance %.1f mm: drag along z", s.floating_distance_mm);
  if (auto w = handle("distance", m.to_screen(aerial.y, aerial.z), IM_COL32(255, 120, 200, 255), m, tip)) {
    s.floating_distance_mm = std::clamp(std::round(w->y * 10) / 10, 10.0, 2000.0);
  }
  std::snprintf(tip, sizeof tip, "source offset y %.1f, z %.1f mm: drag to move the source", s.source.offset_mm[1],
                s.source.offset_mm[2]);
  if (auto w = handle("source", m.to_screen(src.center.y, src.center.z), IM_COL32(255, 255, 255, 255), m, tip)) {
    s.source.offset_mm[1] = std::round((w->x + s.floating_distance_mm) * 10) / 10;
    s.source.offset_mm[2] = std::round(w->y * 10) / 10;
  }
  any_active = ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
               (ImGui::IsItemActive() || ImGui::GetActiveID() == ImGui::GetID("tilt") ||
                ImGui::GetActiveID() == ImGui::GetID("distance") || ImGui::GetActiveID() == ImGui::GetID("source"));
  dragging = any_active;
  ImGui::SetCursorScreenPos(ImVec2(canvas0.x, canvas0.y + canvas.y));
  ImGui::End();
}

}  // namespace airr::ui
