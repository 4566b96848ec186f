// The Bokeh tab: the blur as a designer judges it. The 2D model PSF (log scale, mm axes, its r50
// circle), the PSF through focus (r50 and r80 against the offset, and a strip of pictures), the
// spot matrix across the aerial image, and r50 over a floating distance x tilt grid with the
// design marked (a click there sets D and tilt). Every view names the layout it shows and says so
// while it still shows the previous one.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <imgui.h>

#include "airr/layout/layout.hpp"
#include "airr/ui/views/plot_widget.hpp"
#include "airr/ui/views/views.hpp"

namespace airr::ui {

namespace {

// A PSF picture's log10 density as a heat map over its square (mm), its floor `decades` below
// `top` (the largest density of the pictures shown together).
plot_heatmap psf_heatmap(const analysis::psf_grid& g, double top, double decades = 4) {
  plot_heatmap m;
  m.nx = m.ny = g.size;
  const double half = 0.5 * (g.size - 1) * g.mm_per_pixel;
  m.x_first = m.y_first = -half;
  m.x_last = m.y_last = half;
  m.value_max = top > 0 ? std::log10(top) : 0.0;
  m.value_min = m.value_max - decades;
  m.values.resize(g.density.size());
  for (int row = 0; row < g.size; ++row)
    for (int col = 0; col < g.size; ++col) {
      const double d = g.at(col, row);
      m.values[std::size_t(g.size - 1 - row) * g.size + col] = d > 0 ? std::log10(d) : m.value_min;
    }
  return m;
}

plot_params picture_params(const analysis::psf_grid& g, const plot_heatmap& m, std::string title, float height) {
  const double half = 0.5 * g.size * g.mm_per_pixel;
  return {.title = std::move(title),
          .x_title = "",
          .y_title = "",
          .x_min = -half,
          .x_max = half,
          .y_min = -half,
          .y_max = half,
          .auto_x = false,
          .auto_y = false,
          .height = height,
          .heatmap = &m,
          .equal_aspect = true};
}

plot_curve circle(const char* label, double r, unsigned colour) {
  plot_curve c{label, {}, {}, colour, true};
  for (int k = 0; k <= 64; ++k) {
    c.x.push_back(r * std::cos(2 * std::numbers::pi * k / 64));
    c.y.push_back(r * std::sin(2 * std::numbers::pi * k / 64));
  }
  return c;
}

// Keeps a plot's area for scripted checks.
void keep(studio& st, const char* name, const plot_hover& h) {
  st.regions[name] = {h.area[0], h.area[1], h.area[2], h.area[3]};
}

}  // namespace

static void draw_psf2d(studio& st, const bokeh_plots* b, float unit) {
  if (b->psf.size > 0) {
    ImGui::Text("2D PSF, r50 %.3f mm", b->r50_mm);
    const plot_heatmap m = psf_heatmap(b->psf, b->psf.peak());
    char title[96];
    std::snprintf(title, sizeof title, "log10 (1/mm^2), %.0f decades", m.value_max - m.value_min);
    plot_params pp = picture_params(b->psf, m, title, 2.0f * unit);
    pp.x_title = "x, y up (mm)";
    const plot_hover h = draw_plot("psf2d", {circle("r50", b->r50_mm, IM_COL32(255, 255, 255, 255))}, pp);
    keep(st, "plot_psf2d", h);
    st.bokeh_shown.psf_area = {h.area[0], h.area[1], h.area[2], h.area[3]};
    st.bokeh_shown.psf_x_mm = {h.range[0], h.range[1]};
  }
}

static void draw_focus(studio& st, const bokeh_plots* b, float unit) {
  if (!b->focus.planes.empty()) {
    plot_curve r50{"r50", {}, {}}, r80{"r80", {}, {}};
    double top = 0;
    for (const auto& p : b->focus.planes) {
      r50.x.push_back(p.offset_mm);
      r50.y.push_back(p.r50_mm);
      r80.x.push_back(p.offset_mm);
      r80.y.push_back(p.r80_mm);
      top = std::max(top, p.r80_mm);
    }
    const plot_curve best{"best focus", {b->focus.best_offset_mm, b->focus.best_offset_mm}, {0.0, top}, 0, true};
    ImGui::Text("through focus: best at %+.2f mm (smallest r50)", b->focus.best_offset_mm);
    keep(st, "plot_focus",
         draw_plot("focus", {r50, r80, best},
                   {.title = "energy radius (mm)",
                    .x_title = "offset along the chief ray (mm, + towards the observer)",
                    .y_title = "",
                    .x_min = -20,
                    .x_max = 20,
                    .y_min = 0,
                    .auto_x = false,
                    .auto_y = true,
                    .height = 0.9f * unit}));
    double peak = 0;
    for (std::size_t i : b->strip) peak = std::max(peak, b->focus.planes[i].grid.peak());
    if (ImGui::BeginTable("focus_strip", int(b->strip.size()))) {
      for (std::size_t i : b->strip) {
        ImGui::TableNextColumn();
        const analysis::focus_plane& p = b->focus.planes[i];
        const plot_heatmap m = psf_heatmap(p.grid, peak);
        char title[48];
        std::snprintf(title, sizeof title, "%+.0f mm", p.offset_mm);
        ImGui::PushID(int(i));
        plot_params pp = picture_params(p.grid, m, title, 0.75f * unit);
        pp.compact = true;
        draw_plot("strip", {}, pp);
        ImGui::PopID();
      }
      ImGui::EndTable();
    }
  }
}

static void draw_spots(studio& st, const bokeh_plots* b, float unit) {
  if (!b->spots.spots.empty()) {
    double peak = 0;
    for (const auto& s : b->spots.spots) peak = std::max(peak, s.grid.peak());
    ImGui::Text("spot matrix, r50 (mm)");
    if (ImGui::BeginTable("spots", b->spots.n)) {
      for (std::size_t i = 0; i < b->spots.spots.size(); ++i) {
        ImGui::TableNextColumn();
        const analysis::field_spot& s = b->spots.spots[i];
        const plot_heatmap m = psf_heatmap(s.grid, peak);
        char title[48];
        if (s.missed.empty())
          std::snprintf(title, sizeof title, "%.3f", s.r50_mm);
        else
          std::snprintf(title, sizeof title, "not reached");
        ImGui::PushID(int(i));
        plot_params pp = picture_params(s.grid, m, title, 0.62f * unit);
        pp.compact = true;
        const plot_hover h = draw_plot("spot", {}, pp);
        if (i == 0) st.regions["plot_spots"] = {h.area[0], h.area[1], h.area[2], h.area[3]};
        ImGui::PopID();
      }
      ImGui::EndTable();
    }
  }
}

static void draw_blur_map(studio& st, const bokeh_plots* b, float unit) {
  if (!b->map_r50_mm.empty()) {
    double lo = 1e300, hi = 0;
    for (double v : b->map_r50_mm)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(hi > lo)) lo = 0, hi = std::max(hi, 1e-6);
    const plot_heatmap map{b->map_r50_mm,
                           int(b->map_d_mm.size()),
                           int(b->map_tilt_deg.size()),
                           b->map_d_mm.front(),
                           b->map_d_mm.back(),
                           b->map_tilt_deg.front(),
                           b->map_tilt_deg.back(),
                           lo,
                           hi};
    const double hx =
        0.5 * (b->map_d_mm.back() - b->map_d_mm.front()) / std::max<std::size_t>(1, b->map_d_mm.size() - 1);
    const double hy =
        0.5 * (b->map_tilt_deg.back() - b->map_tilt_deg.front()) / std::max<std::size_t>(1, b->map_tilt_deg.size() - 1);
    const std::vector<plot_curve> design = {
        {"design", {b->floating_distance_mm}, {b->tilt_deg}, IM_COL32(255, 255, 255, 255)}};
    char title[96];
    std::snprintf(title, sizeof title, "r50 %.2f to %.2f mm", lo, hi);
    ImGui::Text("blur over D x tilt (click: set them)");
    const plot_hover h = draw_plot("blur_map", design,
                                   {.title = title,
                                    .x_title = "floating distance D (mm)",
                                    .y_title = "tilt (deg)",
                                    .x_min = b->map_d_mm.front() - hx,
                                    .x_max = b->map_d_mm.back() + hx,
                                    .y_min = b->map_tilt_deg.front() - hy,
                                    .y_max = b->map_tilt_deg.back() + hy,
                                    .auto_x = false,
                                    .auto_y = false,
                                    .height = 1.3f * unit,
                                    .heatmap = &map});
    keep(st, "plot_blur_map", h);
    const double fx = (b->floating_distance_mm - (b->map_d_mm.front() - hx)) / (b->map_d_mm.size() * 2 * hx);
    const double fy = (b->tilt_deg - (b->map_tilt_deg.front() - hy)) / (b->map_tilt_deg.size() * 2 * hy);
    st.bokeh_shown.marker = {h.area[0] + float(fx) * (h.area[2] - h.area[0]),
                             h.area[3] - float(fy) * (h.area[3] - h.area[1])};
    st.bokeh_shown.marker_d_tilt = {b->floating_distance_mm, b->tilt_deg};
    if (h.clicked) {
      try {
        set_floating_distance(st.doc, h.x);
        st.doc.sheet().pose.pitch_deg = h.y;
        char msg[96];
        std::snprintf(msg, sizeof msg, "floating distance %.1f mm, tilt %.1f deg (from the blur map)", h.x, h.y);
        st.status = msg;
      } catch (const std::exception& e) {
        st.status = e.what();
      }
    }
  }
}

