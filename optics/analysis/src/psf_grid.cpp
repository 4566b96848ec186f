#include "airr/analysis/psf_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "airr/analysis/psf_mtf.hpp"
#include "airr/core/error.hpp"
#include "airr/core/random.hpp"

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

psf_samples blur_by_disc(const psf_samples& psf, double disc_mm, std::uint64_t seed) {
  psf_samples out = psf;
  for (std::size_t i = 0; i < out.offset_mm.size(); ++i) {
    pcg32 rng = sample_rng(i, 7, seed);
    const double r = 0.5 * disc_mm * std::sqrt(rng.next_double()), phi = 2 * std::numbers::pi * rng.next_double();
    out.offset_mm[i] += glm::dvec2(r * std::cos(phi), r * std::sin(phi));
  }
  return out;
}

double grid_energy_radius(const psf_grid& g, double fraction) {
  std::vector<std::pair<double, double>> rw;
  double total = 0;
  const double half = 0.5 * (g.size - 1);
  for (int row = 0; row < g.size; ++row) {
    for (int col = 0; col < g.size; ++col) {
      const double d = g.at(col, row);
      if (d <= 0) continue;
      rw.emplace_back(std::hypot(col - half, row - half) * g.mm_per_pixel, d);
      total += d;
    }
  }
  if (total <= 0) return 0;
  std::sort(rw.begin(), rw.end());
  // Pixels at one radius come in rings of four or eight; between rings, the radius is interpolated
  // by the energy gathered, so that it does not jump from ring to ring.
  double acc = 0, previous_r = 0;
  for (std::size_t i = 0; i < rw.size();) {
    const double r = rw[i].first;
    double ring = 0;
    for (; i < rw.size() && rw[i].first == r; ++i) ring += rw[i].second;
    if (acc + ring >= fraction * total) return previous_r + (r - previous_r) * (fraction * total - acc) / ring;
    acc += ring;
    previous_r = r;
  }
  return rw.back().first;
}

double grid_mean_mtf(const psf_grid& g) {
  psf_samples line;
  const double half = 0.5 * (g.size - 1);
  for (int col = 0; col < g.size; ++col) {
    double sum = 0;
    for (int row = 0; row < g.size; ++row) sum += std::max(0.0, g.at(col, row));
    line.offset_mm.emplace_back((col - half) * g.mm_per_pixel, 0.0);
    line.weight.push_back(sum);
  }
  line.launched = 1;
  return psf_mean_mtf(line, 1.0, 0.0);
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
