#include "airr/analysis/psf_png.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "airr/analysis/plot_png.hpp"
#include "airr/core/error.hpp"

namespace airr::analysis {

cv::Mat render_psf_panels(const std::vector<psf_panel>& panels, const psf_picture_params& params) {
  if (panels.empty()) throw measurement_error("PSF picture: no panels");
  double top = 0;
  for (const psf_panel& p : panels) {
    if (!p.grid || p.grid->size < 1) throw measurement_error("PSF picture: a panel has no PSF");
    top = std::max(top, p.grid->peak());
  }
  const double log_top = top > 0 ? std::log10(top) : 0.0;
  const int columns = std::clamp(params.columns, 1, int(panels.size()));
  const int rows = int((panels.size() + columns - 1) / columns);
  const int title_h = params.title.empty() ? 0 : 40;
  cv::Mat out(title_h + rows * params.panel_height, columns * params.panel_width, CV_8UC3, cv::Scalar::all(255));
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const psf_grid& g = *panels[k].grid;
    // Heatmap rows run upwards; the grid's row 0 is its top. Empty pixels are the scale's floor.
    std::vector<double> values(g.density.size());
    for (int row = 0; row < g.size; ++row) {
      for (int col = 0; col < g.size; ++col) {
        const double d = g.at(col, row);
        values[std::size_t(g.size - 1 - row) * g.size + col] = d > 0 ? std::log10(d) : log_top - params.decades - 1.0;
      }
    }
    heatmap_params hp;
    hp.title = panels[k].label;
    hp.x_title = "x (mm)";
    hp.y_title = "y (mm)";
    hp.value_title = params.value_title;
    const double half = 0.5 * (g.size - 1) * g.mm_per_pixel;
    hp.x_min = hp.y_min = -half;
    hp.x_max = hp.y_max = half;
    hp.value_min = log_top - params.decades;
    hp.value_max = log_top;
    hp.scale_bar_unit = "mm";
    hp.width = params.panel_width;
    hp.height = params.panel_height;
    const cv::Mat panel = render_heatmap(values, g.size, g.size, hp);
    const int r = int(k) / columns, c = int(k) % columns;
    panel.copyTo(out(
        cv::Rect(c * params.panel_width, title_h + r * params.panel_height, params.panel_width, params.panel_height)));
  }
  if (!params.title.empty()) {
    // Smaller type for a title wider than the picture.
    int baseline = 0;
    double scale = 0.7;
    cv::Size sz = cv::getTextSize(params.title, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    if (sz.width > out.cols - 10) {
      scale *= double(out.cols - 10) / sz.width;
      sz = cv::getTextSize(params.title, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
    }
    cv::putText(out, params.title, {std::max(5, (out.cols - sz.width) / 2), 28}, cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar::all(0), 1, cv::LINE_AA);
  }
  return out;
}

void write_psf_panels_png(const std::filesystem::path& path, const std::vector<psf_panel>& panels,
                          const psf_picture_params& params) {
  write_png(path, render_psf_panels(panels, params));
}

void write_focus_plot_png(const std::filesystem::path& path, const through_focus& tf, const std::string& title) {
  plot_series r50{"r50 (50% energy radius)", {}, {}, {}}, r80{"r80 (80% energy radius)", {}, {}, {}};
  for (const focus_plane& p : tf.planes) {
    r50.x.push_back(p.offset_mm);
    r50.y.push_back(p.r50_mm);
    r80.x.push_back(p.offset_mm);
    r80.y.push_back(p.r80_mm);
  }
  plot_params pp;
  pp.title = title;
  pp.x_title = "offset from the aerial image along the chief ray (mm, + towards the observer)";
  pp.y_title = "energy radius (mm)";
  pp.y_min = 0.0;
  write_plot_png(path, {r50, r80}, pp);
}

}  // namespace airr::analysis
