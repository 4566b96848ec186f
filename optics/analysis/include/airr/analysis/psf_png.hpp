#pragma once
// Pictures of PSFs: each on a log scale with mm axes, a scale bar and a colour bar, alone or as a
// row or matrix of panels sharing one colour scale.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "airr/analysis/bokeh.hpp"
#include "airr/analysis/psf_grid.hpp"

namespace airr::analysis {

struct psf_panel {
  const psf_grid* grid = nullptr;
  std::string label;  // the panel's title
};

struct psf_picture_params {
  std::string title;   // above the panels
  int columns = 1;     // panels per row
  double decades = 4;  // the colour scale spans the largest density down by this many decades
  std::string value_title = "log10 density (1/mm^2)";
  int panel_width = 500, panel_height = 400;
};

// 8-bit BGR. Throws measurement_error when there is no panel or a panel without a grid.
cv::Mat render_psf_panels(const std::vector<psf_panel>& panels, const psf_picture_params& params);
void write_psf_panels_png(const std::filesystem::path& path, const std::vector<psf_panel>& panels,
                          const psf_picture_params& params);

// r50 and r80 against the offset through focus, as a PNG plot.
void write_focus_plot_png(const std::filesystem::path& path, const through_focus& tf, const std::string& title);

}  // namespace airr::analysis
