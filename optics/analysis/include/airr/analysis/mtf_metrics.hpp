#pragma once

#include <optional>
#include <vector>

#include "airr/analysis/slanted_edge_mtf.hpp"

namespace airr::analysis {

struct mtf50_result {
  double cycles_per_pixel = 0;
  double lp_per_mm = 0;  // 0 when no pixel size was given
};

struct mean_mtf_params {
  double max_lp_per_mm = 1.0;  // upper end of the averaging range (0, max]
  int samples = 200;           // uniform grid points in (0, max]
};

struct mean_mtf_result {
  double value = 0;
  double upper_lp_per_mm = 0;  // upper end actually used
  bool clamped = false;        // the range was cut at the image's Nyquist frequency
};

// MTF linearly interpolated at a frequency in cycles/pixel; 0 beyond the measured range.
double interpolate_mtf(const mtf_curve& curve, double cycles_per_pixel);

// Where y first falls from >= level to below it, linearly interpolated in x; empty if never.
std::optional<double> first_crossing(const std::vector<double>& x, const std::vector<double>& y, double level);

// First crossing of 0.5, linearly interpolated; empty when the curve stays above 0.5.
// mm_per_pixel <= 0 leaves lp_per_mm at 0.
std::optional<mtf50_result> mtf50(const mtf_curve& curve, double mm_per_pixel = 0);

// Slope of the least-squares line through (x, y); 0 with fewer than two points.
double least_squares_slope(const std::vector<double>& x, const std::vector<double>& y);

// Mean of the MTF over (0, max_lp_per_mm] lp/mm on a uniform grid, cut at the Nyquist frequency
// (0.5 cycles/pixel) when that is lower.
mean_mtf_result mean_mtf(const mtf_curve& curve, double mm_per_pixel, const mean_mtf_params& params = {});

// The standard deviation of an MTF measured on the mean of two independent half estimates (the
// even- and odd-numbered samples of a render), from the halves' MTFs a and b: the mean's error is
// (e_a + e_b) / 2 and E[(a - b)^2] = 2 var(e), so sigma = rms(a - b) / 2, the RMS taken over
// `half_window` neighbouring frequencies either side (one difference alone is a noisy estimate).
// Halves of a stratified sequence err in opposite directions more often than independent ones,
// which makes this an overestimate there.
std::vector<double> mtf_sigma_from_halves(const std::vector<double>& a, const std::vector<double>& b,
                                          int half_window = 3);

// The frequency up to which every sigma stays at or below max_sigma (the last such point before
// the first that exceeds it); 0 when the first point already exceeds it.
double readable_up_to(const std::vector<double>& frequency, const std::vector<double>& sigma, double max_sigma);

}  // namespace airr::analysis
