// The one-dimensional minimisers and root finder the sheet fit uses, on functions whose minimum or
// root is known in closed form.
#include <cmath>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "airr/analysis/minimise.hpp"

namespace aa = airr::analysis;

namespace {

// f, counting its evaluations, so the functions' own counts can be checked.
struct counted {
  std::function<double(double)> f;
  int calls = 0;
  double operator()(double x) {
    ++calls;
    return f(x);
  }
};

aa::scalar_function by_ref(counted& c) {
  return [&c](double x) { return c(x); };
}

}  // namespace

// ---- Grid scan ----

TEST(GridScan, PicksTheBestGridPointAndItsNeighbours) {
  counted f{[](double x) { return (x - 0.37) * (x - 0.37); }};
  const aa::min_bracket b = aa::grid_scan(by_ref(f), 0.0, 1.0, 11);
  EXPECT_NEAR(b.x, 0.4, 1e-12);
  EXPECT_NEAR(b.fx, 0.03 * 0.03, 1e-12);
  EXPECT_NEAR(b.lo, 0.3, 1e-12);
  EXPECT_NEAR(b.hi, 0.5, 1e-12);
  EXPECT_EQ(b.evaluations, 11);
  EXPECT_EQ(f.calls, 11);
}

TEST(GridScan, MinimumAtAnEndKeepsTheBracketInside) {
  counted f{[](double x) { return x; }};
  const aa::min_bracket b = aa::grid_scan(by_ref(f), 2.0, 4.0, 5);
  EXPECT_EQ(b.x, 2.0);
  EXPECT_EQ(b.lo, 2.0);
  EXPECT_NEAR(b.hi, 2.5, 1e-12);
  const aa::min_bracket top = aa::grid_scan([](double x) { return -x; }, 2.0, 4.0, 5);
  EXPECT_NEAR(top.x, 4.0, 1e-12);
  EXPECT_NEAR(top.lo, 3.5, 1e-12);
  EXPECT_EQ(top.hi, 4.0);
}

TEST(GridScan, UsesAtLeastThreePoints) {
  counted f{[](double x) { return std::abs(x - 0.5); }};
  const aa::min_bracket b = aa::grid_scan(by_ref(f), 0.0, 1.0, 1);
  EXPECT_EQ(f.calls, 3);
  EXPECT_NEAR(b.x, 0.5, 1e-12);
}

TEST(GridScan, TheFirstOfEqualMinimaWins) {
  const aa::min_bracket b = aa::grid_scan([](double x) { return std::pow((x - 0.2) * (x - 0.8), 2); }, 0.0, 1.0, 6);
  EXPECT_NEAR(b.x, 0.2, 1e-12);
  EXPECT_NEAR(b.fx, 0.0, 1e-24);
}

TEST(GridScan, NanNeverWins) {
  const aa::min_bracket b = aa::grid_scan([](double x) { return x < 0.3 ? std::nan("") : x; }, 0.0, 1.0, 11);
  EXPECT_NEAR(b.x, 0.3, 1e-12);
}

// ---- Downhill bracket ----

TEST(DownhillBracket, WalksToTheMinimum) {
  counted f{[](double x) { return (x - 3.0) * (x - 3.0); }};
  const aa::min_bracket b = aa::downhill_bracket(by_ref(f), -10.0, 10.0, 0.0, 0.05);
  EXPECT_LE(b.lo, 3.0);
  EXPECT_GE(b.hi, 3.0);
  EXPECT_LE(b.fx, f.f(b.lo));
  EXPECT_LE(b.fx, f.f(b.hi));
  EXPECT_GT(b.lo, -10.0);  // no further than the steps took it
  EXPECT_EQ(b.evaluations, f.calls);
  EXPECT_LE(b.evaluations, 12);  // doubling steps: 3 to start, then one per step (0.05 * 2^k passes 3 at k = 6)
}

TEST(DownhillBracket, AtTheMinimumEvaluatesThreeTimes) {
  counted f{[](double x) { return (x - 1.0) * (x - 1.0); }};
  const aa::min_bracket b = aa::downhill_bracket(by_ref(f), 0.0, 2.0, 1.0, 0.1);
  EXPECT_EQ(f.calls, 3);
  EXPECT_EQ(b.x, 1.0);
  EXPECT_NEAR(b.lo, 0.9, 1e-12);
  EXPECT_NEAR(b.hi, 1.1, 1e-12);
}

TEST(DownhillBracket, StopsAtTheEndOfTheInterval) {
  counted f{[](double x) { return -x; }};
  const aa::min_bracket b = aa::downhill_bracket(by_ref(f), 0.0, 1.0, 0.2, 0.05);
  EXPECT_EQ(b.x, 1.0);
  EXPECT_EQ(b.hi, 1.0);
  EXPECT_LT(b.lo, 1.0);
  EXPECT_EQ(b.evaluations, f.calls);
}

