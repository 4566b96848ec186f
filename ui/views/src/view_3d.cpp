// The 3D layout view: the parts, the props, the luminaires, the aerial image, a few ideal light
// paths and the observer, shaded by OpenGL; drag to orbit, right- or middle-drag to pan, the wheel
// to zoom, double-click to frame everything again.
#include <algorithm>
#include <cmath>

#include <imgui.h>
#include <glm/gtc/matrix_transform.hpp>

#include "airr/layout/layout.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

namespace {

std::vector<glm::vec3> rectangle(const part_frame& f, double lift = 0) {
  const auto k = corners(f);
  std::vector<glm::vec3> out;
  for (int i : {0, 1, 2, 0, 2, 3}) out.emplace_back(k[std::size_t(i)] + lift * f.n);
  return out;
}

// Props are see-through, so that the optics inside a housing stay in view.
glm::vec4 prop_colour(const prop_params& p, const triangle_mesh& mesh) {
  switch (p.surface) {
    case prop_surface::absorber:
      return {0.22f, 0.22f, 0.24f, 0.3f};
    case prop_surface::diffuse:
      return {float(p.albedo[0]), float(p.albedo[1]), float(p.albedo[2]), 0.3f};
    case prop_surface::mirror:
      return {0.8f, 0.85f, 0.9f, 0.3f};
    case prop_surface::material:
      break;
  }
  const glm::vec3 c = mesh.materials.empty() ? glm::vec3(0.6f) : glm::max(mesh.materials.front().base_color, 0.15f);
  return {c, 0.3f};
}

// A part's films: each a tinted sheet lifted off its face (violet a retarder, amber a polarizer),
// hatched along its axis.
void add_films(const part_frame& f, const std::vector<film_params>& films, std::vector<gl_draw_item>& items) {
  int on_face[2] = {0, 0};
  for (const film_params& film : films) {
    const int face = int(film.face);
    const double lift = (face == 0 ? 1.0 : -1.0) * (1.0 + on_face[face]++);
    const glm::vec3 tint =
        film.kind == film_kind::retarder ? glm::vec3(0.7f, 0.45f, 1.0f) : glm::vec3(1.0f, 0.7f, 0.2f);
    gl_draw_item sheet;
    sheet.triangles = rectangle(f, lift);
    sheet.colour = {tint, 0.3f};
    items.push_back(std::move(sheet));
    const double a = radians(film.axis_deg), half = 0.45 * std::min(f.width, f.height);
    const glm::dvec3 along = std::cos(a) * f.u + std::sin(a) * f.v, across = -std::sin(a) * f.u + std::cos(a) * f.v;
    gl_draw_item hatch;
    hatch.colour = {tint, 1.0f};
    for (double o = -0.8; o <= 0.81; o += 0.4) {
      const glm::dvec3 c = f.center + lift * f.n + o * half * across;
      const double reach = half * std::sqrt(std::max(0.0, 1 - o * o));
      hatch.lines.insert(hatch.lines.end(), {glm::vec3(c - reach * along), glm::vec3(c + reach * along)});
    }
    items.push_back(std::move(hatch));
  }
}

// Everything the view draws, in world millimetres; `meshes` are the props' (null: not loaded).
std::vector<gl_draw_item> layout_items(const scene& s,
                                       const std::vector<std::shared_ptr<const triangle_mesh>>& meshes) {
  std::vector<gl_draw_item> items;
  auto solid = [&](std::vector<glm::vec3> tris, glm::vec4 colour) {
    gl_draw_item it;
    it.triangles = std::move(tris);
    it.colour = colour;
    items.push_back(std::move(it));
  };
  auto lines = [&](std::vector<glm::vec3> segs, glm::vec4 colour) {
    gl_draw_item it;
    it.lines = std::move(segs);
    it.colour = colour;
    items.push_back(std::move(it));
  };
  const part_frame panel = source_panel_frame(s), area = source_frame(s), hm = half_mirror_frame(s);
  solid(rectangle(panel), {0.2f, 0.2f, 0.22f, 1});
  solid(rectangle(area, 0.2), {0.95f, 0.95f, 0.95f, 1});
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i)
    solid(rectangle(retroreflector_frame(s, i)), {0.47f, 0.85f, 0.55f, 1});
  if (s.half_mirror.kind == half_mirror_kind::plate) {
    // Its two faces, about its mid-plane.
    const double t = 0.5 * s.half_mirror.plate.thickness_mm;
    solid(rectangle(hm, t), {0.55f, 0.78f, 1.0f, 0.3f});
    solid(rectangle(hm, -t), {0.55f, 0.78f, 1.0f, 0.3f});
  } else {
    solid(rectangle(hm), {0.55f, 0.78f, 1.0f, 0.35f});
  }
  add_films(area, s.source.films, items);
  add_films(hm, s.half_mirror.films, items);
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i)
    add_films(retroreflector_frame(s, i), s.retroreflectors[i].films, items);
  const part_frame aerial = aerial_image_frame(s);
  solid(rectangle(aerial), {1.0f, 0.47f, 0.78f, 0.55f});
  for (std::size_t i = 0; i < s.props.size() && i < meshes.size(); ++i) {
    const prop_params& p = s.props[i];
    if (!p.visible || !meshes[i]) continue;
    gl_draw_item it;
    it.mesh = meshes[i];
    it.model = glm::mat4(prop_transform(p));
    it.colour = prop_colour(p, *it.mesh);
    items.push_back(std::move(it));
  }
  // The luminaires (Environment), lit on both sides here: a fan over their outline.
  for (const luminaire_params& l : s.environment.luminaires) {
    const std::vector<glm::dvec3> edge = luminaire_outline(l);
    const glm::dvec3 centre = luminaire_frame(l).center;
    std::vector<glm::vec3> fan;
    for (std::size_t k = 0; k < edge.size(); ++k)
      fan.insert(fan.end(), {glm::vec3(centre), glm::vec3(edge[k]), glm::vec3(edge[(k + 1) % edge.size()])});
    solid(std::move(fan), {1.0f, 0.94f, 0.59f, 1});
  }
  // Ideal light paths through the aerial image's centre and four points towards its corners.
  std::vector<glm::vec3> rays;
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {-0.35, -0.35}, {0.35, -0.35}, {0.35, 0.35}, {-0.35, 0.35}}) {
    const auto path = ideal_light_path(s, part_point(aerial, x * aerial.width, y * aerial.height));
    for (std::size_t i = 1; i < path.size(); ++i) rays.insert(rays.end(), {glm::vec3(path[i - 1]), glm::vec3(path[i])});
  }
  lines(rays, {1.0f, 0.82f, 0.35f, 1});
  // The observer: sight lines to the aerial image's corners and a small camera.
  const pinhole_camera cam = make_camera(s);
  std::vector<glm::vec3> sight;
  for (const auto& c : corners(aerial)) sight.insert(sight.end(), {glm::vec3(cam.position), glm::vec3(c)});
  lines(sight, {0.6f, 0.6f, 0.6f, 1});
  const double r = 12, h = r * cam.tan_half_fov * 2;
  std::vector<glm::vec3> box;
  std::array<glm::dvec3, 4> k;
  for (int i = 0; i < 4; ++i) {
    const double sx = (i == 1 || i == 2) ? 1 : -1, sy = i >= 2 ? 1 : -1;
    k[std::size_t(i)] = cam.position + 2.0 * r * cam.forward + sx * h * cam.right + sy * h * cam.up;
  }
  for (int i = 0; i < 4; ++i) {
    box.insert(box.end(), {glm::vec3(cam.position), glm::vec3(k[std::size_t(i)]), glm::vec3(k[std::size_t(i)]),
                           glm::vec3(k[std::size_t((i + 1) % 4)])});
  }
  lines(box, {0.9f, 0.9f, 0.9f, 1});
  return items;
}

