#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace airr::analysis {

struct plot_series {
  std::string label;
  std::vector<double> x;
  std::vector<double> y;
  std::optional<cv::Scalar> colour;  // BGR; a palette colour by index if empty
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

// Line plot on a white background with axes, ticks, tick labels, axis titles and a legend.
cv::Mat render_plot(const std::vector<plot_series>& series, const plot_params& params = {});

// render_plot written as PNG atomically.
void write_plot_png(const std::filesystem::path& path, const std::vector<plot_series>& series,
                    const plot_params& params = {});

}  // namespace airr::analysis
