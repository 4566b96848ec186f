// Fraunhofer diffraction by an aperture: the polygon's far field in closed form is the square's
// sinc^2 x sinc^2, the sampled far fields of a square and a circle follow the analytic sinc^2 and
// Airy patterns and two polygons' their closed form out to the reach (chi-square), and a prism
// sheet's retroreflected spread scales with wavelength over pitch.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "airr/core/geometry.hpp"
#include "airr/models/diffraction.hpp"
#include "airr/models/prism_sheet.hpp"
#include "chi_square.hpp"
#include "prism_test_support.hpp"

using namespace airr;

namespace {

double sinc(double u) { return std::abs(u) < 1e-12 ? 1.0 : std::sin(u) / u; }

// The square of side a about the origin: |F|^2 = a^4 sinc^2(pi a fx) sinc^2(pi a fy).
aperture square(double a) { return {{{-a / 2, -a / 2}, {a / 2, -a / 2}, {a / 2, a / 2}, {-a / 2, a / 2}}}; }

double square_intensity(double a, const glm::dvec2& f) {
  return std::pow(a, 4) * std::pow(sinc(pi * a * f.x) * sinc(pi * a * f.y), 2);
}

// Integral of sinc^2(pi a x) dx over [x0, x1], by Simpson's rule on 200 intervals.
double sinc2_integral(double a, double x0, double x1) {
  const int n = 200;
  const double h = (x1 - x0) / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double w = i == 0 || i == n ? 1 : (i % 2 ? 4 : 2);
    s += w * std::pow(sinc(pi * a * (x0 + i * h)), 2);
  }
  return s * h / 3;
}

}  // namespace

TEST(Diffraction, PolygonFarFieldIsTheSquaresSincSquared) {
  const double a = 0.3;
  pcg32 rng(1, 1);
  for (int i = 0; i < 1000; ++i) {
    const glm::dvec2 f((rng.next_double() - 0.5) * 40, (rng.next_double() - 0.5) * 40);
    const double expected = square_intensity(a, f);
    EXPECT_NEAR(far_field_intensity(square(a), f), expected, 1e-9 * std::pow(a, 4)) << f.x << " " << f.y;
  }
  EXPECT_DOUBLE_EQ(far_field_intensity(square(a), {0, 0}), std::pow(a, 4));
  // A triangle's far field carries its area (Parseval): the integral of |F|^2 over a wide grid.
  const aperture triangle{{{0, 0}, {0.2, 0}, {0.05, 0.15}}};
  double sum = 0;
  const double h = 0.25, reach = 400;
  for (double fx = -reach; fx < reach; fx += h) {
    for (double fy = -reach; fy < reach; fy += h) sum += far_field_intensity(triangle, {fx + h / 2, fy + h / 2});
  }
  EXPECT_NEAR(sum * h * h / triangle.area(), 1.0, 0.01);
}

// The second moments the far-field draw's lower bound uses: a turned and moved rectangle's in
// closed form (either orientation), a triangle's against a grid's sums.
TEST(Diffraction, PolygonMomentsAreTheRectanglesAndAGridsSums) {
  const double w = 0.3, h = 0.1, turn = 0.7;
  const glm::dvec2 at(5, -2), u(std::cos(turn), std::sin(turn)), v(-u.y, u.x);
  polygon2 rectangle{at - w / 2 * u - h / 2 * v, at + w / 2 * u - h / 2 * v, at + w / 2 * u + h / 2 * v,
                     at - w / 2 * u + h / 2 * v};
  const glm::dmat2 spread = w * h / 12 * (w * w * glm::outerProduct(u, u) + h * h * glm::outerProduct(v, v));
  for (int pass = 0; pass < 2; ++pass) {
    const polygon_moments m = moments(rectangle);
    EXPECT_NEAR(m.area, w * h, 1e-12);
    EXPECT_NEAR(glm::length(m.centroid - at), 0, 1e-12);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.spread[i / 2][i % 2], spread[i / 2][i % 2], 1e-12);
    std::reverse(rectangle.begin(), rectangle.end());
  }
  const polygon2 triangle{{0, 0}, {0.2, 0}, {0.05, 0.15}};
  const polygon_moments m = moments(triangle);
  double area = 0;
  glm::dvec2 sum(0);
  glm::dmat2 second(0);
  const double step = 1e-4;
  for (double x = step / 2; x < 0.2; x += step) {
    for (double y = step / 2; y < 0.15; y += step) {
      if (y > 3 * x || y > (0.2 - x)) continue;  // outside the edges from (0, 0) and (0.2, 0)
      area += step * step;
      sum += step * step * glm::dvec2(x, y);
      second += step * step * glm::outerProduct(glm::dvec2(x, y) - m.centroid, glm::dvec2(x, y) - m.centroid);
    }
  }
  EXPECT_NEAR(m.area, 0.015, 1e-12);
  EXPECT_NEAR(glm::length(m.centroid - glm::dvec2(0.25, 0.15) / 3.0), 0, 1e-12);
  EXPECT_NEAR(m.area / area, 1, 1e-3);
  EXPECT_NEAR(glm::length(m.centroid - sum / area), 0, 1e-4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.spread[i / 2][i % 2], second[i / 2][i % 2], 1e-3 * second[0][0]);
}