// The centre and radius that hold the parts, the aerial image, the observer and the props' boxes.
std::pair<glm::vec3, float> extent(const scene& s, const std::vector<mesh_bounds>& prop_bounds) {
  glm::dvec3 lo(1e30), hi(-1e30);
  auto grow = [&](const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  std::vector<part_frame> frames = {source_panel_frame(s), half_mirror_frame(s), aerial_image_frame(s)};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) frames.push_back(retroreflector_frame(s, i));
  for (const auto& f : frames) {
    for (const auto& c : corners(f)) grow(c);
  }
  grow(observer_position(s));
  for (const luminaire_params& l : s.environment.luminaires) {
    for (const glm::dvec3& p : luminaire_outline(l)) grow(p);
  }
  for (std::size_t i = 0; i < s.props.size() && i < prop_bounds.size(); ++i) {
    const mesh_bounds& b = prop_bounds[i];
    if (!s.props[i].visible || b.lo == b.hi) continue;
    const glm::dmat4 xf = prop_transform(s.props[i]);
    for (int c = 0; c < 8; ++c) {
      grow(glm::dvec3(xf * glm::dvec4(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z, 1.0)));
    }
  }
  return {glm::vec3(0.5 * (lo + hi)), float(0.5 * glm::length(hi - lo))};
}

}  // namespace

