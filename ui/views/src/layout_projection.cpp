#include "airr/ui/views/layout_projection.hpp"

#include <algorithm>

#include "airr/layout/layout.hpp"

namespace airr::ui {

projection_view compute_projection(const scene& s, const std::vector<mesh_bounds>& prop_bounds, projection proj,
                                   ImVec2 canvas0, ImVec2 canvas, float font_size, const text_size_fn& text_size,
                                   const std::optional<view_map>& frozen) {
  projection_view v;
  v.aerial = aerial_image_frame(s);
  v.emitting = source_frame(s);
  v.eye = make_camera(s).position;
  v.parts = {{half_mirror_frame(s), {"half mirror", IM_COL32(140, 200, 255, 255), 2}},
             {source_panel_frame(s), {"display", IM_COL32(255, 255, 255, 255), 3}}};
  for (std::size_t i = 0; i < s.retroreflectors.size(); ++i) {
    v.parts.push_back({retroreflector_frame(s, i), {"sheet", IM_COL32(120, 230, 140, 255), 3}});
  }

  // Every visible prop's box: its mesh's bounds, placed.
  for (std::size_t i = 0; i < s.props.size() && i < prop_bounds.size(); ++i) {
    const mesh_bounds& b = prop_bounds[i];
    if (!s.props[i].visible || b.lo == b.hi) continue;
    const glm::dmat4 xf = prop_transform(s.props[i]);
    std::array<glm::dvec3, 8> k;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 local(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
      k[std::size_t(c)] = glm::dvec3(xf * glm::dvec4(local, 1.0));
    }
    v.boxes.push_back({i, k});
  }

  // Fit every part, the props, the aerial image and the observer into the canvas.
  view_map& m = v.map;
  m.proj = proj;
  glm::dvec2 lo(1e30), hi(-1e30);
  auto grow = [&](const glm::dvec3& p) {
    lo = glm::min(lo, m.flat(p));
    hi = glm::max(hi, m.flat(p));
  };
  for (const auto& [f, style] : v.parts) {
    for (const auto& c : corners(f)) grow(c);
  }
  for (const auto& c : corners(v.aerial)) grow(c);
  for (const auto& [i, k] : v.boxes) {
    for (const auto& c : k) grow(c);
  }
  grow(v.eye);
  // Room around the device for the labels, and above it for the scale bar.
  const float margin = 1.6f * font_size, top = 2.4f * font_size;
  const glm::dvec2 span = glm::max(hi - lo, glm::dvec2(1.0));
  m.scale = std::min((canvas.x - 2 * margin) / float(span.x), (canvas.y - margin - top) / float(span.y));
  m.origin =
      ImVec2(canvas0.x + margin - float(lo.x) * m.scale + 0.5f * (canvas.x - 2 * margin - float(span.x) * m.scale),
             canvas0.y + top + float(hi.y) * m.scale + 0.5f * (canvas.y - margin - top - float(span.y) * m.scale));
  // While a handle is dragged the view keeps its scale, so the part follows the mouse steadily.
  if (frozen) m = *frozen;
  v.line_width = std::max(1.0f, font_size / 7.0f);

  auto screen = [&](const glm::dvec3& p) {
    const ImVec2 q = m.to_screen(p);
    return glm::vec2(q.x, q.y);
  };
  auto outline = [&](const part_frame& f) {
    const auto k = corners(f);
    for (std::size_t i = 0; i < 4; ++i) v.outlines.push_back({screen(k[i]), screen(k[(i + 1) % 4])});
  };
  for (const auto& [f, style] : v.parts) outline(f);
  outline(v.emitting);
  outline(v.aerial);
  for (const auto& [i, k] : v.boxes) {
    for (int a = 0; a < 8; ++a) {
      for (int bit : {1, 2, 4}) {
        if (!(a & bit)) v.outlines.push_back({screen(k[std::size_t(a)]), screen(k[std::size_t(a | bit)])});
      }
    }
  }
  // The observer's dot.
  const glm::vec2 e = screen(v.eye);
  const float r = 4 * v.line_width;
  const glm::vec2 dot[4] = {e + glm::vec2(-r, -r), e + glm::vec2(r, -r), e + glm::vec2(r, r), e + glm::vec2(-r, r)};
  for (int i = 0; i < 4; ++i) v.outlines.push_back({dot[i], dot[(i + 1) % 4]});

  // The drag handles: every part's centre and turning point, the props' centres, the aerial
  // image's centre, the observer.
  const float hr = 1.3f * handle_radius(font_size);
  auto add_handle = [&](const glm::dvec3& p) {
    const glm::vec2 c = screen(p);
    v.handles.push_back({c.x - hr, c.y - hr, c.x + hr, c.y + hr});
  };
  for (const auto& [f, style] : v.parts) {
    add_handle(f.center);
    add_handle(turn_handle_point(proj, f));
  }
  for (const auto& [i, k] : v.boxes) {
    const auto& c = s.props[i].pose.center_mm;
    add_handle({c[0], c[1], c[2]});
  }
  add_handle(v.aerial.center);
  add_handle(v.eye);

  // The scale bar of 50 mm and its text, at the top left.
  v.scale_bar = glm::vec2(canvas0.x + margin, canvas0.y + 0.6f * margin);
  v.scale_text = proj == projection::side ? "50 mm   side: z right, y up" : "50 mm   top: z right, x up";
  const glm::vec2 scale_size = text_size(v.scale_text);
  v.scale_box = {v.scale_bar.x, v.scale_bar.y - 0.5f * font_size, v.scale_bar.x + 50 * m.scale + 4 + scale_size.x,
                 v.scale_bar.y - 0.5f * font_size + scale_size.y};

  auto add_label = [&](const glm::dvec3& p, const std::string& text) { v.labels.push_back({text, screen(p), {}}); };
  for (std::size_t i = 0; i < v.parts.size(); ++i) {
    const part_frame& f = v.parts[i].first;
    const std::string name = i >= 2 && s.retroreflectors.size() > 1 ? "sheet " + std::to_string(i - 2)
                             : i >= 2                               ? std::string("retroreflector")
                                                                    : std::string(v.parts[i].second.name);
    add_label(f.center + 0.5 * f.height * f.v, name);
  }
  add_label(v.aerial.center + 0.5 * v.aerial.height * v.aerial.v, "aerial image");
  for (const auto& [i, k] : v.boxes) add_label(k[7], s.props[i].name.empty() ? "prop" : s.props[i].name);
  add_label(v.eye, s.observer.lens == observer_lens::thin_lens ? "observer (lens)" : "observer");

  std::vector<label_request> requests;
  for (const view_text& t : v.labels) requests.push_back({t.anchor, text_size(t.text)});
  std::vector<screen_rect> taken = {v.scale_box};
  taken.insert(taken.end(), v.handles.begin(), v.handles.end());
  const std::vector<placed_label> placed =
      place_labels(requests, v.outlines, taken, {canvas0.x, canvas0.y, canvas0.x + canvas.x, canvas0.y + canvas.y},
                   2.0f + v.line_width);
  for (std::size_t i = 0; i < placed.size(); ++i) v.labels[i].place = placed[i];
  return v;
}

}  // namespace airr::ui
