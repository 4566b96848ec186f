#include "airr/analysis/mtf_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace airr::analysis {

double interpolate_mtf(const mtf_curve& curve, double cycles_per_pixel) {
  const auto& f = curve.cycles_per_pixel;
  const auto& m = curve.mtf;
  if (f.empty() || f.size() != m.size()) throw std::runtime_error("MTF curve is empty");
  if (cycles_per_pixel <= f.front()) return m.front();
  if (cycles_per_pixel > f.back()) return 0.0;
  const auto it = std::lower_bound(f.begin(), f.end(), cycles_per_pixel);
  const size_t i = static_cast<size_t>(it - f.begin());
  const double t = (cycles_per_pixel - f[i - 1]) / (f[i] - f[i - 1]);
  return m[i - 1] + t * (m[i] - m[i - 1]);
}

std::optional<mtf50_result> mtf50(const mtf_curve& curve, double mm_per_pixel) {
  const auto& f = curve.cycles_per_pixel;
  const auto& m = curve.mtf;
  for (size_t i = 1; i < f.size() && i < m.size(); ++i) {
    if (m[i - 1] >= 0.5 && m[i] < 0.5) {
      mtf50_result r;
      r.cycles_per_pixel = f[i - 1] + (m[i - 1] - 0.5) / (m[i - 1] - m[i]) * (f[i] - f[i - 1]);
      if (mm_per_pixel > 0) r.lp_per_mm = r.cycles_per_pixel / mm_per_pixel;
      return r;
    }
  }
  return std::nullopt;
}

mean_mtf_result mean_mtf(const mtf_curve& curve, double mm_per_pixel,
                         const mean_mtf_params& params) {
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw std::runtime_error("pixel size must be a positive number of mm, got " +
                             std::to_string(mm_per_pixel));
  if (!(params.max_lp_per_mm > 0) || params.samples < 1)
    throw std::runtime_error("mean MTF needs a positive range and at least one sample");
  mean_mtf_result r;
  const double nyquist_lp_per_mm = curve.nyquist_cycles_per_pixel / mm_per_pixel;
  r.upper_lp_per_mm = std::min(params.max_lp_per_mm, nyquist_lp_per_mm);
  r.clamped = nyquist_lp_per_mm < params.max_lp_per_mm;
  double sum = 0;
  for (int i = 1; i <= params.samples; ++i) {
    const double lp_per_mm = r.upper_lp_per_mm * i / params.samples;
    sum += interpolate_mtf(curve, lp_per_mm * mm_per_pixel);
  }
  r.value = sum / params.samples;
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

}  // namespace airr::analysis
