#include "airr/measure/noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "airr/analysis/mtf_metrics.hpp"
#include "airr/core/error.hpp"

namespace airr {

double pair_relative_noise(const image_rgb& a, const image_rgb& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size() || a.rgb.empty()) {
    throw input_error("noise: the two renders differ in size (" + std::to_string(a.width) + "x" +
                      std::to_string(a.height) + " and " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                      ")");
  }
  double squares = 0, sum = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = double(a.rgb[i]) - double(b.rgb[i]);
    squares += d * d;
    sum += 0.5 * (double(a.rgb[i]) + double(b.rgb[i]));
  }
  const double n = double(a.rgb.size());
  if (!(sum > 0)) throw input_error("noise: the renders are black (no mean to relate the noise to)");
  return std::sqrt(squares / n / 2) / (sum / n);
}

double relative_rms_difference(const std::vector<float>& a, const std::vector<float>& b,
                               const std::vector<float>& reference) {
  if (a.size() != b.size() || a.size() != reference.size()) {
    throw input_error("relative RMS difference: images of different sizes");
  }
  double squares = 0, sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = double(a[i]) - double(b[i]);
    squares += d * d;
    sum += reference[i];
  }
  const double n = double(a.size());
  return n > 0 && sum > 0 ? std::sqrt(squares / n) / (sum / n) : 0.0;
}

noise_law fit_noise_law(const std::vector<noise_point>& points) {
  std::set<std::uint64_t> distinct;
  for (const noise_point& p : points) {
    if (!(p.noise > 0) || p.spp == 0) throw input_error("noise: a measured point has no noise or no samples");
    distinct.insert(p.spp);
  }
  if (distinct.size() < 2) throw input_error("noise: the noise law needs renders at two or more sample counts");
  std::vector<double> log_spp, log_noise, spp, seconds;
  for (const noise_point& p : points) {
    log_spp.push_back(std::log(double(p.spp)));
    log_noise.push_back(std::log(p.noise));
    spp.push_back(double(p.spp));
    seconds.push_back(p.seconds);
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
  };
  noise_law law;
  const double slope = analysis::least_squares_slope(log_spp, log_noise);
  law.exponent = -slope;
  law.amplitude = std::exp(mean(log_noise) - slope * mean(log_spp));
  law.seconds_per_spp = analysis::least_squares_slope(spp, seconds);
  law.startup_s = std::max(0.0, mean(seconds) - law.seconds_per_spp * mean(spp));
  return law;
}

noise_target time_to_noise(const noise_law& law, const std::vector<noise_point>& points, double relative_noise) {
  std::vector<noise_point> sorted = points;
  std::sort(sorted.begin(), sorted.end(), [](const noise_point& a, const noise_point& b) { return a.spp < b.spp; });
  noise_target t;
  t.relative_noise = relative_noise;
  for (std::size_t i = 0; i + 1 < sorted.size() && !t.within_measured; ++i) {
    const noise_point &a = sorted[i], &b = sorted[i + 1];
    if (relative_noise > a.noise || relative_noise < b.noise || !(a.noise > b.noise)) continue;
    const double f = std::log(a.noise / relative_noise) / std::log(a.noise / b.noise);
    t.spp = std::exp(std::log(double(a.spp)) + f * std::log(double(b.spp) / double(a.spp)));
    t.within_measured = true;
  }
  if (!t.within_measured) {
    // From the nearest end of the measured range; towards more samples at most plain Monte
    // Carlo's rate 1/2, since stratification's extra gain fades as the samples grow.
    const bool more = relative_noise < sorted.back().noise;
    const noise_point& from = more ? sorted.back() : sorted.front();
    const double exponent = more ? std::min(law.exponent, 0.5) : law.exponent;
    t.spp = exponent > 0 ? double(from.spp) * std::pow(from.noise / relative_noise, 1 / exponent) : INFINITY;
  }
  t.seconds = law.startup_s + t.spp * law.seconds_per_spp;
  return t;
}

}  // namespace airr
