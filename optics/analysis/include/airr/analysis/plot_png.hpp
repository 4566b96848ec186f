#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace airr::analysis {

struct plot_series {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  std::optional<cv::Scalar> colour;  // BGR; a palette colour by index if empty
  bool points = false;               // a dot at each point, no line
};

struct plot_params {
  std::string title;
  std::string x_title = "spatial frequency (lp/mm)";
  std::string y_title = "MTF";
  std::optional<double> x_min, x_max, y_min, y_max;  // from the data if empty
  int width = 960;
  int height = 640;
};

// Distinct BGR colours cycled through for series without a colour.
cv::Scalar plot_palette_colour(int index);

// Line (or dot) plot on a white background with axes, ticks, tick labels, axis titles and a legend.
cv::Mat render_plot(const std::vector<plot_series>& series, const plot_params& params = {});

// render_plot written as PNG atomically.
void write_plot_png(const std::filesystem::path& path, const std::vector<plot_series>& series,
                    const plot_params& params = {});

struct heatmap_params {
  std::string title, x_title, y_title, value_title;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;  // the first and last grid nodes' coordinates
  double value_min = 0, value_max = 1;                // the colour bar's ends (values beyond: clamped)
  std::optional<std::pair<double, double>> marker;    // a position to mark (x, y), and its label
  std::string marker_label;
  std::string scale_bar_unit;  // non-empty: a bar of a round length in x's unit, e.g. "mm", bottom left
  int width = 900;
  int height = 760;
};

// Values on an nx x ny grid (row j at y_min + j dy, y up) as coloured cells (viridis; non-finite
// values grey), with axes, ticks, titles, a colour bar and an optional marker.
cv::Mat render_heatmap(const std::vector<double>& values, int nx, int ny, const heatmap_params& params);
void write_heatmap_png(const std::filesystem::path& path, const std::vector<double>& values, int nx, int ny,
                       const heatmap_params& params);

// An 8-bit BGR image written as PNG atomically.
void write_png(const std::filesystem::path& path, const cv::Mat& img);

}  // namespace airr::analysis