// Samples within the central 6 x 6 lobes, binned by half lobes, against the analytic masses.
TEST(Diffraction, SampledSquareFarFieldFollowsSincSquared) {
  const double a = 0.2;
  const aperture sq = square(a);
  const int cells = 12;
  const double lo = -3 / a, width = 6 / a / cells;
  std::vector<double> counts(std::size_t(cells * cells), 0.0);
  pcg32 rng(7, 3);
  for (int i = 0; i < 200000; ++i) {
    const glm::dvec2 f = sample_far_field(sq, rng);
    const int x = int(std::floor((f.x - lo) / width)), y = int(std::floor((f.y - lo) / width));
    if (x >= 0 && y >= 0 && x < cells && y < cells) counts[std::size_t(y * cells + x)] += 1;
  }
  double inside = 0;
  for (double c : counts) inside += c;
  std::vector<double> mass(static_cast<std::size_t>(cells), 0.0), expected;
  for (int k = 0; k < cells; ++k) mass[std::size_t(k)] = sinc2_integral(a, lo + k * width, lo + (k + 1) * width);
  double total = 0;
  for (double mx : mass) {
    for (double my : mass) total += mx * my;
  }
  for (int y = 0; y < cells; ++y) {
    for (int x = 0; x < cells; ++x) expected.push_back(inside * mass[std::size_t(x)] * mass[std::size_t(y)] / total);
  }
  const test::chi_square_result r = test::chi_square(counts, expected);
  std::printf("square: %.0f of 200000 in the central lobes, chi-square %.1f on %d dof, p = %.3f\n", inside, r.statistic,
              r.dof, r.p_value);
  EXPECT_GT(r.p_value, 1e-3);
}

// Rings of |f| within the Airy pattern's third dark ring, against the encircled energy
// 1 - J0(x)^2 - J1(x)^2, x = pi D |f|.
TEST(Diffraction, SampledCircleFarFieldFollowsAiry) {
  const double d = 0.15;
  const aperture circle{{}, d};
  auto encircled = [&](double r) {
    const double x = pi * d * r;
    return 1 - std::pow(std::cyl_bessel_j(0.0, x), 2) - std::pow(std::cyl_bessel_j(1.0, x), 2);
  };
  const double reach = 3.24 / d;  // third dark ring: x = 10.17
  const int rings = 40;
  std::vector<double> counts(std::size_t(rings), 0.0), expected;
  pcg32 rng(5, 9);
  double inside = 0;
  for (int i = 0; i < 200000; ++i) {
    const double r = glm::length(sample_far_field(circle, rng));
    if (r >= reach) continue;
    counts[std::size_t(r / reach * rings)] += 1;
    inside += 1;
  }
  for (int k = 0; k < rings; ++k) {
    expected.push_back(inside * (encircled(reach * (k + 1) / rings) - encircled(reach * k / rings)) / encircled(reach));
  }
  const test::chi_square_result r = test::chi_square(counts, expected);
  std::printf("circle: %.0f of 200000 inside the third dark ring (Airy: %.4f), chi-square %.1f on %d dof, p = %.3f\n",
              inside, encircled(reach), r.statistic, r.dof, r.p_value);
  EXPECT_GT(r.p_value, 1e-3);
  EXPECT_NEAR(inside / 200000, encircled(reach), 0.005);
}

