#include "airr/analysis/psf_mtf.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <tbb/parallel_for.h>

#include "airr/analysis/mtf_metrics.hpp"

namespace airr::analysis {

// |E[exp(-2 pi i f x)]| at f = k * step, k = 0 .. count - 1, times the pixel's aperture. The phase
// advances by one rotation per frequency step (a complex product instead of a cosine and a sine),
// over blocks of samples in parallel joined in order, so the result does not depend on threads.
static std::vector<double> mtf_on_grid(const psf_samples& psf, double step, int count, double pixel_mm,
                                       bool along_y = false) {
  using cplx = std::complex<double>;
  constexpr std::size_t block = 4096;
  const std::size_t n = psf.offset_mm.size(), blocks = (n + block - 1) / block;
  std::vector<std::vector<cplx>> parts(blocks, std::vector<cplx>(std::size_t(count)));
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::vector<cplx>& acc = parts[b];
    for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
      const double x = along_y ? psf.offset_mm[i].y : psf.offset_mm[i].x;
      const cplx turn = std::polar(1.0, -2.0 * std::numbers::pi * step * x);
      cplx phase = psf.weight[i];
      for (int k = 0; k < count; ++k) {
        acc[k] += phase;
        phase *= turn;
      }
    }
  });
  std::vector<cplx> sum(static_cast<std::size_t>(count));
  for (const auto& part : parts)
    for (int k = 0; k < count; ++k) sum[k] += part[k];
  const double total = sum.empty() ? 0.0 : sum[0].real();
  std::vector<double> mtf(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    mtf[k] = total > 0 ? std::abs(sum[k]) / total : 0.0;
    const double f = k * step;
    if (pixel_mm > 0 && f > 0) {
      const double x = std::numbers::pi * f * pixel_mm;
      mtf[k] *= std::abs(std::sin(x) / x);
    }
  }
  return mtf;
}

psf_mtf_curve psf_mtf(const psf_samples& psf, const psf_mtf_params& p) {
  psf_mtf_curve c;
  const double step = p.max_lp_per_mm / std::max(1, p.points - 1);
  c.mtf = mtf_on_grid(psf, step, std::max(p.points, 0), p.pixel_mm, p.along_y);
  for (int i = 0; i < p.points; ++i) c.lp_per_mm.push_back(p.max_lp_per_mm * i / std::max(1, p.points - 1));
  return c;
}

double psf_mean_mtf(const psf_samples& psf, double max_lp_per_mm, double pixel_mm, int samples) {
  // The mean over the grid max * i / samples, i = 1 .. samples (grid_mean's).
  const std::vector<double> mtf = mtf_on_grid(psf, max_lp_per_mm / samples, samples + 1, pixel_mm);
  double sum = 0;
  for (int i = 1; i <= samples; ++i) sum += mtf[i];
  return sum / samples;
}

double psf_mtf50(const psf_mtf_curve& c) { return first_crossing(c.lp_per_mm, c.mtf, 0.5).value_or(0.0); }

}  // namespace airr::analysis