TEST(DownhillBracket, ClampsTheStart) {
  const aa::min_bracket b = aa::downhill_bracket([](double x) { return x * x; }, -1.0, 1.0, 5.0, 0.1);
  EXPECT_GE(b.lo, -1.0);
  EXPECT_LE(b.hi, 1.0);
  EXPECT_LE(b.lo, 0.0);
  EXPECT_GE(b.hi, 0.0);
}

// ---- Brent's minimum ----

namespace {

aa::minimum brent_from_scan(counted& f, double lo, double hi, double tol, int scan_points = 5) {
  const aa::min_bracket b = aa::grid_scan(by_ref(f), lo, hi, scan_points);
  return aa::brent_minimum(by_ref(f), b, tol);
}

}  // namespace

TEST(BrentMinimum, Parabola) {
  counted f{[](double x) { return (x - 2.0) * (x - 2.0) + 1.0; }};
  const aa::min_bracket b{.lo = 0.0, .hi = 5.0, .x = 1.0, .fx = 2.0};
  const aa::minimum m = aa::brent_minimum(by_ref(f), b, 1e-6);
  EXPECT_NEAR(m.x, 2.0, 3e-6);
  EXPECT_NEAR(m.fx, 1.0, 1e-10);
  EXPECT_EQ(m.evaluations, f.calls);
  EXPECT_LE(m.evaluations, 12);  // a parabola is found by the parabolic steps, not by golden sections
}

TEST(BrentMinimum, CosineOnTwoToFourIsPi) {
  counted f{[](double x) { return std::cos(x); }};
  const aa::minimum m = brent_from_scan(f, 2.0, 4.0, 1e-8);
  EXPECT_NEAR(m.x, std::numbers::pi, 3e-8);
  EXPECT_NEAR(m.fx, -1.0, 1e-14);
  EXPECT_LE(f.calls, 5 + 20);
}

TEST(BrentMinimum, ToleranceSetsTheAccuracy) {
  // |x - 1|^1.5 is not a parabola near its minimum, so the stopping width is what limits x.
  for (double tol : {1e-2, 1e-4, 1e-6}) {
    counted f{[](double x) { return std::pow(std::abs(x - 1.0), 1.5); }};
    const aa::minimum m = brent_from_scan(f, -3.0, 2.0, tol, 6);
    EXPECT_NEAR(m.x, 1.0, 3 * tol) << tol;
  }
  counted coarse_f{[](double x) { return std::pow(std::abs(x - 1.0), 1.5); }};
  counted fine_f{coarse_f.f};
  brent_from_scan(coarse_f, -3.0, 2.0, 1e-2, 6);
  brent_from_scan(fine_f, -3.0, 2.0, 1e-6, 6);
  EXPECT_LT(coarse_f.calls, fine_f.calls);
}

TEST(BrentMinimum, MinimumAtTheLowerEnd) {
  counted f{[](double x) { return x; }};
  const double tol = 1e-5;
  const aa::minimum m = aa::brent_minimum(by_ref(f), {.lo = 1.0, .hi = 3.0, .x = 2.0, .fx = 2.0}, tol);
  EXPECT_GE(m.x, 1.0);
  EXPECT_LT(m.x - 1.0, 2 * tol);  // what the fit's "at the bracket end" test relies on
  EXPECT_LE(m.evaluations, 40);
}

TEST(BrentMinimum, MinimumAtTheUpperEnd) {
  counted f{[](double x) { return std::exp(-x); }};
  const double tol = 1e-5;
  const aa::minimum m = aa::brent_minimum(by_ref(f), {.lo = 0.0, .hi = 1.0, .x = 0.5, .fx = std::exp(-0.5)}, tol);
  EXPECT_LE(m.x, 1.0);
  EXPECT_LT(1.0 - m.x, 2 * tol);
  EXPECT_LE(m.evaluations, 40);
}

TEST(BrentMinimum, MaxIterationsBoundsTheEvaluations) {
  counted f{[](double x) { return std::cos(x); }};
  const aa::minimum m = aa::brent_minimum(by_ref(f), {.lo = 2.0, .hi = 4.0, .x = 2.5, .fx = std::cos(2.5)}, 0.0, 7);
  EXPECT_EQ(m.evaluations, 7);
  EXPECT_EQ(f.calls, 7);
  EXPECT_LT(m.fx, std::cos(2.5));  // still downhill of the start
}

// ---- Root of a rising function ----