// A polygon's far field out to the sampler's reach, where most of it lies in streaks across the
// edges: samples binned in rings (doubling in radius) and sectors against the masses summed from
// the closed-form |F|^2 on a grid fine enough for the narrowest streak's fringes (1 / the longest
// edge wide) and, within 8 f0, for the sectors' edges. Returns the p-value.
namespace {

double far_field_fit(const aperture& shape, double h, std::uint64_t seed) {
  const double reach = far_field_reach(shape), f0 = shape.perimeter() / (2 * pi * shape.area());
  std::vector<double> rings{0};
  for (double r = f0 / 2; r < reach; r *= 2) rings.push_back(r);
  rings.push_back(reach);
  const int sectors = 12;
  auto bin = [&](const glm::dvec2& f) {
    const double r = glm::length(f);
    const auto ring = std::size_t(std::upper_bound(rings.begin(), rings.end(), r) - rings.begin()) - 1;
    // Sectors start 7.5 deg off the axes and diagonals, where the test shapes' streaks lie.
    const double angle = std::fmod(std::atan2(f.y, f.x) + 3 * pi - radians(7.5), 2 * pi);
    return ring * sectors + std::size_t(std::min(sectors - 1, int(angle / (2 * pi) * sectors)));
  };
  const std::size_t bins = (rings.size() - 1) * sectors;
  std::vector<double> counts(bins, 0.0), mass(bins, 0.0), expected;
  const int n = 400000;
  pcg32 rng(seed, 4);
  for (int i = 0; i < n; ++i) counts[bin(sample_far_field(shape, rng))] += 1;
  double total = 0;
  for (double fx = -reach; fx < reach; fx += h) {
    for (double fy = -reach; fy < reach; fy += h) {
      const int split = glm::length(glm::dvec2(fx, fy)) < 8 * f0 ? 8 : 1;
      for (int i = 0; i < split * split; ++i) {
        const glm::dvec2 f = glm::dvec2(fx, fy) + h / split * glm::dvec2(i % split + 0.5, i / split + 0.5);
        if (glm::length(f) >= reach) continue;
        const double m = far_field_intensity(shape, f) / (split * split);
        mass[bin(f)] += m;
        total += m;
      }
    }
  }
  for (double m : mass) expected.push_back(n * m / total);
  double beyond = 0;
  for (std::size_t k = 5 * sectors; k < bins; ++k) beyond += counts[k];
  const test::chi_square_result r = test::chi_square(counts, expected);
  std::printf("%zu corners: %zu rings x %d sectors, %.0f of %d beyond 8 f0, chi-square %.1f on %d dof, p = %.3f\n",
              shape.polygon.size(), rings.size() - 1, sectors, beyond, n, r.statistic, r.dof, r.p_value);
  return r.p_value;
}

}  // namespace

// A triangle (every edge longer than 1 / (pi f0)) and a thin quadrilateral whose short edge is not:
// the sampler's two forms of a streak.
TEST(Diffraction, SampledPolygonFarFieldsFollowTheirStreaks) {
  EXPECT_GT(far_field_fit({{{0, 0}, {0.2, 0}, {0.05, 0.15}}}, 0.5, 11), 1e-3);
  EXPECT_GT(far_field_fit({{{0, 0}, {0.2, 0}, {0.2, 0.02}, {0, 0.06}}}, 0.5, 12), 1e-3);
}

// Corners in a line (a clipped aperture can end so): no area to diffract by, and no endless draw.
TEST(Diffraction, AnApertureWithoutAreaDoesNotSpread) {
  pcg32 rng(3, 3);
  const glm::dvec2 f = sample_far_field({{{0, 0}, {0.1, 0}, {0.2, 0}}}, rng);
  EXPECT_EQ(f, glm::dvec2(0));
}

// The median angle between a retroreflected ray and the exact reversal: doubling the pitch halves
// it, doubling the wavelength doubles it.
TEST(Diffraction, PrismSheetSpreadScalesWithWavelengthOverPitch) {
  auto median_spread = [](double pitch, double wavelength) {
    prism_sheet_geometry g;
    g.pitch_mm = pitch;
    g.wavelength_nm = wavelength;
    return test::median_retro_spread(g, glm::normalize(glm::dvec3(0.1, 0.05, 1)), 2, 8);
  };
  const double base = median_spread(0.1, 550), coarse = median_spread(0.2, 550), red = median_spread(0.1, 1100);
  std::printf("median spread: %.3f mrad at 0.1 mm and 550 nm, %.3f at 0.2 mm, %.3f at 1100 nm (lambda / pitch %.1f)\n",
              1e3 * base, 1e3 * coarse, 1e3 * red, 550e-6 / 0.1 * 1e3);
  EXPECT_NEAR(coarse / base, 0.5, 0.03);
  EXPECT_NEAR(red / base, 2.0, 0.1);
  EXPECT_GT(base, 0.3 * 550e-6 / 0.1);  // of the order of lambda / pitch
  EXPECT_LT(base, 3 * 550e-6 / 0.1);
}

