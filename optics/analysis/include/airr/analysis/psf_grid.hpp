#pragma once
// A sampled PSF as a picture: its density on a square grid of the aerial-image plane (or of a
// plane across the chief ray), and the numbers read off it.
#include <vector>

#include "airr/layout/psf.hpp"

namespace airr::analysis {

// Density per mm^2 of the PSF's weight per launched sample, so that the grid integrates to the
// PSF's brightness (what falls inside it). x right, y up, centred on the ideal point (the centre
// of the middle pixel); row 0 is the top row.
struct psf_grid {
  int size = 0;  // pixels per side, odd
  double mm_per_pixel = 0;
  std::vector<double> density;

  double at(int col, int row) const { return density[std::size_t(row) * size + col]; }
  double integral() const;  // sum of density x pixel area
  double peak() const;      // the largest density
  double half_width_mm() const { return 0.5 * size * mm_per_pixel; }
};

// Each sample's weight shared among the four pixels around it (bilinear), so that the picture
// does not depend on where the pixel boundaries fall. Throws measurement_error for a size that is
// not odd in [3, 4095] or a pixel that is not positive.
psf_grid psf_to_grid(const psf_samples& psf, int size, double mm_per_pixel);

// The half-width of the square around the ideal point that holds `fraction` of the PSF's weight
// (at least `at_least_mm`).
double psf_square_half_width(const psf_samples& psf, double fraction, double at_least_mm);

// The half-width of a PSF's picture (at least 0.05 mm): the square holding 99.8% of it for an
// image that is integrated (`whole`), else a view of its core and near wings, 1.25 times the
// square holding 95% (sheets' PSFs have wings too long to show whole at a readable scale).
inline constexpr double psf_whole_fraction = 0.998;
double psf_picture_half_width(const psf_samples& psf, bool whole);

// The PSF blurred by a uniform disc of diameter `disc_mm` (each sample moved by a point of the
// disc drawn with its own generator, seeded by `seed`): what a small disc instead of a point shows.
psf_samples blur_by_disc(const psf_samples& psf, double disc_mm, std::uint64_t seed = 1);

// Numbers read off a picture, alike for any grid: the radius around the middle pixel's centre
// holding `fraction` of what the grid holds, and the mean over (0, 1] lp/mm of the MTF along x
// of the grid's line spread (its columns summed).
double grid_energy_radius(const psf_grid& g, double fraction = 0.5);
double grid_mean_mtf(const psf_grid& g);

// A cross-section through the PSF's centre: the weight within `band_mm` of y = 0, in `bins` bins
// over [-half_range_mm, half_range_mm] along x, per mm^2 of the weight of the whole PSF.
struct psf_section {
  std::vector<double> x_mm, density;
};
psf_section psf_cross_section(const psf_samples& psf, double half_range_mm, double band_mm, int bins);

}  // namespace airr::analysis
