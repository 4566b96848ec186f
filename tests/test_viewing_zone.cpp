// The geometric viewing zone against an independent computation: the aerial-image rectangle
// clipped by the central projections, from the eye, of the half mirror's and the sheet's
// rectangles onto the aerial-image plane (convex polygon clipping, no ray following).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"
#include "airr/layout/viewing_zone.hpp"
#include "polygon_visible_fraction.hpp"

using namespace airr;
using airr::test::polygon_visible_fraction;

namespace {

scene tilted_sheet() {
  scene s;
  s.sheet().pose.pitch_deg = 20;
  s.sheet().pose.yaw_deg = 10;
  return s;
}

scene small_parts() {
  scene s;
  s.half_mirror.width_mm = 140;
  s.half_mirror.height_mm = 160;
  s.sheet().width_mm = 120;
  s.sheet().height_mm = 200;
  return s;
}

}  // namespace

TEST(ViewingZone, VisibleFractionMatchesPolygonClippingOnA21x21Grid) {
  const std::vector<std::pair<const char*, scene>> layouts = {
      {"canonical", scene{}}, {"tilted sheet", tilted_sheet()}, {"small parts", small_parts()}};
  for (const auto& [name, s] : layouts) {
    check_layout(s, name);
    eye_grid g;
    g.distance_mm = 300;
    g.x_min = g.y_min = -250;
    g.x_max = g.y_max = 250;
    const viewing_zone_map map = geometric_viewing_zone(s, g, {});
    ASSERT_EQ(map.visible.size(), 441u);
    double worst = 0;
    int partial = 0;
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const double want = polygon_visible_fraction(s, eye_position(s, g, g.x_at(i), g.y_at(j)));
        const double got = map.visible[std::size_t(j) * g.nx + i];
        worst = std::max(worst, std::abs(got - want));
        if (want > 0.01 && want < 0.99) ++partial;
        EXPECT_NEAR(got, want, 1e-4) << name << " at eye (" << g.x_at(i) << ", " << g.y_at(j) << ") mm";
      }
    }
    std::printf("%s: worst difference %.5f over 441 eyes, %d of them partly visible\n", name, worst, partial);
    EXPECT_GT(partial, 20) << name << ": the grid should cross the zone's edge";
  }
}

// Canonical layout, eye 300 mm in front of the aerial image (z = 450), moving along x: the
// aerial image (50 mm wide at z = 150) sends its line of sight to the sheet plane (z = -150) at
// x_s = 2 p - x_e for image point p, and the sheet reaches to |x_s| = 150. All of it is seen for
// x_e <= 150 - 50 = 100 mm, none of it beyond x_e = 150 + 50 = 200 mm.
TEST(ViewingZone, WholeInsideTheAnalyticLimitAndNothingBeyondIt) {
  const scene s;
  const viewing_parts parts(s);
  ASSERT_DOUBLE_EQ(parts.aerial.width, 50);
  ASSERT_DOUBLE_EQ(parts.sheets.front().width, 300);
  eye_grid g;
  for (double x : {0.0, 50.0, 99.0, -99.0}) {
    EXPECT_NEAR(visible_fraction(parts, eye_position(s, g, x, 0)), 1.0, 1e-9) << x;
  }
  for (double x : {201.0, 250.0, -201.0, 400.0}) {
    EXPECT_EQ(visible_fraction(parts, eye_position(s, g, x, 0)), 0.0) << x;
  }
  // Half way, x_e = 150: image points p < 0 are seen, half the image.
  EXPECT_NEAR(visible_fraction(parts, eye_position(s, g, 150, 0)), 0.5, 1e-4);
}

TEST(ViewingZone, BadGridsAreNamed) {
  const scene s;
  eye_grid g;
  g.nx = 0;
  EXPECT_THROW(geometric_viewing_zone(s, g, {}), input_error);
  g = {};
  g.x_max = std::nan("");
  EXPECT_THROW(geometric_viewing_zone(s, g, {}), input_error);
  g = {};
  g.distance_mm = -1;
  EXPECT_THROW(geometric_viewing_zone(s, g, {}), input_error);
  g = {};
  g.kind = eye_grid::shape::sphere;
  g.y_max = 95;
  EXPECT_THROW(geometric_viewing_zone(s, g, {}), input_error);
}

TEST(ViewingZone, PlacingTheObserverPutsItAtThePointsCoordinates) {
  for (const auto kind : {eye_grid::shape::sphere, eye_grid::shape::plane}) {
    scene s;
    eye_grid g;
    g.kind = kind;
    g.distance_mm = 420;
    place_observer(s, g, 25, -12);
    const glm::dvec2 at = eye_grid_coordinates(s, g, observer_position(s));
    EXPECT_NEAR(at.x, 25, 1e-9);
    EXPECT_NEAR(at.y, -12, 1e-9);
    EXPECT_NEAR(glm::length(observer_target(s) - aerial_image_center(s)), 0, 1e-9);
    check_layout(s, "placed");
  }
}
