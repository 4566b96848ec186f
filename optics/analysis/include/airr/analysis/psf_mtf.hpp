#pragma once
// MTF of the model PSF: |E[exp(-2 pi i f x)]| over the PSF's offsets along the measurement
// direction (x: what a near-vertical edge measures; or y), optionally times a square pixel's
// aperture.
#include <vector>

#include "airr/layout/psf.hpp"

namespace airr::analysis {

struct psf_mtf_params {
  double max_lp_per_mm = 2.0;
  int points = 101;       // frequencies 0 .. max, evenly spaced
  double pixel_mm = 0.0;  // > 0: include the aperture of a pixel this wide on the aerial-image plane
  bool along_y = false;   // measure along the image's y (what horizontal strokes need) instead of x
};

struct psf_mtf_curve {
  std::vector<double> lp_per_mm;
  std::vector<double> mtf;
};

psf_mtf_curve psf_mtf(const psf_samples& psf, const psf_mtf_params& params = {});

// Mean of the MTF over (0, max] lp/mm on a uniform grid of `samples` points.
double psf_mean_mtf(const psf_samples& psf, double max_lp_per_mm = 1.0, double pixel_mm = 0.0, int samples = 200);

// Frequency where the MTF first falls to 0.5 (linear interpolation); 0 if it never does.
double psf_mtf50(const psf_mtf_curve& curve);

}  // namespace airr::analysis
