#pragma once
// The noise of a Monte Carlo render measured without a noise-free reference: two renders of the
// same scene with independent seeds differ by sqrt(2) times the noise of one. A few such pairs at
// growing samples per pixel give the noise law and the time per sample, from which the samples
// and seconds to reach a noise level follow.
#include <cstdint>
#include <vector>

#include "airr/formats/image.hpp"

namespace airr {

// Relative RMS noise of one render: sqrt(mean over pixels and channels of (a - b)^2 / 2) divided
// by the mean of (a + b) / 2. Throws input_error for images of different sizes or a zero mean.
double pair_relative_noise(const image_rgb& a, const image_rgb& b);

// RMS over pixels and channels of a - b, divided by the mean of `reference`; 0 when that mean is
// not positive. Throws input_error for arrays of different sizes.
double relative_rms_difference(const std::vector<float>& a, const std::vector<float>& b,
                               const std::vector<float>& reference);

// One measured pair.
struct noise_point {
  std::uint64_t spp = 0;
  double seconds = 0;  // wall time of one render of the pair (mean of the two)
  double noise = 0;    // pair_relative_noise
};

// noise = amplitude * spp^-exponent fitted in log-log (an unbiased estimator has exponent 1/2;
// stratification may give more), seconds = startup + spp * seconds_per_spp fitted linearly.
struct noise_law {
  double amplitude = 0;
  double exponent = 0.5;
  double startup_s = 0;
  double seconds_per_spp = 0;
};

// Needs points at two or more distinct spp; throws input_error otherwise.
noise_law fit_noise_law(const std::vector<noise_point>& points);

// Samples per pixel and seconds (startup included) to reach `relative_noise`: interpolated in
// log-log between measured points, or beyond them from the nearest measured point with the fitted
// exponent, towards more samples at most 1/2 (so the forecast is never optimistic).
struct noise_target {
  double relative_noise = 0;
  double spp = 0;
  double seconds = 0;
  bool within_measured = false;  // the target lies inside the measured noise range (no extrapolation)
};
noise_target time_to_noise(const noise_law& law, const std::vector<noise_point>& points, double relative_noise);

}  // namespace airr
