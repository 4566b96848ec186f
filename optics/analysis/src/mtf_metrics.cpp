#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "airr/core/interpolate.hpp"

namespace airr::analysis {

double interpolate_mtf(const mtf_curve& curve, double cycles_per_pixel) {
  const auto& f = curve.cycles_per_pixel;
  if (f.empty() || f.size() != curve.mtf.size()) throw measurement_error("MTF curve is empty");
  if (cycles_per_pixel > f.back()) return 0.0;
  return interpolate_linear(f, curve.mtf, cycles_per_pixel);
}

std::optional<double> first_crossing(const std::vector<double>& x, const std::vector<double>& y, double level) {
  for (std::size_t i = 1; i < x.size() && i < y.size(); ++i) {
    if (y[i - 1] >= level && y[i] < level) return x[i - 1] + (y[i - 1] - level) / (y[i - 1] - y[i]) * (x[i] - x[i - 1]);
  }
  return std::nullopt;
}

std::optional<mtf50_result> mtf50(const mtf_curve& curve, double mm_per_pixel) {
  const auto f = first_crossing(curve.cycles_per_pixel, curve.mtf, 0.5);
  if (!f) return std::nullopt;
  mtf50_result r;
  r.cycles_per_pixel = *f;
  if (mm_per_pixel > 0) r.lp_per_mm = r.cycles_per_pixel / mm_per_pixel;
  return r;
}

mean_mtf_result mean_mtf(const mtf_curve& curve, double mm_per_pixel, const mean_mtf_params& params) {
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw measurement_error("pixel size must be a positive number of mm, got " + std::to_string(mm_per_pixel));
  if (!(params.max_lp_per_mm > 0) || params.samples < 1)
    throw measurement_error("mean MTF needs a positive range and at least one sample");
  mean_mtf_result r;
  const double nyquist_lp_per_mm = curve.nyquist_cycles_per_pixel / mm_per_pixel;
  r.upper_lp_per_mm = std::min(params.max_lp_per_mm, nyquist_lp_per_mm);
  r.clamped = nyquist_lp_per_mm < params.max_lp_per_mm;
  r.value = grid_mean(r.upper_lp_per_mm, params.samples,
                      [&](double lp_per_mm) { return interpolate_mtf(curve, lp_per_mm * mm_per_pixel); });
  return r;
}

double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= double(n), my /= double(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxx > 0 ? sxy / sxx : 0;
}

std::vector<double> mtf_sigma_from_halves(const std::vector<double>& a, const std::vector<double>& b, int half_window) {
  const int n = int(std::min(a.size(), b.size()));
  std::vector<double> sigma(std::size_t(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    int count = 0;
    for (int j = std::max(0, i - half_window); j <= std::min(n - 1, i + half_window); ++j, ++count) {
      sum += (a[j] - b[j]) * (a[j] - b[j]);
    }
    sigma[std::size_t(i)] = 0.5 * std::sqrt(sum / count);
  }
  return sigma;
}

double readable_up_to(const std::vector<double>& frequency, const std::vector<double>& sigma, double max_sigma) {
  double last = 0;
  for (std::size_t i = 0; i < std::min(frequency.size(), sigma.size()); ++i) {
    if (!(sigma[i] <= max_sigma)) break;
    last = frequency[i];
  }
  return last;
}

}  // namespace airr::analysis
