#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "airr/formats/scene_json.hpp"

namespace airr::analysis {

namespace {

constexpr int font = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar black(0, 0, 0);
const cv::Scalar grid_grey(225, 225, 225);

struct axis_range {
  double lo = 0;
  double hi = 1;
  double step = 0.1;
};

// Tick step of 1, 2 or 5 times a power of ten giving about `target` intervals.
double nice_step(double span, int target) {
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * magnitude * 1.0000001) return m * magnitude;
  return 10.0 * magnitude;
}

axis_range make_axis(double data_lo, double data_hi, std::optional<double> lo, std::optional<double> hi, int target) {
  axis_range a;
  const bool have_data = data_lo <= data_hi;
  double l = lo.value_or(have_data ? data_lo : 0.0);
  double h = hi.value_or(have_data ? data_hi : 1.0);
  if (!(h > l)) {
    const double pad = std::max(1e-9, std::abs(l) * 0.1 + (l == 0 ? 1.0 : 0.0));
    l -= lo ? 0 : pad;
    h += hi ? 0 : pad;
    if (!(h > l)) h = l + pad;
  }
  a.step = nice_step(h - l, target);
  a.lo = lo ? l : std::floor(l / a.step + 1e-9) * a.step;
  a.hi = hi ? h : std::ceil(h / a.step - 1e-9) * a.step;
  return a;
}

std::string tick_text(double v, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(v) < step * 1e-6) v = 0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

void put_text(cv::Mat& img, const std::string& text, cv::Point anchor, double scale, int thickness, double align_x,
              double align_y, const cv::Scalar& colour = black) {
  int baseline = 0;
  const cv::Size sz = cv::getTextSize(text, font, scale, thickness, &baseline);
  const cv::Point org(anchor.x - static_cast<int>(align_x * sz.width),
                      anchor.y + static_cast<int>((1.0 - align_y) * sz.height));
  cv::putText(img, text, org, font, scale, colour, thickness, cv::LINE_AA);
}

// Vertical text reading bottom to top, centred on `centre`.
void put_vertical_text(cv::Mat& img, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size sz = cv::getTextSize(text, font, scale, 1, &baseline);
  cv::Mat strip(sz.height + baseline + 4, sz.width + 4, CV_8UC3, cv::Scalar::all(255));
  cv::putText(strip, text, cv::Point(2, sz.height + 2), font, scale, black, 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  cv::Rect dst(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols, rotated.rows);
  dst &= cv::Rect(0, 0, img.cols, img.rows);
  rotated(cv::Rect(0, 0, dst.width, dst.height)).copyTo(img(dst));
}

// Ticks and tick labels along the bottom and left of `area` (and grid lines across it).
void draw_ticks(cv::Mat& img, const cv::Rect& area, const axis_range& xa, const axis_range& ya, bool grid_lines) {
  auto px = [&](double x) { return area.x + (x - xa.lo) / (xa.hi - xa.lo) * area.width; };
  auto py = [&](double y) { return area.y + area.height - (y - ya.lo) / (ya.hi - ya.lo) * area.height; };
  const double tick_scale = 0.5;
  for (int i = 0;; ++i) {
    const double v = std::ceil(xa.lo / xa.step - 1e-9) * xa.step + i * xa.step;
    if (v > xa.hi + xa.step * 1e-6) break;
    const int x = static_cast<int>(std::lround(px(v)));
    if (grid_lines) cv::line(img, {x, area.y}, {x, area.y + area.height}, grid_grey, 1);
    cv::line(img, {x, area.y + area.height}, {x, area.y + area.height + 6}, black, 1);
    put_text(img, tick_text(v, xa.step), {x, area.y + area.height + 12}, tick_scale, 1, 0.5, 0.0);
  }
  for (int i = 0;; ++i) {
    const double v = std::ceil(ya.lo / ya.step - 1e-9) * ya.step + i * ya.step;
    if (v > ya.hi + ya.step * 1e-6) break;
    const int y = static_cast<int>(std::lround(py(v)));
    if (grid_lines) cv::line(img, {area.x, y}, {area.x + area.width, y}, grid_grey, 1);
    cv::line(img, {area.x - 6, y}, {area.x, y}, black, 1);
    put_text(img, tick_text(v, ya.step), {area.x - 10, y}, tick_scale, 1, 1.0, 0.5);
  }
}

}  // namespace

cv::Scalar plot_palette_colour(int index) {
  static const std::array<cv::Scalar, 8> palette = {
      cv::Scalar(180, 119, 31),  cv::Scalar(14, 127, 255), cv::Scalar(44, 160, 44),   cv::Scalar(40, 39, 214),
      cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140),  cv::Scalar(194, 119, 227), cv::Scalar(34, 189, 188)};
  return palette[static_cast<size_t>(index) % palette.size()];
}

