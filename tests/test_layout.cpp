// Layout geometry against hand-derived positions: the mirror image, the camera, intersections.
#include <gtest/gtest.h>

#include "airr/core/error.hpp"
#include "airr/layout/layout.hpp"
#include "test_helpers.hpp"

using namespace airr;

TEST(Layout, AerialImageIsTheMirrorImageAtPlusD) {
  for (double d : {110.0, 150.0, 300.0}) {
    scene s;
    airr::set_floating_distance(s, d);
    const glm::dvec3 a = aerial_image_center(s);
    EXPECT_NEAR(a.x, 0, 1e-12);
    EXPECT_NEAR(a.y, 0, 1e-12);
    EXPECT_NEAR(a.z, d, 1e-12);
  }
}

TEST(Layout, CameraLooksAtTheAerialImageFromDPlus300) {
  scene s;
  airr::set_floating_distance(s, 225);
  const pinhole_camera c = make_camera(s);
  EXPECT_NEAR(c.position.z, 525, 1e-12);
  const glm::dvec2 p = camera_project(c, {0, 0, 225});
  EXPECT_NEAR(p.x, s.observer.width / 2.0, 1e-9);
  EXPECT_NEAR(p.y, s.observer.height / 2.0, 1e-9);
  // Projection inverts the ray direction of a pixel position.
  const glm::dvec3 d = camera_direction(c, 10.25, 200.5);
  const glm::dvec2 back = camera_project(c, c.position + 123.0 * d);
  EXPECT_NEAR(back.x, 10.25, 1e-9);
  EXPECT_NEAR(back.y, 200.5, 1e-9);
  // One pixel on the aerial-image plane: 2 * 300 * tan(7 deg) / 256.
  EXPECT_NEAR(c.mm_per_pixel, 2 * 300 * std::tan(7 * M_PI / 180) / 256, 1e-12);
}

TEST(Layout, TiltTurnsTheSheetNormalUpwards) {
  scene s;
  s.sheet().pose.pitch_deg = 30;
  const part_frame f = retroreflector_frame(s);
  EXPECT_NEAR(f.n.y, 0.5, 1e-12);
  EXPECT_NEAR(f.n.z, std::sqrt(3.0) / 2, 1e-12);
  // The chief ray (along -z) meets it at incidence angle tilt.
  EXPECT_NEAR(std::acos(glm::dot(glm::dvec3(0, 0, 1), f.n)) * 180 / M_PI, 30, 1e-9);
}

TEST(Layout, IntersectingPartsAreALayoutError) {
  scene s;
  EXPECT_NO_THROW(check_layout(s, "x"));
  s.sheet().pose.center_mm[2] = -50;  // inside the mirror's reach (its top edge is at z = -106)
  try {
    check_layout(s, "x.json");
    FAIL() << "no error";
  } catch (const input_error& e) {
    EXPECT_STREQ(e.what(), "x.json: retroreflectors[0]: layout: the half mirror and the retroreflector intersect");
  }
  s = scene{};
  airr::set_floating_distance(s, 90);  // the mirror at y = -90 is at z = 90, clear of the source
  EXPECT_NO_THROW(check_layout(s, "x"));
  airr::set_floating_distance(s, 20);  // the mirror at y = -20 is at z = 20, inside the source's +-25 mm
  EXPECT_THROW(check_layout(s, "x"), input_error);
  s = scene{};
  s.sheet().pose.pitch_deg = 45;  // leaning away: still clear
  EXPECT_NO_THROW(check_layout(s, "x"));
}

TEST(Layout, ATrianglesCutThroughAPartIsTheOverlapOfTheirChords) {
  part_frame f;  // 2 x 2 mm in the xy plane
  f.width = f.height = 2;
  // A triangle in the plane x = 0.3, reaching from z = -1 to z = 1 and from y = -3 to y = 3 at z = 0:
  // the plane z = 0 meets it in y in [-2, 2] (its chord there), the part in y in [-1, 1].
  std::array<glm::dvec3, 3> t = {glm::dvec3(0.3, -4, -1), glm::dvec3(0.3, 4, -1), glm::dvec3(0.3, 0, 1)};
  EXPECT_NEAR(part_cut_length(f, t), 2.0, 1e-12);
  for (auto& p : t) p.y += 2.5;  // its chord y in [0.5, 4.5] overlaps the part's in [0.5, 1]
  EXPECT_NEAR(part_cut_length(f, t), 0.5, 1e-12);
  for (auto& p : t) p.x += 0.8;  // x = 1.1: beyond the part's edge
  EXPECT_EQ(part_cut_length(f, t), 0.0);
  // In the plane x = z: it meets z = 0 on the line x = 0.
  t = {glm::dvec3(-1, -5, -1), glm::dvec3(1, -5, 1), glm::dvec3(0, 0, 0)};
  EXPECT_NEAR(part_cut_length(f, t), 1.0, 1e-12);  // its chord at z = 0 runs from y = -5 to y = 0
  // Touching from one side (a corner or an edge on the plane) and lying in the plane do not cut.
  t = {glm::dvec3(0, -0.5, 0), glm::dvec3(0, 0.5, 0), glm::dvec3(0, 0, 1)};
  EXPECT_EQ(part_cut_length(f, t), 0.0);
  t = {glm::dvec3(-0.5, -0.5, 0), glm::dvec3(0.5, -0.5, 0), glm::dvec3(0, 0.5, 0)};
  EXPECT_EQ(part_cut_length(f, t), 0.0);
  // The rectangle's own edge can end the cut: a triangle across the part's corner region.
  t = {glm::dvec3(0.5, -1.5, -1), glm::dvec3(0.5, -1.5, 1), glm::dvec3(0.5, 10, 0)};
  EXPECT_NEAR(part_cut_length(f, t), 2.0, 1e-12);  // y from -1.5 (clipped to -1) to 10 (clipped to 1)
}

TEST(Layout, RectangleIntersectionAgreesWithHandCases) {
  part_frame a, b;
  a.width = a.height = b.width = b.height = 2;
  b.n = {1, 0, 0};
  b.u = {0, 1, 0};
  b.v = {0, 0, 1};
  EXPECT_TRUE(parts_intersect(a, b));  // crossing at x = 0
  b.center = {0.99, 0, 0};
  EXPECT_TRUE(parts_intersect(a, b));
  b.center = {1.01, 0, 0};
  EXPECT_FALSE(parts_intersect(a, b));
  b.center = {0, 0, 1.01};
  EXPECT_FALSE(parts_intersect(a, b));
}
