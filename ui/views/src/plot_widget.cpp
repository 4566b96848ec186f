#include "airr/ui/views/plot_widget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <imgui.h>

namespace airr::ui {

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || target < 1) return ticks;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

unsigned plot_palette(int index) {
  static const ImU32 colours[] = {IM_COL32(80, 160, 255, 255),  IM_COL32(255, 150, 60, 255),
                                  IM_COL32(90, 200, 110, 255),  IM_COL32(230, 80, 90, 255),
                                  IM_COL32(190, 120, 240, 255), IM_COL32(240, 220, 80, 255)};
  return colours[index % 6];
}

unsigned viridis(double t) {
  static const float stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  const double u = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int k = std::min(3, int(u));
  const float f = float(u - k);
  auto mix = [&](int c) { return int(std::lround(stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f)); };
  return IM_COL32(mix(0), mix(1), mix(2), 255);
}

static std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = step >= 1 ? 0 : std::min(6, int(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

plot_hover draw_plot(const char* id, const std::vector<plot_curve>& curves, const plot_params& in) {
  plot_params p = in;
  if (p.auto_x || p.auto_y) {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& c : curves) {
      for (std::size_t i = 0; i < c.x.size() && i < c.y.size(); ++i) {
        if (!std::isfinite(c.x[i]) || !std::isfinite(c.y[i])) continue;
        x0 = std::min(x0, c.x[i]);
        x1 = std::max(x1, c.x[i]);
        y0 = std::min(y0, c.y[i]);
        y1 = std::max(y1, c.y[i]);
      }
    }
    if (x1 >= x0 && p.auto_x) {
      p.x_min = x0;
      p.x_max = x1 > x0 ? x1 : x0 + 1;
    }
    if (y1 >= y0 && p.auto_y) {
      const double pad = 0.05 * std::max(y1 - y0, 1e-9);
      p.y_min = y0 - pad;
      p.y_max = y1 + pad;
    }
  }

  const float scale = ImGui::GetFontSize() / 13.0f;
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = std::max(p.compact ? 30.0f : 100.0f, ImGui::GetContentRegionAvail().x);
  const float height = p.height * scale;
  ImGui::InvisibleButton(id, ImVec2(width, height));
  const bool hovered = ImGui::IsItemHovered();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float line_h = ImGui::GetTextLineHeight();

  // A title too long to share the top line with the y title takes a line of its own above it.
  const float title_w = p.title.empty() ? 0.0f : ImGui::CalcTextSize(p.title.c_str()).x;
  const float y_title_w = p.y_title.empty() || p.compact ? 0.0f : ImGui::CalcTextSize(p.y_title.c_str()).x;
  const float title_line = y_title_w > 0 && title_w > 0 && y_title_w + line_h + title_w > width ? line_h : 0.0f;
  // Plot area inside margins for tick labels and titles.
  const ImVec2 a = p.compact ? ImVec2(origin.x + 0.2f * line_h, origin.y + 1.1f * line_h)
                             : ImVec2(origin.x + 4.2f * line_h, origin.y + title_line + 1.4f * line_h);
  const ImVec2 b = p.compact ? ImVec2(origin.x + width - 0.2f * line_h, origin.y + height - 0.2f * line_h)
                             : ImVec2(origin.x + width - 0.8f * line_h, origin.y + height - 2.4f * line_h);
  if (p.equal_aspect && b.x > a.x && b.y > a.y) {
    const double ux = (p.x_max - p.x_min) / (b.x - a.x), uy = (p.y_max - p.y_min) / (b.y - a.y);
    double& lo = ux > uy ? p.y_min : p.x_min;
    double& hi = ux > uy ? p.y_max : p.x_max;
    const double centre = 0.5 * (lo + hi), half = 0.5 * std::max(ux, uy) * (ux > uy ? b.y - a.y : b.x - a.x);
    lo = centre - half;
    hi = centre + half;
  }
  const ImU32 axis_col = ImGui::GetColorU32(ImGuiCol_Text);
  const ImU32 grid_col = ImGui::GetColorU32(ImGuiCol_TextDisabled, 0.35f);
  dl->AddRectFilled(a, b, ImGui::GetColorU32(ImGuiCol_FrameBg));
  auto sx = [&](double x) { return float(a.x + (x - p.x_min) / (p.x_max - p.x_min) * (b.x - a.x)); };
  auto sy = [&](double y) { return float(b.y - (y - p.y_min) / (p.y_max - p.y_min) * (b.y - a.y)); };
  if (const plot_heatmap* hm = p.heatmap;
      hm && hm->nx > 0 && hm->ny > 0 && hm->values.size() == std::size_t(hm->nx) * std::size_t(hm->ny)) {
    // Each node owns the cell around it.
    const double dx = hm->nx > 1 ? (hm->x_last - hm->x_first) / (hm->nx - 1) : 1.0;
    const double dy = hm->ny > 1 ? (hm->y_last - hm->y_first) / (hm->ny - 1) : 1.0;
    const double range = hm->value_max > hm->value_min ? hm->value_max - hm->value_min : 1.0;
    dl->PushClipRect(a, b, true);
    for (int j = 0; j < hm->ny; ++j) {
      for (int i = 0; i < hm->nx; ++i) {
        const double x = hm->x_first + i * dx, y = hm->y_first + j * dy;
        const double v = hm->values[std::size_t(j) * hm->nx + i];
        dl->AddRectFilled(ImVec2(sx(x - dx / 2), sy(y + dy / 2)), ImVec2(sx(x + dx / 2), sy(y - dy / 2)),
                          std::isfinite(v) ? viridis((v - hm->value_min) / range) : IM_COL32(110, 110, 110, 255));
      }
    }
    dl->PopClipRect();
  }

  plot_hover hover;
  // A title wider than the whole plot is drawn in a smaller font that fits it.
  const auto draw_title = [&](const std::string& text, ImVec2 at, float w, float(&box)[4]) {
    const float shrink = w > width ? width / w : 1.0f;
    dl->AddText(ImGui::GetFont(), ImGui::GetFontSize() * shrink, at, axis_col, text.c_str());
    box[0] = at.x, box[1] = at.y, box[2] = at.x + w * shrink, box[3] = at.y + line_h;
  };
  if (!p.title.empty()) {
    // The y title takes the left; a compact plot's title is centred.
    const float x = p.compact ? (a.x + b.x - title_w) / 2 : b.x - title_w;
    draw_title(p.title, ImVec2(std::max(origin.x, x), origin.y), title_w, hover.title_box);
  }
  const auto xt =
      p.compact ? std::vector<double>{} : nice_ticks(p.x_min, p.x_max, std::max(2, int((b.x - a.x) / (5 * line_h))));
  const auto yt =
      p.compact ? std::vector<double>{} : nice_ticks(p.y_min, p.y_max, std::max(2, int((b.y - a.y) / (2.5f * line_h))));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1, ystep = yt.size() > 1 ? yt[1] - yt[0] : 1;
  for (double t : xt) {
    const float x = sx(t);
    dl->AddLine(ImVec2(x, a.y), ImVec2(x, b.y), grid_col);
    dl->AddLine(ImVec2(x, b.y), ImVec2(x, b.y + 0.3f * line_h), axis_col);
    const std::string s = tick_label(t, xstep);
    const float w = ImGui::CalcTextSize(s.c_str()).x;
    dl->AddText(ImVec2(x - w / 2, b.y + 0.35f * line_h), axis_col, s.c_str());
  }
  for (double t : yt) {
    const float y = sy(t);
    dl->AddLine(ImVec2(a.x, y), ImVec2(b.x, y), grid_col);
    dl->AddLine(ImVec2(a.x - 0.3f * line_h, y), ImVec2(a.x, y), axis_col);
    const std::string s = tick_label(t, ystep);
    const float w = ImGui::CalcTextSize(s.c_str()).x;
    dl->AddText(ImVec2(a.x - 0.45f * line_h - w, y - line_h / 2), axis_col, s.c_str());
  }
  dl->AddRect(a, b, axis_col);
  if (!p.x_title.empty() && !p.compact) {
    const float w = ImGui::CalcTextSize(p.x_title.c_str()).x;
    dl->AddText(ImVec2((a.x + b.x - w) / 2, b.y + 1.35f * line_h), axis_col, p.x_title.c_str());
  }
  if (!p.y_title.empty() && !p.compact) {
    // ImGui draws no vertical text: the y title sits above the y axis.
    draw_title(p.y_title, ImVec2(origin.x, origin.y + title_line), y_title_w, hover.y_title_box);
  }

  dl->PushClipRect(a, b, true);
  for (std::size_t ci = 0; ci < curves.size(); ++ci) {
    const auto& c = curves[ci];
    const ImU32 col = c.colour ? c.colour : plot_palette(int(ci));
    const ImU32 band_col = (col & 0x00ffffffu) | 0x40000000u;  // the curve's colour at a quarter opacity
    for (std::size_t i = 1; i < c.x.size() && i < c.y.size() && i < c.band.size(); ++i) {
      const double x0 = c.x[i - 1], x1 = c.x[i];
      const double lo0 = c.y[i - 1] - c.band[i - 1], hi0 = c.y[i - 1] + c.band[i - 1];
      const double lo1 = c.y[i] - c.band[i], hi1 = c.y[i] + c.band[i];
      if (!std::isfinite(lo0 + hi0 + lo1 + hi1)) continue;
      dl->AddQuadFilled(ImVec2(sx(x0), sy(hi0)), ImVec2(sx(x1), sy(hi1)), ImVec2(sx(x1), sy(lo1)),
                        ImVec2(sx(x0), sy(lo0)), band_col);
    }
    if (c.points) {
      for (std::size_t i = 0; i < c.x.size() && i < c.y.size(); ++i) {
        if (std::isfinite(c.x[i]) && std::isfinite(c.y[i]))
          dl->AddCircleFilled(ImVec2(sx(c.x[i]), sy(c.y[i])), 3 * scale, col);
      }
      continue;
    }
    for (std::size_t i = 1; i < c.x.size() && i < c.y.size(); ++i) {
      if (!std::isfinite(c.y[i - 1]) || !std::isfinite(c.y[i])) continue;
      const ImVec2 p0(sx(c.x[i - 1]), sy(c.y[i - 1])), p1(sx(c.x[i]), sy(c.y[i]));
      if (!c.dashed) {
        dl->AddLine(p0, p1, col, 2.0f * scale);
        continue;
      }
      const float len = std::hypot(p1.x - p0.x, p1.y - p0.y), dash = 5.0f * scale;
      for (float t = 0; t < len; t += 2 * dash) {
        const float t1 = std::min(len, t + dash);
        dl->AddLine(ImVec2(p0.x + (p1.x - p0.x) * t / len, p0.y + (p1.y - p0.y) * t / len),
                    ImVec2(p0.x + (p1.x - p0.x) * t1 / len, p0.y + (p1.y - p0.y) * t1 / len), col, 2.0f * scale);
      }
    }
    if (c.x.size() == 1) dl->AddCircleFilled(ImVec2(sx(c.x[0]), sy(c.y[0])), 3 * scale, col);
  }
  dl->PopClipRect();

  // Legend, top right inside the plot area.
  float ly = a.y + 0.3f * line_h;
  for (std::size_t ci = 0; ci < curves.size(); ++ci) {
    const auto& c = curves[ci];
    if (c.label.empty()) continue;
    const float w = ImGui::CalcTextSize(c.label.c_str()).x;
    const float lx = b.x - w - 2.6f * line_h;
    dl->AddRectFilled(ImVec2(lx - 0.3f * line_h, ly - 0.1f * line_h), ImVec2(b.x - 0.2f * line_h, ly + 1.05f * line_h),
                      ImGui::GetColorU32(ImGuiCol_PopupBg, 0.85f));
    const ImU32 col = c.colour ? c.colour : plot_palette(int(ci));
    if (c.points)
      dl->AddCircleFilled(ImVec2(lx + 0.8f * line_h, ly + line_h / 2), 3 * scale, col);
    else
      dl->AddLine(ImVec2(lx, ly + line_h / 2), ImVec2(lx + 1.6f * line_h, ly + line_h / 2), col, 2.0f * scale);
    dl->AddText(ImVec2(lx + 2.0f * line_h, ly), axis_col, c.label.c_str());
    ly += 1.15f * line_h;
  }

  hover.area[0] = a.x;
  hover.area[1] = a.y;
  hover.area[2] = b.x;
  hover.area[3] = b.y;
  hover.range[0] = p.x_min;
  hover.range[1] = p.x_max;
  hover.range[2] = p.y_min;
  hover.range[3] = p.y_max;
  if (hovered) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    if (m.x >= a.x && m.x <= b.x && m.y >= a.y && m.y <= b.y) {
      hover.active = true;
      hover.clicked = ImGui::IsMouseClicked(0);
      hover.x = p.x_min + (m.x - a.x) / (b.x - a.x) * (p.x_max - p.x_min);
      hover.y = p.y_min + (b.y - m.y) / (b.y - a.y) * (p.y_max - p.y_min);
      dl->AddLine(ImVec2(m.x, a.y), ImVec2(m.x, b.y), grid_col);
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g, %.3g", hover.x, hover.y);
      dl->AddText(ImVec2(m.x + 4, a.y + 2), axis_col, buf);
    }
  }
  return hover;
}

}  // namespace airr::ui
