#pragma once
// The tracer's PSF, to set beside the model's: a small disc alone on the display, at the display
// point of the aerial image's centre, rendered by the plain path tracer (no model image as control
// variate: the tracer alone) and read on the model PSF's grid.
#include <cstdint>
#include <functional>

#include "airr/analysis/psf_grid.hpp"
#include "airr/layout/psf.hpp"
#include "airr/layout/scene.hpp"

namespace airr {

struct traced_psf_params {
  double disc_mm = 0.2;     // the disc's diameter on the display
  std::uint64_t spp = 256;  // samples per pixel
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all cores
};

struct traced_psf {
  // The aerial component per unit source radiance and disc area: the model PSF blurred by the
  // disc, density per mm^2 integrating to the brightness.
  analysis::psf_grid grid;
  double disc_area_mm2 = 0;  // of the disc as drawn (its anti-aliased pixels)
  std::uint64_t spp = 0;
  double seconds = 0;
};

// The observer becomes a pinhole at its position aimed at the aerial image's centre, framing a
// square of `size` pixels of `mm_per_pixel` there (odd size: the middle pixel is the centre); the
// display shrinks to a square of four disc diameters (its bezel kept) showing only the disc, with
// a Lambertian emission. Throws input_error for a disc that is not positive or larger than the
// display, or a size outside [3, 1025] or even. `progress` receives the fraction done.
traced_psf trace_psf(const scene& s, int size, double mm_per_pixel, const traced_psf_params& p,
                     const std::function<void(double)>& progress = {});

}  // namespace airr
