// The render view: the progressive image with its statistics, pause/resume, exposure, zoom and
// pan, the luminance and contrast views (false colour with their scales), and a cursor readout of
// the pixel value, its luminance, its contrast and its position on the aerial-image plane.
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "airr/core/color.hpp"
#include "airr/formats/image.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/contrast.hpp"
#include "airr/render/render_metadata.hpp"
#include "airr/render/tracer.hpp"
#include "airr/ui/views/luminance_scale.hpp"
#include "airr/ui/views/plot_widget.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

// The component the view shows of this snapshot (-1: the whole image, the best estimate shown;
// a component is the tracer's alone, and previews have none).
// The component the view shows (its slot: the designer's session keeps every component at its own
// index, then each luminaire's), or -1 for the whole image.
static int shown_component(const studio& st, const render_snapshot& snap) {
  return snap.components && st.view.component < snap.component_layout.count ? st.view.component : -1;
}

// Uploads `pixel(i)` (linear RGB of pixel i) as the view's texture, as the exposure shows it or
// in the luminance view's false colour.
template <class Pixel>
static void upload_pixels(studio& st, int width, int height, float exposure, const Pixel& pixel) {
  const luminance_scale scale = luminance_scale::for_exposure(exposure);
  std::vector<std::uint8_t> rgba(std::size_t(width) * height * 4);
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) {
    const float* v = pixel(i);
    if (st.view.luminance) {
      const auto c = scale.colour(v);
      std::copy(c.begin(), c.end(), rgba.begin() + std::ptrdiff_t(4 * i));
    } else {
      for (int c = 0; c < 3; ++c) rgba[4 * i + c] = srgb_encode_8bit(v[c] * exposure);
    }
    rgba[4 * i + 3] = 255;
  }
  st.view.texture.upload(width, height, rgba);
  st.view.uploaded_exposure = exposure;
  st.view.uploaded_luminance = st.view.luminance;
  st.view.uploaded_contrast = false;
}

// Uploads the contrast view of the snapshot's components.
static void upload_contrast(studio& st, const render_snapshot& snap, float exposure) {
  const contrast_scale scale;
  std::vector<std::uint8_t> rgba(std::size_t(snap.width) * snap.height * 4);
  for (std::size_t i = 0; i < std::size_t(snap.width) * snap.height; ++i) {
    const auto c = scale.colour(snap.components->data() + 3 * std::size_t(snap.component_layout.count) * i);
    std::copy(c.begin(), c.end(), rgba.begin() + std::ptrdiff_t(4 * i));
    rgba[4 * i + 3] = 255;
  }
  st.view.texture.upload(snap.width, snap.height, rgba);
  st.view.uploaded_exposure = exposure;
  st.view.uploaded_luminance = false;
  st.view.uploaded_contrast = true;
}

// A false-colour scale bar along the image area's right edge, with labels at `ticks` (position
// on the scale, text), kept as the screenshot region `name`.
static void draw_scale_bar(studio& st, ImDrawList* dl, const ImVec2& origin, const ImVec2& area,
                           const std::vector<std::pair<double, std::string>>& ticks, const char* name) {
  const float font = ImGui::GetFontSize();
  const float x1 = origin.x + area.x - 0.5f * font, x0 = x1 - 0.8f * font;
  const float y0 = origin.y + 0.5f * font, y1 = origin.y + area.y - 0.5f * font;
  if (y1 - y0 < 2 * font) return;
  const int steps = 64;
  for (int k = 0; k < steps; ++k) {
    const float ya = y1 - (y1 - y0) * float(k) / steps, yb = y1 - (y1 - y0) * float(k + 1) / steps;
    dl->AddRectFilled(ImVec2(x0, yb), ImVec2(x1, ya), viridis((k + 0.5) / steps));
  }
  float label_x0 = x0;
  for (const auto& [position, text] : ticks) {
    const float y = y1 - (y1 - y0) * float(position);
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const ImVec2 at(x0 - size.x - 0.4f * font, std::clamp(y - 0.5f * size.y, y0, y1 - size.y));
    dl->AddRectFilled(at, ImVec2(at.x + size.x, at.y + size.y), IM_COL32(20, 20, 20, 200));
    dl->AddText(at, IM_COL32(230, 230, 230, 255), text.c_str());
    dl->AddLine(ImVec2(x0 - 0.3f * font, y), ImVec2(x0, y), IM_COL32(230, 230, 230, 255));
    label_x0 = std::min(label_x0, at.x);
  }
  st.regions[name] = {label_x0, y0, x1, y1};
}

