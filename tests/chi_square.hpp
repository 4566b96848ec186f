#pragma once
// Pearson's chi-square goodness-of-fit: statistic and p-value (upper regularised gamma).
#include <cmath>
#include <vector>

namespace airr::test {

// Q(s, x) = Gamma(s, x) / Gamma(s): series below s + 1, continued fraction above.
inline double upper_regularized_gamma(double s, double x) {
  if (x <= 0) return 1.0;
  const double log_prefix = s * std::log(x) - x - std::lgamma(s);
  if (x < s + 1) {
    double term = 1.0 / s, sum = term;
    for (int n = 1; n < 1000; ++n) {
      term *= x / (s + n);
      sum += term;
      if (term < sum * 1e-15) break;
    }
    return 1.0 - sum * std::exp(log_prefix);
  }
  // Lentz's method for the continued fraction of Gamma(s, x).
  double b = x + 1 - s, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - s);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-15) break;
  }
  return std::exp(log_prefix) * h;
}

struct chi_square_result {
  double statistic = 0;
  int dof = 0;
  double p_value = 0;
};

// Bins with expected count below 5 are pooled into their neighbour.
inline chi_square_result chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  std::vector<double> o, e;
  double po = 0, pe = 0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    po += observed[i];
    pe += expected[i];
    if (pe >= 5) {
      o.push_back(po);
      e.push_back(pe);
      po = pe = 0;
    }
  }
  if (pe > 0 && !e.empty()) {
    o.back() += po;
    e.back() += pe;
  }
  chi_square_result r;
  for (std::size_t i = 0; i < o.size(); ++i) r.statistic += (o[i] - e[i]) * (o[i] - e[i]) / e[i];
  r.dof = int(o.size()) - 1;
  r.p_value = upper_regularized_gamma(0.5 * r.dof, 0.5 * r.statistic);
  return r;
}

}  // namespace airr::test
