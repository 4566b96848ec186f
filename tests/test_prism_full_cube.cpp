// The prism sheet of full cubes: every cube corner is three square faces, so at normal incidence
// all the light entering a mirror-faced sheet in air comes back; at other angles the share that
// does is one corner's effective area, which this file traces independently with three square
// mirrors alone (no lattice), and which the model's own aperture polygons give too.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/core/polygon.hpp"
#include "airr/models/prism_sheet.hpp"
#include "prism_test_support.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The cube axes at azimuth 0, as the model documents them: 120 deg apart about the sheet normal,
// the first along azimuth 90 deg, each acos(1 / sqrt 3) from the normal.
glm::dvec3 cube_axis(int k) {
  const double phi = radians(90 + 120.0 * k);
  return {std::sqrt(2.0 / 3) * std::cos(phi), std::sqrt(2.0 / 3) * std::sin(phi), 1 / std::sqrt(3.0)};
}

// One cube corner alone: mirrors on the squares x_k = 0, 0 <= x_j <= 1 (cube coordinates), light
// along `d` (cube coordinates) from points spread over the plane x + y + z = 3 above it. Of the
// rays that meet the corner, the share that leaves reversed after one reflection on each face.
struct corner_share {
  double share = 0;
  int met = 0;  // rays that met the corner
};
corner_share single_corner_retro_share(const glm::dvec3& d, int n, std::uint64_t seed) {
  pcg32 rng(seed, 5);
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, -1, 0)), v = glm::normalize(glm::dvec3(1, 1, -2));
  int met = 0, reversed = 0;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 p = glm::dvec3(1, 1, 1) + 4 * (rng.next_double() - 0.5) * u + 4 * (rng.next_double() - 0.5) * v;
    glm::dvec3 dir = d;
    int hits = 0, faces = 0;
    for (int bounce = 0; bounce < 4; ++bounce) {
      std::optional<int> hit;
      double t_hit = 1e30;
      for (int k = 0; k < 3; ++k) {
        if (dir[k] == 0) continue;
        const double t = -p[k] / dir[k];
        if (t <= 1e-12 || t >= t_hit) continue;
        const glm::dvec3 q = p + t * dir;
        bool inside = true;
        for (int j = 0; j < 3; ++j)
          if (j != k && (q[j] < 0 || q[j] > 1)) inside = false;
        if (inside) hit = k, t_hit = t;
      }
      if (!hit) break;
      p += t_hit * dir;
      dir[*hit] = -dir[*hit];
      ++hits;
      faces |= 1 << *hit;
    }
    if (hits == 0) continue;
    ++met;
    if (hits == 3 && faces == 7) ++reversed;
  }
  return {double(reversed) / met, met};
}

}  // namespace

TEST(FullCube, HexagonsTileTheSheet) {
  prism_sheet_geometry g;
  g.full_cubes = true;
  g.pitch_mm = 0.2;
  const double cell = std::sqrt(3.0) * g.cube_edge_mm() * g.cube_edge_mm();
  const glm::dvec2 b1 = full_cube_cell_point(g, {1, 0}), b2 = full_cube_cell_point(g, {0, 1});
  EXPECT_NEAR(std::abs(b1.x * b2.y - b1.y * b2.x), cell, 1e-12);
  EXPECT_NEAR(glm::length(b1), g.pitch_mm, 1e-12);  // the apexes' spacing is the width across flats
  pcg32 rng(3, 1);
  for (int i = 0; i < 50; ++i) {
    const glm::dvec3 d = -test::unit_direction(30 * rng.next_double(), 360 * rng.next_double());
    EXPECT_NEAR(polygon_area(full_cube_hexagon(g, d)), cell, 1e-9 * cell);
  }
}

// Mirror faces in air: the model's retroreflected share (one corner's three faces, 20000 paths)
// equals the single corner's (the rays of 500000 that meet it, traced above without the lattice)
// within 4 standard errors, and so does the share the model's aperture polygons give.
TEST(FullCube, RetroreflectedShareIsOneCornersEffectiveArea) {
  prism_sheet_geometry g;
  g.full_cubes = true;
  g.index = 1;
  g.plate_mm = 0;
  g.metallised = true;
  g.face_reflectance = 1;
  g.wavelength_nm = 0;
  for (const double theta : {0.0, 10.0, 20.0, 30.0}) {
    for (const double phi : {0.0, 25.0, 90.0}) {
      const glm::dvec3 wi = test::unit_direction(theta, phi), d = -wi;
      const glm::dvec3 d_cube(glm::dot(d, cube_axis(0)), glm::dot(d, cube_axis(1)), glm::dot(d, cube_axis(2)));
      const corner_share single = single_corner_retro_share(d_cube, 500000, std::uint64_t(theta * 10 + phi));
      const test::fates f = test::trace_many(g, wi, 20000, std::uint64_t(theta + phi));
      const double model = f.cube_retro / f.n;
      const double polygons = polygon_area(full_cube_effective_aperture(g, d)) / polygon_area(full_cube_hexagon(g, d));
      const double variance = std::max(single.share * (1 - single.share), 1e-4);
      const double sigma_single = std::sqrt(variance / single.met);
      std::printf("theta %4.1f phi %4.1f: single corner %.4f (%d rays), model %.4f, aperture polygons %.4f\n", theta,
                  phi, single.share, single.met, model, polygons);
      EXPECT_NEAR(model, single.share, 4 * std::sqrt(variance / f.n + variance / single.met)) << theta << " " << phi;
      EXPECT_NEAR(polygons, single.share, 4 * sigma_single) << theta << " " << phi;
      EXPECT_EQ(f.retro, f.cube_retro);
    }
  }
}