// The luminance view's scale: a label at each decade.
static void draw_luminance_scale(studio& st, ImDrawList* dl, const ImVec2& origin, const ImVec2& area) {
  const luminance_scale scale = luminance_scale::for_exposure(st.view.uploaded_exposure);
  std::vector<std::pair<double, std::string>> ticks;
  for (int d = 0; d <= scale.decades; ++d) {
    char text[48];
    std::snprintf(text, sizeof text, "%.3g%s", scale.bottom() * std::pow(10.0, d),
                  in_cd_m2(st.doc.source) ? " cd/m2" : "");
    ticks.push_back({double(d) / scale.decades, text});
  }
  draw_scale_bar(st, dl, origin, area, ticks, "luminance_scale");
}

// The contrast view's scale: 1, the guidelines' thresholds and its top.
static void draw_contrast_scale(studio& st, ImDrawList* dl, const ImVec2& origin, const ImVec2& area) {
  const contrast_scale scale;
  std::vector<std::pair<double, std::string>> ticks = {{0.0, "1"}};
  for (double t : default_contrast_thresholds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", t);
    ticks.push_back({scale.position(t), text});
  }
  ticks.push_back({1.0, "100 contrast"});
  draw_scale_bar(st, dl, origin, area, ticks, "contrast_scale");
}

static void upload_snapshot(studio& st, const render_snapshot& snap, float exposure) {
  const int component = shown_component(st, snap);
  if (st.view.contrast && snap.components) {
    upload_contrast(st, snap, exposure);
  } else {
    upload_pixels(st, snap.width, snap.height, exposure, [&](std::size_t i) {
      return component < 0 ? snap.shown->data() + 3 * i
                           : snap.components->data() +
                                 3 * (std::size_t(snap.component_layout.count) * i + std::size_t(component));
    });
  }
  st.view.uploaded_component = component;
  st.view.uploaded_ghost = -1;
  st.view.uploaded_generation = snap.generation;
  st.view.uploaded_spp = snap.spp;
  st.view.uploaded_model_image = snap.model_image;
  st.view.uploaded_estimate = estimate_name(snap);
}

