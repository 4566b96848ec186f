#pragma once
// Shared by the microfacet tests: directions, named samples from a generator, integration over
// Beckmann normals and chi-square bins.
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>
#include <vector>
#include "airr/core/geometry.hpp"
#include "airr/core/random.hpp"
#include "airr/models/retro_microfacet.hpp"
#include "chi_square.hpp"
#include "test_helpers.hpp"

namespace airr::test {

using namespace airr;

constexpr double rad = pi / 180;

inline glm::dvec3 direction(double theta_deg, double phi_deg) {
  const double t = theta_deg * rad, p = phi_deg * rad;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

inline retro_samples next_randoms(pcg32& rng) { return random_retro_samples(rng); }

// Integrates f(m) over the part of the hemisphere about +z with tan(theta_m) / alpha in [q0, q1]
// and azimuth in [p0, p1] (composite Simpson in q and phi).
inline double integrate_patch(const std::function<double(const glm::dvec3&)>& f, double alpha, double q0, double q1,
                              double p0, double p1, int nq, int np) {
  const double hq = (q1 - q0) / nq, hp = (p1 - p0) / np;
  double sum = 0;
  for (int i = 0; i <= nq; ++i) {
    const double q = q0 + i * hq;
    const double theta = std::atan(alpha * q);
    const double jac = std::sin(theta) * alpha / (1 + alpha * alpha * q * q);  // d(omega) = sin(theta) d(theta) d(phi)
    const double wq = (i == 0 || i == nq) ? 1 : (i % 2 ? 4 : 2);
    for (int j = 0; j <= np; ++j) {
      const double p = p0 + j * hp;
      const double wp = (j == 0 || j == np) ? 1 : (j % 2 ? 4 : 2);
      const glm::dvec3 m{std::sin(theta) * std::cos(p), std::sin(theta) * std::sin(p), std::cos(theta)};
      sum += wq * wp * jac * f(m);
    }
  }
  return sum * hq * hp / 9;
}

// Beyond tan(theta) / alpha = 8 a Beckmann density holds less than exp(-64) of its mass.
constexpr double q_max = 8;

// Bins in (theta_m, phi_m): 10 rings holding a tenth of the plain Beckmann mass each, 8 sectors.
struct beckmann_bins {
  static constexpr int rings = 10, sectors = 8;
  double alpha;
  std::array<double, rings + 1> q{};  // ring edges in tan(theta) / alpha
  explicit beckmann_bins(double a) : alpha(a) {
    for (int k = 0; k < rings; ++k) q[k] = std::sqrt(-std::log(1 - double(k) / rings));
    q[rings] = q_max;
  }
  int index(const glm::dvec3& m) const {
    const double qm = std::sqrt(std::max(0.0, 1 - m.z * m.z)) / m.z / alpha;
    const int ring = int(std::upper_bound(q.begin() + 1, q.end() - 1, qm) - q.begin()) - 1;
    double phi = std::atan2(m.y, m.x);
    if (phi < 0) phi += 2 * pi;
    const int sector = std::min(sectors - 1, int(phi / (2 * pi) * sectors));
    return ring * sectors + sector;
  }
  std::vector<double> probabilities(const std::function<double(const glm::dvec3&)>& density) const {
    std::vector<double> p(rings * sectors);
    for (int k = 0; k < rings; ++k)
      for (int s = 0; s < sectors; ++s)
        p[k * sectors + s] =
            integrate_patch(density, alpha, q[k], q[k + 1], 2 * pi * s / sectors, 2 * pi * (s + 1) / sectors, 100, 32);
    return p;
  }
};

// p-value of the chi-square goodness of fit of `n` samples against the bin probabilities.
inline double chi_square_p(const beckmann_bins& bins, const std::vector<double>& prob, int n,
                           const std::function<glm::dvec3()>& draw) {
  std::vector<double> counts(prob.size(), 0), expected(prob.size());
  for (int i = 0; i < n; ++i) counts[bins.index(draw())] += 1;
  for (std::size_t i = 0; i < prob.size(); ++i) expected[i] = prob[i] * n;
  return test::chi_square(counts, expected).p_value;
}

inline double total(const std::vector<double>& p) {
  double s = 0;
  for (double v : p) s += v;
  return s;
}

}  // namespace airr::test
