#pragma once
// Slanted Gaussian-blurred edges with analytic MTFs, for checking the MTF measurement.
#include <cstdint>

#include <opencv2/core.hpp>

namespace airr::analysis::testing {

struct synthetic_edge_params {
  int width = 200;
  int height = 200;
  double angle_deg = 5;  // tilt of the edge from the vertical (from horizontal if horizontal)
  bool horizontal = false;
  double offset_px = 0;           // shift of the edge from the image centre along the normal
  double sigma_px = 1;            // Gaussian blur standard deviation
  bool pixel_integrated = false;  // average over the pixel area instead of the value at its centre
  int subsamples = 16;            // per axis, for pixel integration
  double dark = 0.1;
  double bright = 0.9;
  bool rising = true;      // dark on the negative side of the normal
  double noise_sigma = 0;  // additive Gaussian noise
  std::uint64_t seed = 1;
};

// CV_64FC1 image of the edge.
cv::Mat make_slanted_edge(const synthetic_edge_params& params);

// exp(-2 pi^2 sigma^2 f^2): MTF of a point-sampled Gaussian edge, f in cycles/pixel.
double gaussian_mtf(double f, double sigma_px);

// sin(pi x) / (pi x).
double sinc(double x);

// Analytic MTF of the edge: Gaussian, times |sinc| when pixel-integrated.
double analytic_mtf(double f, double sigma_px, bool pixel_integrated);

// Frequency where analytic_mtf first falls to 0.5 (bisection).
double analytic_mtf50(double sigma_px, bool pixel_integrated);

}  // namespace airr::analysis::testing
