#pragma once
// Piecewise-linear interpolation and grid means: the one home for tables over an ascending axis
// (a and mu over incidence angle, MTF curves over frequency).
#include <algorithm>
#include <vector>

namespace airr {

// ys at x by linear interpolation over ascending xs, clamped to the end values outside; one value
// (or an empty axis) is constant. xs and ys have the same length, or ys has one value.
inline double interpolate_linear(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (ys.size() == 1 || xs.empty()) return ys.front();
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto hi = std::size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  const std::size_t lo = hi - 1;
  const double t = (x - xs[lo]) / (xs[hi] - xs[lo]);
  return ys[lo] + t * (ys[hi] - ys[lo]);
}

// Mean of f over the uniform grid max * i / samples, i = 1 .. samples: the mean over (0, max].
template <class F>
double grid_mean(double max, int samples, F&& f) {
  double sum = 0;
  for (int i = 1; i <= samples; ++i) sum += f(max * i / samples);
  return sum / samples;
}

}  // namespace airr
