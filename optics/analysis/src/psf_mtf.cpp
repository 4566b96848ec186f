#include "airr/analysis/psf_mtf.hpp"

#include <cmath>
#include <numbers>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/interpolate.hpp"

namespace airr::analysis {

static double mtf_at(const psf_samples& psf, double f, double pixel_mm) {
  double re = 0, im = 0, total = 0;
  const double w0 = -2.0 * std::numbers::pi * f;
  for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
    const double phase = w0 * psf.offset_mm[i].x;
    re += psf.weight[i] * std::cos(phase);
    im += psf.weight[i] * std::sin(phase);
    total += psf.weight[i];
  }
  double m = total > 0 ? std::hypot(re, im) / total : 0.0;
  if (pixel_mm > 0 && f > 0) {
    const double x = std::numbers::pi * f * pixel_mm;
    m *= std::abs(std::sin(x) / x);
  }
  return m;
}

psf_mtf_curve psf_mtf(const psf_samples& psf, const psf_mtf_params& p) {
  psf_mtf_curve c;
  for (int i = 0; i < p.points; ++i) {
    const double f = p.max_lp_per_mm * i / std::max(1, p.points - 1);
    c.lp_per_mm.push_back(f);
    c.mtf.push_back(mtf_at(psf, f, p.pixel_mm));
  }
  return c;
}

double psf_mean_mtf(const psf_samples& psf, double max_lp_per_mm, double pixel_mm, int samples) {
  return grid_mean(max_lp_per_mm, samples, [&](double f) { return mtf_at(psf, f, pixel_mm); });
}

double psf_mtf50(const psf_mtf_curve& c) { return first_crossing(c.lp_per_mm, c.mtf, 0.5).value_or(0.0); }

}  // namespace airr::analysis