void draw_bokeh_tab(studio& st) {
  const auto b = st.analysis.bokeh();
  if (!b) {
    ImGui::TextDisabled("computing the bokeh views ...");
    return;
  }
  const bool current = b->generation == st.generation;
  char layout[96];
  std::snprintf(layout, sizeof layout, "D %.0f mm, tilt %.1f deg%s", b->floating_distance_mm, b->tilt_deg,
                current ? "" : " (previous layout)");
  st.bokeh_shown = {.generation = b->generation, .current = current, .r50_mm = b->r50_mm};
  ImGui::Text("%s", layout);
  if (!current) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "updating");
  }
  if (!b->error.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", b->error.c_str());
  const float unit = std::max(60.0f, (ImGui::GetContentRegionAvail().y - 9 * ImGui::GetFrameHeightWithSpacing()) /
                                         5.6f / (ImGui::GetFontSize() / 13.0f));
  if (ImGui::BeginTable("bokeh_top", 2)) {
    ImGui::TableNextColumn();
    draw_psf2d(st, b.get(), unit);
    ImGui::TableNextColumn();
    draw_spots(st, b.get(), unit);
    ImGui::EndTable();
  }
  draw_focus(st, b.get(), unit);
  draw_blur_map(st, b.get(), unit);
  ImGui::TextDisabled("2D PSF %.0f ms, through focus %.0f ms, spots %.0f ms, map %.0f ms", b->psf_ms, b->focus_ms,
                      b->spots_ms, b->map_ms);
}

}  // namespace airr::ui
