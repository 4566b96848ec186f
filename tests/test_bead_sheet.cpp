// The bead sheet traced as geometry: a lossless sheet returns all the light, a ball lens of index
// 2 retroreflects paraxial light, and the sheet returns light over a wider range of incidence
// than a prism sheet.
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/models/bead_sheet.hpp"
#include "airr/models/polarization.hpp"
#include "airr/models/prism_sheet.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The share of light returned within `cone` (rad) of the exact reversal.
template <typename Trace>
double returned_within(const glm::dvec3& wi, double cone, int n, Trace trace) {
  pcg32 rng(9, 1);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const auto [wo, weight] = trace(wi, rng);
    if (std::acos(std::min(1.0, glm::dot(wo, wi))) < cone) sum += weight;
  }
  return sum / n;
}

}  // namespace

TEST(BeadSheet, NoLightIsLostByALosslessMirrorSheet) {
  bead_sheet_geometry g;
  g.backing_reflectance = 1;
  pcg32 rng(3, 3);
  for (const double theta : {0.0, 30.0, 60.0, 80.0}) {
    double sum = 0, lost = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const bead_path p = trace_bead_sheet(g, test::unit_direction(theta, 11),
                                           bead_cell_point(g, {rng.next_double(), rng.next_double()}), rng);
      sum += p.weight;
      lost += p.lost;
      if (!p.lost) {
        EXPECT_GT(p.wo.z, 0.0);
      }
    }
    std::printf("theta %g: returned %.4f, lost %.0f of %d\n", theta, sum / n, lost, n);
    EXPECT_NEAR(sum / n, 1.0, 0.005) << theta;
    EXPECT_LE(lost / n, 0.001) << theta;
  }
}

// A sphere of index 2 focuses paraxial light on its back surface (focal length n r / (2 (n - 1))
// from the centre): light entering near a bead's axis comes back along itself. At index 1.5 the
// focus lies a radius behind the bead, and the light comes back spread.
TEST(BeadSheet, ABallLensOfIndexTwoRetroreflectsParaxialLight) {
  auto spread = [](double index) {
    bead_sheet_geometry g;
    g.index = index;
    g.wavelength_nm = 0;
    pcg32 rng(5, 5);
    double worst = 0;
    int through = 0;
    for (int i = 0; i < 2000; ++i) {
      // Within a tenth of the radius of the bead centred under the origin.
      const double a = 2 * pi * rng.next_double(), rho = 0.1 * g.diameter_mm / 2 * std::sqrt(rng.next_double());
      const bead_path p = trace_bead_sheet(g, {0, 0, 1}, {rho * std::cos(a), rho * std::sin(a)}, rng);
      if (!p.through_bead || p.backing_reflections != 1) continue;
      ++through;
      worst = std::max(worst, std::acos(std::min(1.0, p.wo.z)));
    }
    EXPECT_GT(through, 1000);
    return worst;
  };
  const double two = spread(2.0), one_and_a_half = spread(1.5);
  std::printf("paraxial light back from the bead: within %.2e rad at index 2, %.2e at 1.5\n", two, one_and_a_half);
  EXPECT_LT(two, 2e-3);
  EXPECT_GT(one_and_a_half, 10 * two);
}