cv::Mat render_plot(const std::vector<plot_series>& series, const plot_params& params) {
  if (params.width < 200 || params.height < 150) throw measurement_error("plot must be at least 200x150 pixels");
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const auto& s : series) {
    if (s.x.size() != s.y.size())
      throw measurement_error("plot series '" + s.label + "' has different x and y lengths");
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]);
      xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]);
      yhi = std::max(yhi, s.y[i]);
    }
  }
  const axis_range xa = make_axis(xlo, xhi, params.x_min, params.x_max, 10);
  const axis_range ya = make_axis(ylo, yhi, params.y_min, params.y_max, 8);

  cv::Mat img(params.height, params.width, CV_8UC3, cv::Scalar::all(255));
  const int left = 90, right = 30, top = params.title.empty() ? 25 : 55, bottom = 75;
  const cv::Rect area(left, top, params.width - left - right, params.height - top - bottom);
  auto px = [&](double x) { return area.x + (x - xa.lo) / (xa.hi - xa.lo) * area.width; };
  auto py = [&](double y) { return area.y + area.height - (y - ya.lo) / (ya.hi - ya.lo) * area.height; };

  draw_ticks(img, area, xa, ya, true);

  // Curves, clipped to the plot area by drawing into it.
  cv::Mat inner = img(area);
  constexpr int shift = 4;  // sub-pixel precision of the polyline points
  for (size_t s = 0; s < series.size(); ++s) {
    const cv::Scalar colour = series[s].colour.value_or(plot_palette_colour(static_cast<int>(s)));
    std::vector<cv::Point> run;
    auto flush = [&] {
      if (series[s].points) {
        for (const cv::Point& p : run) cv::circle(inner, p, 3 << shift, colour, cv::FILLED, cv::LINE_AA, shift);
      } else if (run.size() >= 2)
        cv::polylines(inner, std::vector<std::vector<cv::Point>>{run}, false, colour, 2, cv::LINE_AA, shift);
      else if (run.size() == 1)
        cv::circle(inner, run[0], 3 << shift, colour, cv::FILLED, cv::LINE_AA, shift);
      run.clear();
    };
    for (size_t i = 0; i < series[s].x.size(); ++i) {
      const double x = series[s].x[i], y = series[s].y[i];
      if (!std::isfinite(x) || !std::isfinite(y)) {
        flush();
        continue;
      }
      // Keep far-off points representable in fixed point; the drawing clips them anyway.
      const double fx = std::clamp(px(x) - area.x, -1e5, 1e5);
      const double fy = std::clamp(py(y) - area.y, -1e5, 1e5);
      run.emplace_back(static_cast<int>(std::lround(fx * (1 << shift))),
                       static_cast<int>(std::lround(fy * (1 << shift))));
    }
    flush();
  }
  cv::rectangle(img, area, black, 1);

  // Titles.
  const double title_scale = 0.6;
  put_text(img, params.x_title, {area.x + area.width / 2, params.height - 28}, title_scale, 1, 0.5, 0.5);
  put_vertical_text(img, params.y_title, {22, area.y + area.height / 2}, title_scale);
  if (!params.title.empty()) put_text(img, params.title, {area.x + area.width / 2, 22}, 0.7, 1, 0.5, 0.5);

  // Legend in the top-right corner of the plot area.
  std::vector<size_t> labelled;
  for (size_t s = 0; s < series.size(); ++s)
    if (!series[s].label.empty()) labelled.push_back(s);
  if (!labelled.empty()) {
    const double legend_scale = 0.5;
    int text_w = 0, text_h = 0, baseline = 0;
    for (size_t s : labelled) {
      const cv::Size sz = cv::getTextSize(series[s].label, font, legend_scale, 1, &baseline);
      text_w = std::max(text_w, sz.width);
      text_h = std::max(text_h, sz.height);
    }
    const int row_h = text_h + 12, sample_w = 36, pad = 10;
    const cv::Rect box(area.x + area.width - (text_w + sample_w + 3 * pad) - 10, area.y + 10,
                       text_w + sample_w + 3 * pad, static_cast<int>(labelled.size()) * row_h + pad);
    cv::rectangle(img, box, cv::Scalar::all(255), cv::FILLED);
    cv::rectangle(img, box, black, 1);
    for (size_t i = 0; i < labelled.size(); ++i) {
      const size_t s = labelled[i];
      const cv::Scalar colour = series[s].colour.value_or(plot_palette_colour(static_cast<int>(s)));
      const int cy = box.y + pad / 2 + static_cast<int>(i) * row_h + row_h / 2;
      if (series[s].points)
        cv::circle(img, {box.x + pad + sample_w / 2, cy}, 4, colour, cv::FILLED, cv::LINE_AA);
      else
        cv::line(img, {box.x + pad, cy}, {box.x + pad + sample_w, cy}, colour, 2, cv::LINE_AA);
      put_text(img, series[s].label, {box.x + 2 * pad + sample_w, cy}, legend_scale, 1, 0.0, 0.5);
    }
  }
  return img;
}

