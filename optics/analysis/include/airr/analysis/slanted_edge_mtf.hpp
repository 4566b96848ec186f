#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace airr::analysis {

enum class edge_orientation { near_vertical, near_horizontal };
inline constexpr const char* edge_orientation_names[] = {"near-vertical", "near-horizontal"};

struct slanted_edge_params {
  std::optional<cv::Rect> roi;        // region holding one straight edge; the whole image if empty
  int oversampling = 4;               // bins per pixel along the edge normal
  double max_cycles_per_pixel = 1.0;  // highest frequency reported
};

struct mtf_curve {
  std::vector<double> cycles_per_pixel;  // along the edge normal, starting at 0
  std::vector<double> mtf;               // normalised to 1 at zero frequency
  // Signed tilt of the edge from the image axis it runs along: atan(dx/dy) for a near-vertical
  // edge, atan(dy/dx) for a near-horizontal one (image coordinates, y pointing down).
  double edge_angle_deg = 0;
  edge_orientation orientation = edge_orientation::near_vertical;
  bool rising = true;  // dark-to-bright going right (vertical) or down (horizontal)
  double nyquist_cycles_per_pixel = 0.5;
  double esf_contrast = 0;          // bright minus dark plateau of the edge spread function
  double window_half_width_px = 0;  // half-width of the Hamming window applied to the LSF
  cv::Rect roi;                     // the region actually analysed
};

// Slanted-edge (ISO 12233 e-SFR style) MTF of a linear greyscale image (CV_64FC1 or CV_32FC1).
// Throws std::runtime_error when the region is too small, holds NaN/inf, is flat, or shows no
// usable straight edge.
mtf_curve slanted_edge_mtf(const cv::Mat& image, const slanted_edge_params& params = {});

// Spatial frequencies in line pairs per mm for a pixel of mm_per_pixel millimetres.
std::vector<double> to_lp_per_mm(const std::vector<double>& cycles_per_pixel, double mm_per_pixel);

}  // namespace airr::analysis