// Light returned within 2 deg of the reversal, against incidence: the bead sheet keeps half of
// its return at 5 deg to a steeper angle than the prism sheet. (At exactly 0 deg the mirror
// between the beads and the prism sheet's front surface reflect straight back too.)
TEST(BeadSheet, ReturnsLightOverAWiderRangeOfIncidenceThanAPrismSheet) {
  const bead_sheet_geometry bead;
  const prism_sheet_geometry prism;
  auto bead_trace = [&](const glm::dvec3& wi, pcg32& rng) {
    const bead_path p = trace_bead_sheet(bead, wi, bead_cell_point(bead, {rng.next_double(), rng.next_double()}), rng);
    return std::pair{p.wo, p.weight};
  };
  auto prism_trace = [&](const glm::dvec3& wi, pcg32& rng) {
    const prism_path p = trace_prism_sheet(prism, wi, prism_cell_point(prism, {rng.next_double(), rng.next_double()}),
                                           rng.next_double(), rng);
    return std::pair{p.wo, p.weight};
  };
  const double cone = radians(2);
  double bead_half = -1, prism_half = -1, bead_5 = 0, prism_5 = 0;
  for (double theta = 0; theta <= 80; theta += 5) {
    const glm::dvec3 wi = test::unit_direction(theta, 7);
    const double b = returned_within(wi, cone, 20000, bead_trace), p = returned_within(wi, cone, 20000, prism_trace);
    if (theta == 5) bead_5 = b, prism_5 = p;
    if (theta > 5 && bead_half < 0 && b < 0.5 * bead_5) bead_half = theta;
    if (theta > 5 && prism_half < 0 && p < 0.5 * prism_5) prism_half = theta;
    std::printf("theta %2.0f: bead sheet %.3f, prism sheet %.3f\n", theta, b, p);
  }
  std::printf("below half the return at 5 deg: bead sheet from %g deg, prism sheet from %g deg\n", bead_half,
              prism_half);
  EXPECT_GT(prism_half, 0);
  EXPECT_TRUE(bead_half < 0 || bead_half > prism_half + 10);
}

// Followed with its polarization, a path straight through a bead's centre onto its mirror backing
// meets every surface at normal incidence, where s and p are alike: the light keeps its polarization
// whole, and the matrix (divided by the path's weight) passes all of it. Over many paths at 30 deg
// the refractions at an angle and the backing's metal phases leave the mean partly polarized, and
// a diffuse backing less so.
TEST(BeadSheet, ItsPathsCarryTheirPolarization) {
  bead_sheet_geometry g;
  g.wavelength_nm = 0;  // no diffraction: the path's direction is the geometry's
  int straight = 0;
  for (std::uint64_t seed = 0; seed < 200 && straight < 5; ++seed) {
    pcg32 rng(seed, 1);
    std::optional<mueller> m;
    const bead_path p = trace_bead_sheet(g, {0, 0, 1}, {1e-4 * g.diameter_mm, 0}, rng, &m);
    if (!p.through_bead || p.backing_reflections != 1) continue;  // a Fresnel reflection on the way
    ++straight;
    ASSERT_TRUE(m.has_value());
    for (const stokes& in :
         {linear_light(0), linear_light(radians(30)), linear_light(radians(70)), circular_light(true)}) {
      const stokes out = *m * in;
      EXPECT_NEAR(out[0], 1, 1e-6);
      EXPECT_NEAR(degree_of_polarization(out), 1, 1e-6);
    }
  }
  EXPECT_EQ(straight, 5);

  const auto mean_degree = [](const bead_sheet_geometry& sheet) {
    const glm::dvec3 wi(std::sin(radians(30)), 0, std::cos(radians(30)));
    stokes sum{0, 0, 0, 0};
    for (int i = 0; i < 20000; ++i) {
      pcg32 rng(std::uint64_t(i), 7);
      std::optional<mueller> m;
      const glm::dvec2 entry = bead_cell_point(sheet, {rng.next_double(), rng.next_double()});
      const bead_path p = trace_bead_sheet(sheet, wi, entry, rng, &m);
      if (!p.through_bead || !m) continue;
      // Summed in the frame about the light's way out, as it leaves (near +wi for what returns).
      sum += p.weight * (*m * linear_light(radians(45)));
    }
    return degree_of_polarization(sum);
  };
  const double mirror = mean_degree(g);
  bead_sheet_geometry diffuse = g;
  diffuse.diffuse_backing = true;
  const double scattered = mean_degree(diffuse);
  std::printf(
      "bead sheet at 30 deg, linear light at 45 deg: mean degree of polarization %.4f (mirror backing), "
      "%.4f (diffuse)\n",
      mirror, scattered);
  EXPECT_GT(mirror, 0.2);
  EXPECT_LT(mirror, 0.999);
  EXPECT_LT(scattered, 0.5 * mirror);
}
