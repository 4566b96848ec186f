#include "airr/analysis/minimise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace airr::analysis {

min_bracket grid_scan(const scalar_function& f, double lo, double hi, int points) {
  return grid_scan_batch(
      [&](const std::vector<double>& xs) {
        std::vector<double> fx;
        for (double x : xs) fx.push_back(f(x));
        return fx;
      },
      lo, hi, points);
}

min_bracket grid_scan_batch(const batch_function& f_all, double lo, double hi, int points) {
  const int n = std::max(3, points);
  const double step = (hi - lo) / (n - 1);
  std::vector<double> xs;
  for (int k = 0; k < n; ++k) xs.push_back(lo + k * step);
  const std::vector<double> fxs = f_all(xs);
  min_bracket b;
  b.x = lo, b.fx = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n; ++k) {
    ++b.evaluations;
    if (fxs.at(std::size_t(k)) < b.fx) b.x = xs[std::size_t(k)], b.fx = fxs[std::size_t(k)];
  }
  b.lo = std::max(lo, b.x - step), b.hi = std::min(hi, b.x + step);
  return b;
}

min_bracket downhill_bracket(const scalar_function& f, double lo, double hi, double x0, double step) {
  min_bracket b;
  auto eval = [&](double x) {
    ++b.evaluations;
    return f(x);
  };
  double x = std::clamp(x0, lo, hi), fx = eval(x);
  double left = std::max(lo, x - step), right = std::min(hi, x + step);
  double f_left = left < x ? eval(left) : fx, f_right = right > x ? eval(right) : fx;
  while (f_left < fx || f_right < fx) {
    step *= 2;
    if (f_left < f_right) {
      right = x, f_right = fx, x = left, fx = f_left;
      left = std::max(lo, x - step);
      if (left == x) break;
      f_left = eval(left);
    } else {
      left = x, f_left = fx, x = right, fx = f_right;
      right = std::min(hi, x + step);
      if (right == x) break;
      f_right = eval(right);
    }
  }
  b.lo = left, b.hi = right, b.x = x, b.fx = fx;
  return b;
}

minimum brent_minimum(const scalar_function& f, const min_bracket& b, double tolerance, int max_iterations) {
  constexpr double golden = 0.3819660112501051;  // (3 - sqrt 5) / 2
  double a = b.lo, c = b.hi, x = b.x, w = b.x, v = b.x, fx = b.fx, fw = b.fx, fv = b.fx, d = 0, e = 0;
  int evaluations = 0;
  for (int iter = 0; iter < max_iterations; ++iter) {
    const double xm = 0.5 * (a + c), tol1 = tolerance, tol2 = 2 * tol1;
    if (std::abs(x - xm) <= tol2 - 0.5 * (c - a)) break;
    bool golden_step = true;
    if (std::abs(e) > tol1) {
      // The parabola through (x, w, v); its vertex is x + p / q.
      double r = (x - w) * (fx - fv), q = (x - v) * (fx - fw), p = (x - v) * q - (x - w) * r;
      q = 2 * (q - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      const double e_old = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * e_old) && p > q * (a - x) && p < q * (c - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || c - u < tol2) d = std::copysign(tol1, xm - x);
        golden_step = false;
      }
    }
    if (golden_step) {
      e = x >= xm ? a - x : c - x;
      d = golden * e;
    }
    const double u = std::abs(d) >= tol1 ? x + d : x + std::copysign(tol1, d);
    const double fu = f(u);
    ++evaluations;
    if (fu <= fx) {
      (u >= x ? a : c) = x;
      v = w, fv = fw, w = x, fw = fx, x = u, fx = fu;
    } else {
      (u < x ? a : c) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw, w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return {x, fx, evaluations};
}

const char* to_string(root_bound b) {
  switch (b) {
    case root_bound::lower:
      return "lower";
    case root_bound::upper:
      return "upper";
    case root_bound::none:
      break;
  }
  return "";
}

root_result rising_root(const scalar_function& g, double lo, double hi, double tolerance, int max_evaluations) {
  root_result r;
  r.x = r.lo = r.hi = lo;
  r.g_lo = r.g_hi = g(lo);
  r.evaluations = 1;
  if (r.g_lo >= 0) {
    r.bound = root_bound::lower;
    return r;
  }
  r.hi = hi;
  r.g_hi = g(hi);
  ++r.evaluations;
  if (r.g_hi <= 0) {
    r.bound = root_bound::upper;
    r.x = r.lo = r.hi;
    r.g_lo = r.g_hi;
    return r;
  }
  int side = 0;                         // the end the last step moved: -1 hi, 1 lo
  double f_lo = r.g_lo, f_hi = r.g_hi;  // the end values regula falsi uses, halved when stale
  while (r.evaluations < max_evaluations && r.hi - r.lo > tolerance) {
    double x = (r.lo * f_hi - r.hi * f_lo) / (f_hi - f_lo);
    if (!(x > r.lo && x < r.hi)) x = 0.5 * (r.lo + r.hi);
    const double gx = g(x);
    ++r.evaluations;
    if (gx > 0) {
      r.hi = x, r.g_hi = f_hi = gx;
      if (side == -1) f_lo /= 2;
      side = -1;
    } else {
      r.lo = x, r.g_lo = f_lo = gx;
      if (side == 1) f_hi /= 2;
      side = 1;
    }
  }
  r.x = std::abs(r.g_lo) <= std::abs(r.g_hi) ? r.lo : r.hi;
  return r;
}

}  // namespace airr::analysis