void draw_render_view(studio& st, double now) {
  ImGui::Begin("Render", nullptr, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  const render_snapshot snap = st.session->snapshot();
  const float exposure = float(default_exposure(st.doc) * std::exp2(st.settings.exposure_ev));

  // A ghost class the Ghosts window shows (of the image's size) takes the render's place.
  const image_rgb* ghost = st.ghosts.shown_image();
  if (ghost && (ghost->width != snap.width || ghost->height != snap.height)) ghost = nullptr;
  if (ghost && (st.view.uploaded_ghost != st.ghosts.shown || exposure != st.view.uploaded_exposure ||
                st.view.luminance != st.view.uploaded_luminance)) {
    upload_pixels(st, ghost->width, ghost->height, exposure, [&](std::size_t i) { return ghost->rgb.data() + 3 * i; });
    st.view.uploaded_ghost = st.ghosts.shown;
  } else if (!ghost && snap.shown && (snap.spp > 0 || snap.preview) &&
             (snap.generation != st.view.uploaded_generation || snap.spp != st.view.uploaded_spp ||
              estimate_name(snap) != st.view.uploaded_estimate || exposure != st.view.uploaded_exposure ||
              shown_component(st, snap) != st.view.uploaded_component || st.view.uploaded_ghost >= 0 ||
              st.view.luminance != st.view.uploaded_luminance ||
              (st.view.contrast && snap.components) != st.view.uploaded_contrast)) {
    const bool first_of_edit = snap.generation != st.view.uploaded_generation;
    upload_snapshot(st, snap, exposure);
    if (first_of_edit && st.edit_time >= 0 && snap.generation == st.generation) {
      st.first_image_uploaded = true;
      st.first_image_ready_ms.push_back(1e3 * snap.edit_seconds);
      if (snap.model_image) ++st.first_images_from_model;
    }
    // Measure the render's MTF at most twice a second, on new samples only.
    if (!snap.preview && now - st.last_measure_time > 0.5 && snap.spp != st.last_measured_spp) {
      st.analysis.submit_render(snap, st.doc);
      st.last_measure_time = now;
      st.last_measured_spp = snap.spp;
    }
  }

  // Toolbar.
  if (ImGui::Button(st.view.paused ? "Resume" : "Pause")) {
    st.view.paused = !st.view.paused;
    st.session->set_paused(st.view.paused);
  }
  ImGui::SameLine();
  if (ImGui::Button("Fit")) {
    st.view.zoom = 1.0f;
    st.view.pan_x = st.view.pan_y = 0;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(8 * ImGui::GetFontSize());
  ImGui::SliderFloat("exposure (EV)", &st.settings.exposure_ev, -6.0f, 6.0f, "%+.1f");
  ImGui::SameLine();
  if (ImGui::Button("Auto") && snap.shown) {
    // The 99th percentile of luminance maps to 90% of white.
    std::vector<float> lum(std::size_t(snap.width) * snap.height);
    for (std::size_t i = 0; i < lum.size(); ++i) {
      lum[i] = float(rec709_luminance((*snap.shown)[3 * i], (*snap.shown)[3 * i + 1], (*snap.shown)[3 * i + 2]));
    }
    auto q = lum.begin() + std::ptrdiff_t(0.99 * double(lum.size() - 1));
    std::nth_element(lum.begin(), q, lum.end());
    const double base = default_exposure(st.doc);
    if (*q > 0) st.settings.exposure_ev = std::clamp(float(std::log2(0.9 / (*q * base))), -6.0f, 6.0f);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("0 EV shows a white source seen through a lossless retroreflector as white");
  ImGui::SameLine();
  if (ImGui::Checkbox("luminance", &st.view.luminance) && st.view.luminance) st.view.contrast = false;
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Luminance (CIE Y) in false colour over three decades up to the exposure's white, in %s",
                      in_cd_m2(st.doc.source) ? "cd/m2" : "relative units (set the display's luminance for cd/m2)");
  }
  ImGui::SameLine();
  if (ImGui::Checkbox("contrast", &st.view.contrast) && st.view.contrast) st.view.luminance = false;
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "Contrast (aerial + background) / background per pixel, the background everything but the aerial "
        "image (ambient light included), in false colour from 1 to 100; 1.5 just visible, 3 usable, 25 best");
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(9 * ImGui::GetFontSize());
  // The seven components, then each luminaire's light by its name.
  std::vector<std::string> shows = {"whole image", "aerial image", "display, direct", "its reflection",
                                    "the rest",    "room light",   "sunlight",        "luminaires' light"};
  for (std::size_t k = 0; k < st.doc.environment.luminaires.size(); ++k) {
    const std::string& name = st.doc.environment.luminaires[k].name;
    shows.push_back("luminaire " + std::to_string(k) + (name.empty() ? "" : ": " + name));
  }
  int show = st.view.component + 1;
  if (show >= int(shows.size())) show = 0;
  std::vector<const char*> items;
  for (const std::string& s : shows) items.push_back(s.c_str());
  if (ImGui::Combo("##component", &show, items.data(), int(items.size()))) st.view.component = show - 1;
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "The image's components: paths through a retroreflection (the aerial image), the display "
        "seen directly, its plain reflection in the half mirror, the rest, and the room's, the sun's and the "
        "luminaires' light (Environment)");
  }
  ImGui::SameLine();
  const double rays_per_s = snap.seconds > 0 ? double(snap.rays) / snap.seconds : 0.0;
  const int shown = shown_component(st, snap);
  ImGui::Text("%llu spp  %.1f Mrays/s  %.1f s%s%s%s%s", static_cast<unsigned long long>(snap.spp), rays_per_s * 1e-6,
              snap.seconds, ("  " + st.view.uploaded_estimate).c_str(), shown >= 0 ? ": " : "",
              shown >= 0 ? component_layer_names(snap.component_layout.luminaires)[std::size_t(shown)].c_str() : "",
              st.view.paused ? "  (paused)" : "");
  if (!snap.error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", snap.error.c_str());
  if (ghost) {
    ImGui::TextColored(ImVec4(1, 0.55f, 1, 1), "showing the Ghosts window's class %d: %s", st.ghosts.shown + 1,
                       st.ghosts.found->table.classes[std::size_t(st.ghosts.shown)].expression.c_str());
  }

  // Image area: fit the image, then zoom about the cursor and pan by dragging.
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton(
      "image_area", ImVec2(std::max(avail.x, 10.0f), std::max(avail.y - ImGui::GetTextLineHeightWithSpacing(), 10.0f)));
  const ImVec2 area = ImGui::GetItemRectSize();
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(origin, ImVec2(origin.x + area.x, origin.y + area.y), IM_COL32(20, 20, 20, 255));
  if (st.view.texture.id() == 0 || snap.width == 0) {
    ImGui::TextDisabled("waiting for the first samples...");
    ImGui::End();
    return;
  }
  const float fit = std::min(area.x / snap.width, area.y / snap.height);
  const ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0) {
    const float old_zoom = st.view.zoom;
    st.view.zoom = std::clamp(st.view.zoom * std::pow(1.2f, io.MouseWheel), 0.1f, 64.0f);
    // Keep the image point under the cursor fixed.
    const float cx = io.MousePos.x - origin.x - area.x / 2 - st.view.pan_x;
    const float cy = io.MousePos.y - origin.y - area.y / 2 - st.view.pan_y;
    st.view.pan_x -= cx * (st.view.zoom / old_zoom - 1);
    st.view.pan_y -= cy * (st.view.zoom / old_zoom - 1);
  }
  if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
    st.view.pan_x += io.MouseDelta.x;
    st.view.pan_y += io.MouseDelta.y;
  }
  const float scale = fit * st.view.zoom;
  const ImVec2 size(snap.width * scale, snap.height * scale);
  const ImVec2 p0(origin.x + (area.x - size.x) / 2 + st.view.pan_x, origin.y + (area.y - size.y) / 2 + st.view.pan_y);
  dl->PushClipRect(origin, ImVec2(origin.x + area.x, origin.y + area.y), true);
  dl->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(st.view.texture.id())), p0,
               ImVec2(p0.x + size.x, p0.y + size.y));
  dl->PopClipRect();
  if (st.view.uploaded_luminance) draw_luminance_scale(st, dl, origin, area);
  if (st.view.uploaded_contrast) draw_contrast_scale(st, dl, origin, area);
  st.regions["render_image"] = {std::max(p0.x, origin.x), std::max(p0.y, origin.y),
                                std::min(p0.x + size.x, origin.x + area.x), std::min(p0.y + size.y, origin.y + area.y)};
  const glm::dvec2 centre = camera_project(make_camera(st.doc), aerial_image_center(st.doc));
  const glm::dvec2 half(0.5 * st.doc.source.width_mm / snap.mm_per_pixel,
                        0.5 * st.doc.source.height_mm / snap.mm_per_pixel);
  st.regions["render_aerial_image"] = {
      float(p0.x + (centre.x - half.x) * scale), float(p0.y + (centre.y - half.y) * scale),
      float(p0.x + (centre.x + half.x) * scale), float(p0.y + (centre.y + half.y) * scale)};

  // Cursor readout: pixel, linear value, luminance, position in mm on the aerial-image plane
  // (centre (0, 0, D)).
  std::string readout = "cursor outside the image";
  if (hovered) {
    const double px = (io.MousePos.x - p0.x) / scale, py = (io.MousePos.y - p0.y) / scale;
    if (px >= 0 && py >= 0 && px < snap.width && py < snap.height && snap.shown) {
      const int ix = int(px), iy = int(py);
      const float* v = snap.shown->data() + 3 * (std::size_t(iy) * snap.width + ix);
      const double x_mm = (px - 0.5 * snap.width) * snap.mm_per_pixel;
      const double y_mm = (0.5 * snap.height - py) * snap.mm_per_pixel;
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "pixel (%d, %d)  value %.4g %.4g %.4g  Y %.4g %s  at x %+.3f mm, y %+.3f mm  (%.4f mm/px)", ix, iy,
                    v[0], v[1], v[2], rec709_luminance(v[0], v[1], v[2]), image_units(st.doc.source), x_mm, y_mm,
                    snap.mm_per_pixel);
      readout = buf;
      if (snap.components) {
        const auto [aerial, background] =
            aerial_and_background(snap.components->data() +
                                  3 * std::size_t(snap.component_layout.count) * (std::size_t(iy) * snap.width + ix));
        std::snprintf(buf, sizeof buf, "  contrast %.3g", pixel_contrast(aerial, background));
        readout += buf;
      }
    }
  }
  ImGui::TextUnformatted(readout.c_str());
  ImGui::End();
}

}  // namespace airr::ui
