#pragma once
// Piecewise-linear interpolation and grid means: the one home for tables over an ascending axis
// (a and mu over incidence angle, MTF curves over frequency).
#include <algorithm>
#include <vector>

namespace airr {

// Where x falls on ascending xs: ys at x is (1 - t) ys[lo] + t ys[hi]. Clamped to an end outside
// (lo = hi there); an empty or one-entry axis gives lo = hi = 0.
struct interpolation_segment {
  std::size_t lo = 0, hi = 0;
  double t = 0;
};
inline interpolation_segment segment_at(const std::vector<double>& xs, double x) {
  if (xs.size() < 2 || !(x > xs.front())) return {};  // NaN too
  if (x >= xs.back()) return {xs.size() - 1, xs.size() - 1, 0};
  const auto hi = std::size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  return {hi - 1, hi, (x - xs[hi - 1]) / (xs[hi] - xs[hi - 1])};
}

// ys at x by linear interpolation over ascending xs, clamped to the end values outside; one value
// (or an empty axis) is constant. xs and ys have the same length, or ys has one value.
inline double interpolate_linear(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (ys.size() == 1 || xs.empty()) return ys.front();
  const interpolation_segment g = segment_at(xs, x);
  return ys[g.lo] + g.t * (ys[g.hi] - ys[g.lo]);
}

// Mean of f over the uniform grid max * i / samples, i = 1 .. samples: the mean over (0, max].
template <class F>
double grid_mean(double max, int samples, F&& f) {
  double sum = 0;
  for (int i = 1; i <= samples; ++i) sum += f(max * i / samples);
  return sum / samples;
}

}  // namespace airr