// The display's white: the spread of retroreflected light with display_rgb follows the equal
// mixture of the three primaries' spreads (each drawn alone), binned by angle (chi-square), and
// differs from one wavelength's.
TEST(Diffraction, DisplayWhiteSpreadIsTheMixtureOfThePrimaries) {
  const glm::dvec3 wi = glm::normalize(glm::dvec3(0.1, 0.05, 1));
  auto angles = [&](diffracted_light light, double wavelength, int n, std::uint64_t seed) {
    prism_sheet_geometry g;
    g.metallised = true;  // one aperture per cube corner: the narrower spread tells wavelengths apart best
    g.light = light;
    g.wavelength_nm = wavelength;
    return test::retro_spread_angles(g, wi, n, seed, 3);
  };
  const int n = 30000, bins = 12;
  const double bin_mrad = 1.5;  // the last bin holds everything beyond
  auto histogram = [&](const std::vector<double>& a) {
    std::vector<double> h(bins, 0.0);
    for (double x : a) h[std::min(bins - 1, int(x * 1e3 / bin_mrad))] += 1;
    return h;
  };
  std::vector<double> mixture(bins, 0.0);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto h = histogram(angles(diffracted_light::single, display_primaries_nm[k], n, 10 + k));
    for (int b = 0; b < bins; ++b) mixture[std::size_t(b)] += h[std::size_t(b)] / 3;
  }
  const auto white = histogram(angles(diffracted_light::display_rgb, 550, n, 20));
  const auto green = histogram(angles(diffracted_light::single, 549.1, n, 21));
  // Two samples of equal size: chi-square of their difference, (a - b)^2 / (a + b) over the bins
  // (conservative for the mixture, whose bins vary a third as much as one sample's).
  auto two_sample_p = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double stat = 0;
    for (int i = 0; i < bins; ++i)
      if (a[std::size_t(i)] + b[std::size_t(i)] > 0)
        stat += std::pow(a[std::size_t(i)] - b[std::size_t(i)], 2) / (a[std::size_t(i)] + b[std::size_t(i)]);
    return test::upper_regularized_gamma(0.5 * (bins - 1), 0.5 * stat);
  };
  const double p_mixture = two_sample_p(white, mixture), p_green = two_sample_p(white, green);
  std::printf("display white against the primaries' mixture: p = %.3f; against 549 nm alone: p = %.2g\n", p_mixture,
              p_green);
  EXPECT_GT(p_mixture, 1e-3);
  EXPECT_LT(p_green, 1e-3);
}

// Colour fringes: with the display's white each retroreflected path carries one primary's channel
// (three times over), so the channels average to white, and the light carrying red spreads wider
// than the light carrying blue, by the ratio of their wavelengths.
TEST(Diffraction, DisplayWhiteBlursEachChannelByItsWavelength) {
  prism_sheet_geometry g;
  g.metallised = true;
  g.light = diffracted_light::display_rgb;
  const glm::dvec3 wi = glm::normalize(glm::dvec3(0.1, 0.05, 1));
  pcg32 rng(4, 4);
  glm::dvec3 sum(0);
  std::array<std::vector<double>, 3> spread;
  int n = 0;
  while (n < 60000) {
    const prism_path p =
        trace_prism_sheet(g, wi, prism_cell_point(g, {rng.next_double(), rng.next_double()}), rng.next_double(), rng);
    if (p.fate != prism_fate::retroreflected || p.face_reflections != 3 || p.front_reflections != 0) continue;
    ++n;
    sum += p.channels;
    for (int k = 0; k < 3; ++k)
      if (p.channels[k] > 0) spread[std::size_t(k)].push_back(std::acos(std::min(1.0, glm::dot(p.wo, wi))));
  }
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const glm::dvec3 mean = sum / double(n);
  const double red = median(spread[0]), green = median(spread[1]), blue = median(spread[2]);
  std::printf("channels' mean %.4f %.4f %.4f; median spread R %.3f G %.3f B %.3f mrad (R / B %.3f, wavelengths %.3f)\n",
              mean.r, mean.g, mean.b, red * 1e3, green * 1e3, blue * 1e3, red / blue,
              display_primaries_nm[0] / display_primaries_nm[2]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mean[k], 1.0, 4 * std::sqrt(2.0 / n));
  EXPECT_NEAR(red / blue, display_primaries_nm[0] / display_primaries_nm[2], 0.04);
  EXPECT_NEAR(green / blue, display_primaries_nm[1] / display_primaries_nm[2], 0.04);
}