TEST(RisingRoot, CubeRootOfTwo) {
  counted g{[](double x) { return x * x * x - 2.0; }};
  const double tol = 1e-10;
  const aa::root_result r = aa::rising_root(by_ref(g), 0.0, 2.0, tol);
  EXPECT_EQ(r.bound, aa::root_bound::none);
  EXPECT_NEAR(r.x, std::cbrt(2.0), tol);
  EXPECT_LE(r.hi - r.lo, tol);
  EXPECT_LE(r.lo, std::cbrt(2.0));
  EXPECT_GE(r.hi, std::cbrt(2.0));
  EXPECT_LT(r.g_lo, 0.0);
  EXPECT_GT(r.g_hi, 0.0);
  EXPECT_EQ(r.evaluations, g.calls);
  EXPECT_LE(r.evaluations, 15);  // superlinear; bisection would need 35
}

TEST(RisingRoot, IllinoisMovesBothEnds) {
  // Strongly convex: plain regula falsi keeps hi fixed and creeps up from below, far slower than this.
  counted g{[](double x) { return std::pow(x, 10) - 0.5; }};
  const double tol = 1e-9, truth = std::pow(0.5, 0.1);
  const aa::root_result r = aa::rising_root(by_ref(g), 0.0, 1.5, tol);
  EXPECT_LE(r.hi - r.lo, tol);
  EXPECT_NEAR(r.x, truth, tol);
  EXPECT_LE(r.evaluations, 30);
}

TEST(RisingRoot, ReturnsTheEndWithTheSmallerMismatch) {
  const aa::root_result r = aa::rising_root([](double x) { return x - 0.3; }, 0.0, 1.0, 0.1);
  EXPECT_EQ(r.x, std::abs(r.g_lo) <= std::abs(r.g_hi) ? r.lo : r.hi);
  EXPECT_NEAR(r.x, 0.3, 1e-12);  // linear: the first secant step lands on the root
}

TEST(RisingRoot, ToleranceIsHonoured) {
  for (double tol : {1e-2, 1e-5, 1e-9}) {
    const aa::root_result r =
        aa::rising_root([](double x) { return std::atan(x - 0.7) + 0.1 * (x - 0.7); }, -4.0, 5.0, tol);
    EXPECT_LE(r.hi - r.lo, tol) << tol;
    EXPECT_LE(r.lo, 0.7) << tol;
    EXPECT_GE(r.hi, 0.7) << tol;
  }
}

TEST(RisingRoot, RootAtTheLowerEnd) {
  counted g{[](double x) { return x - 1.0; }};
  const aa::root_result r = aa::rising_root(by_ref(g), 1.0, 3.0, 1e-6);
  EXPECT_EQ(r.bound, aa::root_bound::lower);
  EXPECT_EQ(r.x, 1.0);
  EXPECT_EQ(r.lo, 1.0);
  EXPECT_EQ(r.hi, 1.0);
  EXPECT_EQ(r.evaluations, 1);
  EXPECT_EQ(g.calls, 1);
}

TEST(RisingRoot, RootAtTheUpperEnd) {
  counted g{[](double x) { return x - 3.0; }};
  const aa::root_result r = aa::rising_root(by_ref(g), 1.0, 3.0, 1e-6);
  EXPECT_EQ(r.bound, aa::root_bound::upper);
  EXPECT_EQ(r.x, 3.0);
  EXPECT_EQ(r.lo, 3.0);
  EXPECT_EQ(r.hi, 3.0);
  EXPECT_EQ(r.g_lo, 0.0);
  EXPECT_EQ(r.evaluations, 2);
}

TEST(RisingRoot, RootOutsideIsClampedToAnEnd) {
  const aa::root_result below = aa::rising_root([](double x) { return x + 1.0; }, 0.0, 2.0, 1e-6);
  EXPECT_EQ(below.bound, aa::root_bound::lower);
  EXPECT_EQ(below.x, 0.0);
  EXPECT_EQ(below.g_lo, 1.0);
  const aa::root_result above = aa::rising_root([](double x) { return x - 5.0; }, 0.0, 2.0, 1e-6);
  EXPECT_EQ(above.bound, aa::root_bound::upper);
  EXPECT_EQ(above.x, 2.0);
  EXPECT_EQ(above.g_hi, -3.0);
}

TEST(RisingRoot, MaxEvaluationsBoundsTheWork) {
  counted g{[](double x) { return std::pow(x, 10) - 0.5; }};
  const aa::root_result r = aa::rising_root(by_ref(g), 0.0, 1.5, 0.0, 9);  // a zero-width bracket is never reached
  EXPECT_EQ(r.evaluations, 9);
  EXPECT_EQ(g.calls, 9);
  EXPECT_LT(r.lo, r.hi);
  EXPECT_LE(r.lo, std::pow(0.5, 0.1));
  EXPECT_GE(r.hi, std::pow(0.5, 0.1));
}

TEST(RootBound, Names) {
  EXPECT_STREQ(aa::to_string(aa::root_bound::none), "");
  EXPECT_STREQ(aa::to_string(aa::root_bound::lower), "lower");
  EXPECT_STREQ(aa::to_string(aa::root_bound::upper), "upper");
}