cv::Mat render_heatmap(const std::vector<double>& values, int nx, int ny, const heatmap_params& params) {
  if (params.width < 300 || params.height < 200) throw measurement_error("heatmap must be at least 300x200 pixels");
  if (nx < 1 || ny < 1 || values.size() != std::size_t(nx) * std::size_t(ny)) {
    throw measurement_error("heatmap values do not fill its " + std::to_string(nx) + " x " + std::to_string(ny) +
                            " grid");
  }
  if (!(params.value_max > params.value_min)) throw measurement_error("heatmap value range is empty");
  // Each node owns the cell around it; the axes span the cells.
  const double dx = nx > 1 ? (params.x_max - params.x_min) / (nx - 1) : 1.0;
  const double dy = ny > 1 ? (params.y_max - params.y_min) / (ny - 1) : 1.0;
  const double x_lo = params.x_min - dx / 2, x_hi = params.x_max + dx / 2;
  const double y_lo = params.y_min - dy / 2, y_hi = params.y_max + dy / 2;
  const axis_range xa = make_axis(x_lo, x_hi, x_lo, x_hi, 8), ya = make_axis(y_lo, y_hi, y_lo, y_hi, 8);

  cv::Mat img(params.height, params.width, CV_8UC3, cv::Scalar::all(255));
  const int left = 90, right = 140, top = params.title.empty() ? 25 : 55, bottom = 75;
  const cv::Rect area(left, top, params.width - left - right, params.height - top - bottom);
  cv::Mat codes(ny, nx, CV_8U), missing(ny, nx, CV_8U, cv::Scalar(0));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double v = values[std::size_t(j) * nx + i];
      const int row = ny - 1 - j;  // y up
      if (!std::isfinite(v)) missing.at<unsigned char>(row, i) = 255;
      const double t = std::isfinite(v) ? (v - params.value_min) / (params.value_max - params.value_min) : 0.0;
      codes.at<unsigned char>(row, i) = static_cast<unsigned char>(std::lround(255 * std::clamp(t, 0.0, 1.0)));
    }
  }
  cv::Mat colours, cells, holes;
  cv::applyColorMap(codes, colours, cv::COLORMAP_VIRIDIS);
  colours.setTo(cv::Scalar::all(160), missing);
  cv::resize(colours, cells, area.size(), 0, 0, cv::INTER_NEAREST);
  cells.copyTo(img(area));
  cv::rectangle(img, area, black, 1);
  draw_ticks(img, area, xa, ya, false);

  if (params.marker) {
    const double mx = area.x + (params.marker->first - xa.lo) / (xa.hi - xa.lo) * area.width;
    const double my = area.y + area.height - (params.marker->second - ya.lo) / (ya.hi - ya.lo) * area.height;
    const cv::Point c(static_cast<int>(std::lround(mx)), static_cast<int>(std::lround(my)));
    if (area.contains(c)) {
      cv::circle(img, c, 9, cv::Scalar::all(255), 3, cv::LINE_AA);
      cv::circle(img, c, 9, black, 1, cv::LINE_AA);
      put_text(img, params.marker_label, {c.x + 13, c.y}, 0.5, 2, 0.0, 0.5, cv::Scalar::all(255));
      put_text(img, params.marker_label, {c.x + 13, c.y}, 0.5, 1, 0.0, 0.5);
    }
  }

  if (!params.scale_bar_unit.empty()) {
    // An eighth to a third of the axis: 1, 2 or 5 times a power of ten.
    const double length = nice_step(xa.hi - xa.lo, 8);
    const int px = static_cast<int>(std::lround(length / (xa.hi - xa.lo) * area.width));
    const cv::Point a0(area.x + 15, area.y + area.height - 18), a1(a0.x + px, a0.y);
    cv::line(img, a0, a1, black, 6);
    cv::line(img, a0, a1, cv::Scalar::all(255), 3);
    const std::string label = tick_text(length, length) + " " + params.scale_bar_unit;
    put_text(img, label, {a0.x, a0.y - 14}, 0.5, 3, 0.0, 0.5, black);
    put_text(img, label, {a0.x, a0.y - 14}, 0.5, 1, 0.0, 0.5, cv::Scalar::all(255));
  }

  // Colour bar with its own ticks.
  const cv::Rect bar(area.x + area.width + 25, area.y, 22, area.height);
  cv::Mat ramp(256, 1, CV_8U), ramp_colours, ramp_cells;
  for (int k = 0; k < 256; ++k) ramp.at<unsigned char>(k) = static_cast<unsigned char>(255 - k);
  cv::applyColorMap(ramp, ramp_colours, cv::COLORMAP_VIRIDIS);
  cv::resize(ramp_colours, ramp_cells, bar.size(), 0, 0, cv::INTER_LINEAR);
  ramp_cells.copyTo(img(bar));
  cv::rectangle(img, bar, black, 1);
  const axis_range va = make_axis(params.value_min, params.value_max, params.value_min, params.value_max, 5);
  for (int i = 0;; ++i) {
    const double v = std::ceil(va.lo / va.step - 1e-9) * va.step + i * va.step;
    if (v > va.hi + va.step * 1e-6) break;
    const int y = static_cast<int>(std::lround(bar.y + bar.height - (v - va.lo) / (va.hi - va.lo) * bar.height));
    cv::line(img, {bar.x + bar.width, y}, {bar.x + bar.width + 5, y}, black, 1);
    put_text(img, tick_text(v, va.step), {bar.x + bar.width + 8, y}, 0.45, 1, 0.0, 0.5);
  }
  put_vertical_text(img, params.value_title, {bar.x + bar.width + 70, bar.y + bar.height / 2}, 0.55);

  put_text(img, params.x_title, {area.x + area.width / 2, params.height - 28}, 0.6, 1, 0.5, 0.5);
  put_vertical_text(img, params.y_title, {22, area.y + area.height / 2}, 0.6);
  if (!params.title.empty()) put_text(img, params.title, {area.x + area.width / 2, 22}, 0.7, 1, 0.5, 0.5);
  return img;
}

void write_heatmap_png(const std::filesystem::path& path, const std::vector<double>& values, int nx, int ny,
                       const heatmap_params& params) {
  write_png(path, render_heatmap(values, nx, ny, params));
}

void write_plot_png(const std::filesystem::path& path, const std::vector<plot_series>& series,
                    const plot_params& params) {
  write_png(path, render_plot(series, params));
}

void write_png(const std::filesystem::path& path, const cv::Mat& img) {
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", img, png)) throw input_error(path.string() + ": PNG encoding failed");
  airr::write_file_atomic(path.string(), std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

}  // namespace airr::analysis
