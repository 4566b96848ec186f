#include "airr/analysis/psf_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "airr/core/error.hpp"

namespace airr::analysis {

double psf_grid::integral() const {
  double sum = 0;
  for (double d : density) sum += d;
  return sum * mm_per_pixel * mm_per_pixel;
}

double psf_grid::peak() const { return density.empty() ? 0.0 : *std::max_element(density.begin(), density.end()); }

psf_grid psf_to_grid(const psf_samples& psf, int size, double mm_per_pixel) {
  if (size < 3 || size > 4095 || size % 2 == 0)
    throw measurement_error("PSF picture: " + std::to_string(size) + " pixels per side (an odd number 3..4095)");
  if (!(mm_per_pixel > 0) || !std::isfinite(mm_per_pixel))
    throw measurement_error("PSF picture: the pixel size must be a positive number of mm");
  psf_grid g{size, mm_per_pixel, std::vector<double>(std::size_t(size) * size, 0.0)};
  if (psf.launched == 0) return g;
  const double scale = 1.0 / (double(psf.launched) * mm_per_pixel * mm_per_pixel);
  const double half = 0.5 * (size - 1);
  for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
    // Continuous pixel coordinates of the sample: column from the left, row from the top.
    const double cx = half + psf.offset_mm[i].x / mm_per_pixel, cy = half - psf.offset_mm[i].y / mm_per_pixel;
    const double fx = std::floor(cx), fy = std::floor(cy);
    const double tx = cx - fx, ty = cy - fy;
    const double w = psf.weight[i] * scale;
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const double col = fx + dx, row = fy + dy;
        if (col < 0 || row < 0 || col >= size || row >= size) continue;
        g.density[std::size_t(row) * size + std::size_t(col)] += w * (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
      }
    }
  }
  return g;
}

double psf_square_half_width(const psf_samples& psf, double fraction, double at_least_mm) {
  std::vector<std::pair<double, double>> rw(psf.offset_mm.size());
  double total = 0;
  for (std::size_t i = 0; i < rw.size(); ++i) {
    rw[i] = {std::max(std::abs(psf.offset_mm[i].x), std::abs(psf.offset_mm[i].y)), psf.weight[i]};
    total += psf.weight[i];
  }
  if (total <= 0) return at_least_mm;
  std::sort(rw.begin(), rw.end());
  double acc = 0;
  for (const auto& [r, w] : rw) {
    acc += w;
    if (acc >= fraction * total) return std::max(r, at_least_mm);
  }
  return std::max(rw.back().first, at_least_mm);
}

double psf_picture_half_width(const psf_samples& psf, bool whole) {
  const double half =
      whole ? 1.05 * psf_square_half_width(psf, psf_whole_fraction, 0.0) : 1.25 * psf_square_half_width(psf, 0.95, 0.0);
  return std::max(half, 0.05);
}

psf_section psf_cross_section(const psf_samples& psf, double half_range_mm, double band_mm, int bins) {
  psf_section out;
  out.x_mm.resize(bins);
  out.density.assign(bins, 0.0);
  double total = 0;
  for (double w : psf.weight) total += w;
  for (int b = 0; b < bins; ++b) out.x_mm[b] = -half_range_mm + (b + 0.5) * 2 * half_range_mm / bins;
  for (std::size_t i = 0; i < psf.offset_mm.size(); ++i) {
    const glm::dvec2 o = psf.offset_mm[i];
    if (std::abs(o.y) > band_mm || std::abs(o.x) >= half_range_mm) continue;
    out.density[std::min(bins - 1, int((o.x + half_range_mm) / (2 * half_range_mm) * bins))] += psf.weight[i];
  }
  const double cell_area = (2 * half_range_mm / bins) * (2 * band_mm);
  for (double& d : out.density) d = total > 0 ? d / total / cell_area : 0.0;
  return out;
}

}  // namespace airr::analysis
