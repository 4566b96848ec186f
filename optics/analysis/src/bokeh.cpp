#include "airr/analysis/bokeh.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"

namespace airr::analysis {

// The smallest r50's offset, refined by the parabola through it and its two neighbours.
static double best_offset(const std::vector<focus_plane>& planes) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < planes.size(); ++i)
    if (planes[i].r50_mm < planes[k].r50_mm) k = i;
  if (k == 0 || k + 1 >= planes.size()) return planes[k].offset_mm;
  const double x0 = planes[k - 1].offset_mm, x1 = planes[k].offset_mm, x2 = planes[k + 1].offset_mm;
  const double y0 = planes[k - 1].r50_mm, y1 = planes[k].r50_mm, y2 = planes[k + 1].r50_mm;
  const double denom = (x0 - x1) * (x0 - x2) * (x1 - x2);
  const double a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / denom;
  const double b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / denom;
  if (!(a > 0)) return x1;
  return std::clamp(-b / (2 * a), x0, x2);
}

through_focus compute_through_focus(const scene& s, const retro_model_list& models, const std::vector<double>& offsets,
                                    const focus_params& p, int grid_size) {
  if (offsets.empty()) throw input_error("through focus: no offsets");
  const focus_bundle bundle = sample_focus_bundle(s, models, p, aerial_image_center(s));
  through_focus out;
  out.sheets = bundle.sheets;
  // The planes in parallel: cut, picture extent, radii; then the pictures on one common grid.
  std::vector<psf_samples> cuts(offsets.size());
  std::vector<double> half_widths(offsets.size());
  out.planes.resize(offsets.size());
  tbb::parallel_for(std::size_t(0), offsets.size(), [&](std::size_t i) {
    cuts[i] = cut_focus_bundle(bundle, offsets[i]);
    half_widths[i] = psf_picture_half_width(cuts[i], false);
    const std::vector<double> radii = energy_radii(cuts[i], {0.5, 0.8});
    out.planes[i].offset_mm = offsets[i];
    out.planes[i].r50_mm = radii[0];
    out.planes[i].r80_mm = radii[1];
  });
  const double pixel = 2 * *std::max_element(half_widths.begin(), half_widths.end()) / grid_size;
  tbb::parallel_for(std::size_t(0), offsets.size(), [&](std::size_t i) {
    out.planes[i].grid = psf_to_grid(cuts[i], grid_size, pixel);
    out.planes[i].peak_per_mm2 = out.planes[i].grid.peak();
  });
  out.best_offset_mm = best_offset(out.planes);
  return out;
}

spot_matrix compute_spot_matrix(const scene& s, const retro_model_list& models, int n, const psf_params& p,
                                int grid_size, double field_fraction) {
  if (n < 1 || n > 9) throw input_error("spot matrix: " + std::to_string(n) + " points per side (1..9)");
  if (!(field_fraction > 0 && field_fraction <= 1))
    throw input_error("spot matrix: the field fraction must be in (0, 1]");
  const part_frame aerial = aerial_image_frame(s);
  const pinhole_camera cam = make_camera(s);
  // The image's axes as the observer sees them: right and up.
  const glm::dvec3 right = glm::dot(aerial.u, cam.right) >= 0 ? aerial.u : -aerial.u;
  const glm::dvec3 up = glm::dot(aerial.v, cam.up) >= 0 ? aerial.v : -aerial.v;
  spot_matrix out;
  out.n = n;
  std::vector<psf_samples> psfs;
  double half_width = 0.05;  // when no point reaches a sheet, empty pictures of the smallest size
  for (int row = 0; row < n; ++row) {
    for (int col = 0; col < n; ++col) {
      field_spot spot;
      spot.col = col;
      spot.row = row;
      const double fx = n == 1 ? 0.0 : (double(col) / (n - 1) - 0.5) * field_fraction;
      const double fy = n == 1 ? 0.0 : (0.5 - double(row) / (n - 1)) * field_fraction;
      spot.x_mm = fx * aerial.width;
      spot.y_mm = fy * aerial.height;
      spot.point = aerial.center + spot.x_mm * right + spot.y_mm * up;
      psf_samples psf;
      try {
        psf = sample_psf(s, models, p, spot.point);
        spot.r50_mm = energy_radius(psf, 0.5);
        spot.brightness = psf.brightness();
        spot.incidence_deg = psf.incidence_deg;
        half_width = std::max(half_width, psf_picture_half_width(psf, false));
      } catch (const input_error& e) {
        spot.missed = e.what();
      }
      psfs.push_back(std::move(psf));
      out.spots.push_back(std::move(spot));
    }
  }
  for (std::size_t i = 0; i < out.spots.size(); ++i)
    out.spots[i].grid = psf_to_grid(psfs[i], grid_size, 2 * half_width / grid_size);
  return out;
}

}  // namespace airr::analysis