void draw_view_3d(studio& st, ImVec2 at, ImVec2 size) {
  view_3d_state& v = st.view_3d;
  if (!v.framed) {
    // The sphere holding everything fits the narrower of the two fields of view.
    const auto [centre, radius] = extent(st.doc, st.prop_bounds);
    const float half_fov =
        std::min(glm::radians(22.5f), std::atan(std::tan(glm::radians(22.5f)) * size.x / std::max(1.0f, size.y)));
    v.target = centre;
    v.distance_mm = std::max(50.0f, 1.05f * radius / std::sin(half_fov));
    v.framed = true;
  }
  ImGui::SetCursorScreenPos(at);
  ImGui::InvisibleButton(
      "view3d", size,
      ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight | ImGuiButtonFlags_MouseButtonMiddle);
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsItemActive()) {
    if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
      v.yaw_deg -= 0.4f * io.MouseDelta.x;
      v.pitch_deg = std::clamp(v.pitch_deg + 0.4f * io.MouseDelta.y, -89.0f, 89.0f);
    } else if (ImGui::IsMouseDragging(ImGuiMouseButton_Right) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle)) {
      const float per_pixel = 2.0f * v.distance_mm * std::tan(glm::radians(22.5f)) / std::max(1.0f, size.y);
      const float yaw = glm::radians(v.yaw_deg), pitch = glm::radians(v.pitch_deg);
      const glm::vec3 back(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
      const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0, 1, 0), back));
      const glm::vec3 up = glm::cross(back, right);
      v.target += per_pixel * (-io.MouseDelta.x * right + io.MouseDelta.y * up);
    }
  }
  if (ImGui::IsItemHovered()) {
    if (io.MouseWheel != 0) v.distance_mm = std::clamp(v.distance_mm * std::pow(0.88f, io.MouseWheel), 10.0f, 1e5f);
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) v.framed = false;
    ImGui::SetTooltip("3D: drag to orbit, right-drag to pan, wheel to zoom, double-click to frame");
  }

  const float yaw = glm::radians(v.yaw_deg), pitch = glm::radians(v.pitch_deg);
  const glm::vec3 eye = v.target + v.distance_mm * glm::vec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                                                             std::cos(yaw) * std::cos(pitch));
  const glm::mat4 view = glm::lookAt(eye, v.target, glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspective(glm::radians(45.0f), size.x / std::max(1.0f, size.y), 0.01f * v.distance_mm,
                                          100.0f * v.distance_mm);
  if (!v.renderer) v.renderer = std::make_unique<gl_layout_renderer>();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 end(at.x + size.x, at.y + size.y);
  std::vector<gl_draw_item> items = layout_items(st.doc, st.prop_meshes);
  if (const auto* paths = st.ghosts.shown_paths()) {
    // The Ghosts window's class: a few of its traced paths, display to eye.
    gl_draw_item it;
    for (const auto& line : *paths)
      for (std::size_t i = 1; i < line.size(); ++i) it.lines.insert(it.lines.end(), {line[i - 1], line[i]});
    it.colour = ghost_path_colour;
    items.push_back(std::move(it));
  }
  if (v.renderer->render(int(size.x), int(size.y), proj * view, items)) {
    // OpenGL's rows run bottom-up.
    dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(v.renderer->texture())), at, end,
                 ImVec2(0, 1), ImVec2(1, 0));
  } else {
    dl->AddRectFilled(at, end, IM_COL32(24, 26, 30, 255));
    dl->AddText(ImVec2(at.x + 6, at.y + 6), IM_COL32(255, 140, 120, 255),
                ("3D view unavailable: " + v.renderer->error()).c_str());
  }
  dl->AddText(ImVec2(at.x + 0.6f * ImGui::GetFontSize(), at.y + 0.3f * ImGui::GetFontSize()),
              IM_COL32(220, 220, 220, 255), "3D");
}

}  // namespace airr::ui
