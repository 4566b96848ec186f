#pragma once
// One-dimensional minimisers and a root finder, knowing nothing of what they minimise: a grid scan
// or downhill steps find a bracket around a minimum, Brent's method narrows it; a bracketing
// root finder (Illinois) solves g(x) = 0 for a rising g. Every function evaluates f as few times as
// it can (each evaluation may be a simulation) and reports how many times it did.
#include <functional>
#include <vector>

namespace airr::analysis {

using scalar_function = std::function<double(double)>;

// A point x inside [lo, hi] whose value fx is no larger than f at the ends (when those were
// evaluated): where Brent's minimiser starts.
struct min_bracket {
  double lo = 0, hi = 0;
  double x = 0, fx = 0;
  int evaluations = 0;  // of f, to find this bracket
};

// The best of max(3, points) evenly spaced x on [lo, hi] (both ends included; the first of equal
// values wins, NaN never does), bracketed by its neighbours on the grid (clamped to [lo, hi]).
min_bracket grid_scan(const scalar_function& f, double lo, double hi, int points);
// The same with every grid point's value from one call (f_all(xs) returns f at each x, in order),
// for evaluations that run side by side.
using batch_function = std::function<std::vector<double>(const std::vector<double>& xs)>;
min_bracket grid_scan_batch(const batch_function& f_all, double lo, double hi, int points);

// From x0 (clamped to [lo, hi]): f at x0 -+ step, then steps downhill, doubling the step each
// time, until f is no lower on either side of x or x reaches an end of [lo, hi].
min_bracket downhill_bracket(const scalar_function& f, double lo, double hi, double x0, double step);

struct minimum {
  double x = 0, fx = 0;
  int evaluations = 0;  // of f, beyond the bracket's own
};

// Brent's minimiser (golden section with parabolic steps) of f on [b.lo, b.hi] from b.x, whose
// value b.fx is known. Stops when the bracket is about 4 `tolerance` wide around x (absolute, in
// units of x) or after max_iterations evaluations; never evaluates closer than `tolerance` to an
// end, so a minimum at an end comes back within 2 `tolerance` of it.
minimum brent_minimum(const scalar_function& f, const min_bracket& b, double tolerance, int max_iterations = 100);

// Where the root of a rising g lies relative to the search interval [lo, hi].
enum class root_bound {
  none,   // inside: g(lo) < 0 < g(hi)
  lower,  // g(lo) >= 0: the root is at or below lo, and x = lo
  upper,  // g(hi) <= 0: the root is at or above hi, and x = hi
};

// "", "lower" or "upper".
const char* to_string(root_bound b);

struct root_result {
  double x = 0;               // the end of the final bracket where |g| is smaller
  double lo = 0, hi = 0;      // the final bracket (lo = hi = x when bound is not none)
  double g_lo = 0, g_hi = 0;  // g at its ends
  int evaluations = 0;
  root_bound bound = root_bound::none;
};

// The root of a rising g on [lo, hi] by Illinois regula falsi (the end value that stays put twice
// running is halved, so both ends move in), down to a bracket `tolerance` wide or max_evaluations
// evaluations of g, whichever comes first. Evaluates g(lo) first, then g(hi) only if g(lo) < 0.
root_result rising_root(const scalar_function& g, double lo, double hi, double tolerance, int max_evaluations = 60);

}  // namespace airr::analysis
