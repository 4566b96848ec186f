#include "synthetic_edge.hpp"

#include <cmath>
#include <numbers>

namespace airr::analysis::testing {

cv::Mat make_slanted_edge(const synthetic_edge_params& p) {
  const double theta = p.angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(theta), s = std::sin(theta);
  const double cx = 0.5 * (p.width - 1), cy = 0.5 * (p.height - 1);
  const double polarity = p.rising ? 1.0 : -1.0;
  auto value = [&](double x, double y) {
    // Signed distance to the edge line: across x for a near-vertical edge, across y otherwise.
    const double d =
        p.horizontal ? (y - cy) * c - (x - cx) * s - p.offset_px : (x - cx) * c - (y - cy) * s - p.offset_px;
    const double step = 0.5 * (1.0 + std::erf(polarity * d / (p.sigma_px * std::numbers::sqrt2)));
    return p.dark + (p.bright - p.dark) * step;
  };
  cv::Mat img(p.height, p.width, CV_64FC1);
  const int n = p.pixel_integrated ? p.subsamples : 1;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      double sum = 0;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double ox = p.pixel_integrated ? (i + 0.5) / n - 0.5 : 0.0;
          const double oy = p.pixel_integrated ? (j + 0.5) / n - 0.5 : 0.0;
          sum += value(x + ox, y + oy);
        }
      img.at<double>(y, x) = sum / (n * n);
    }
  if (p.noise_sigma > 0) {
    cv::RNG rng(p.seed);
    cv::Mat noise(img.size(), CV_64FC1);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, p.noise_sigma);
    img += noise;
  }
  return img;
}

double gaussian_mtf(double f, double sigma_px) {
  return std::exp(-2.0 * std::numbers::pi * std::numbers::pi * sigma_px * sigma_px * f * f);
}

double sinc(double x) {
  if (std::abs(x) < 1e-12) return 1.0;
  return std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
}

double analytic_mtf(double f, double sigma_px, bool pixel_integrated) {
  return gaussian_mtf(f, sigma_px) * (pixel_integrated ? std::abs(sinc(f)) : 1.0);
}

double analytic_mtf50(double sigma_px, bool pixel_integrated) {
  double lo = 0, hi = 1;  // analytic_mtf is decreasing on [0, 1]
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (analytic_mtf(mid, sigma_px, pixel_integrated) > 0.5 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace airr::analysis::testing
