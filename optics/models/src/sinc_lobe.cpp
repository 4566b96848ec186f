#include "airr/models/sinc_lobe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "airr/core/table_search.hpp"

namespace airr {

static constexpr double half_pi = std::numbers::pi / 2;

double sinc(double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

sinc_lobe::sinc_lobe() {
  const int n = sinc_lobe_table_size;
  cdf_.resize(n);
  tan_start_.resize(n);
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const double delta = half_pi * j / n;
    tan_start_[std::size_t(j)] = std::tan(delta);
    const double c = std::cos(delta);
    const double s = sinc(tan_start_[std::size_t(j)]);
    sum += s * s / (c * c);
    cdf_[j] = sum;
  }
  for (double& v : cdf_) v /= sum;
  guide_.resize(guide_size + 1);
  for (int b = 0; b <= guide_size; ++b) {
    guide_[b] = int(std::upper_bound(cdf_.begin(), cdf_.end(), double(b) / guide_size) - cdf_.begin());
  }
}

const sinc_lobe& sinc_lobe::instance() {
  static const sinc_lobe lobe;
  return lobe;
}

double sinc_lobe::sample_k_tan_delta(double u_cell, double u_jitter) const {
  // The answer lies between guide_[b] and guide_[b + 1] (inclusive) for u_cell in [b, b + 1) / guide_size.
  const int b = std::clamp(int(u_cell * guide_size), 0, guide_size - 1);
  const std::size_t first = std::size_t(guide_[b]), last = std::size_t(guide_[b + 1]);
  const std::size_t j = std::min(first + first_greater(cdf_.data() + first, last - first, u_cell), cdf_.size() - 1);
  const double cell = half_pi / double(cdf_.size());
  if (j + 1 == cdf_.size()) return std::tan(cell * (double(j) + u_jitter));
  // tan(start + r) by the addition formula, tan r = r + r^3 / 3 to double precision (r < 6e-5).
  const double rest = cell * u_jitter, tan_rest = rest + rest * rest * rest / 3, t = tan_start_[j];
  return (t + tan_rest) / (1 - t * tan_rest);
}

double sinc_lobe::pdf(double delta, double k) {
  if (delta < 0 || delta >= half_pi) return 0;
  const double c = std::cos(delta);
  const double s = sinc(k * std::tan(delta));
  // Integral of sinc^2(y) over [0, inf) is pi/2; dy = k / cos^2(delta) d(delta).
  return s * s * k / (c * c) / half_pi;
}

}  // namespace airr