// At normal incidence a full-cube sheet in air returns all the light, a triangular one two thirds.
TEST(FullCube, ReturnsAllLightAtNormalIncidence) {
  prism_sheet_geometry g;
  g.index = 1;
  g.plate_mm = 0;
  g.metallised = true;
  g.face_reflectance = 1;
  g.wavelength_nm = 0;
  const double triangular = test::trace_many(g, {0, 0, 1}, 20000, 1).retro / 20000;
  g.full_cubes = true;
  const double full = test::trace_many(g, {0, 0, 1}, 20000, 1).retro / 20000;
  std::printf("at normal incidence: full cubes %.4f, triangular %.4f\n", full, triangular);
  EXPECT_GT(full, 0.999);
  EXPECT_NEAR(triangular, 2.0 / 3, 0.015);
}

// Total internal reflection and no absorption: front reflection, retroreflected, stray and
// transmitted light add up to all of it.
TEST(FullCube, NoLightIsLostByALosslessSheet) {
  prism_sheet_geometry g;
  g.full_cubes = true;
  test::expect_no_light_lost(g, 9);
}

// The six face orders divide a cube corner's effective aperture: for shifts in every direction the
// distinct parts' areas add up to the whole, and at normal incidence each is a sixth of it.
TEST(FaceOrders, SixPartsDivideTheEffectiveAperture) {
  for (const bool full : {false, true}) {
    prism_sheet_geometry g;
    g.full_cubes = full;
    for (const double theta : {0.0, 15.0, 30.0}) {
      const glm::dvec3 d = -test::unit_direction(theta, 20);
      const polygon2 whole = full ? full_cube_effective_aperture(g, d) : effective_aperture(g, d, 1);
      // Distinct parts told apart by their vertices' mean (a part and its mirror image through
      // the apex have equal areas).
      std::vector<double> areas;
      std::vector<glm::dvec2> centres;
      for (int k = 0; k < 360; ++k) {
        const double a = radians(k + 0.5);
        const polygon2 part = face_order_aperture(g, d, 1, 0.01 * glm::dvec2(std::cos(a), std::sin(a)));
        const double area = polygon_area(part);
        glm::dvec2 centre(0);  // the area centroid (clipping may leave near-duplicate vertices)
        for (std::size_t i = 0; i < part.size(); ++i) {
          const glm::dvec2 &p0 = part[i], &p1 = part[(i + 1) % part.size()];
          centre += (p0 + p1) * (p0.x * p1.y - p1.x * p0.y) / (6 * area);
        }
        const auto seen = [&](const glm::dvec2& c) { return glm::length(c - centre) < 1e-9 * g.pitch_mm; };
        if (area > 0 && std::none_of(centres.begin(), centres.end(), seen)) {
          areas.push_back(area);
          centres.push_back(centre);
        }
        if (theta == 0) {
          EXPECT_NEAR(area, polygon_area(whole) / 6, 1e-12) << full << " " << k;
        }
      }
      double sum = 0;
      for (double x : areas) sum += x;
      if (theta > 0) {
        EXPECT_NEAR(sum, polygon_area(whole), 1e-9 * polygon_area(whole)) << full << " " << theta;
      }
      EXPECT_LE(areas.size(), 6u);
    }
  }
}

// Total internal reflection diffracts each face order's part apart: its retroreflected light
// spreads wider than a metal-coated sheet's, which diffracts by the whole aperture.
TEST(FaceOrders, TotalInternalReflectionSpreadsWiderThanAMetalCoat) {
  auto median_spread = [](bool metallised) {
    prism_sheet_geometry g;
    g.metallised = metallised;
    return test::median_retro_spread(g, glm::normalize(glm::dvec3(0.05, 0.02, 1)), 5, 5);
  };
  const double tir = median_spread(false), metal = median_spread(true);
  std::printf("median spread: TIR %.3f mrad, metal %.3f mrad (ratio %.2f)\n", 1e3 * tir, 1e3 * metal, tir / metal);
  EXPECT_GT(tir / metal, 1.5);
}
