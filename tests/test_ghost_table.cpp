// The ghost table (airr ghosts): a mirror prop that shows the display to the observer is a path
// class of its own, first by peak, and its layer lights exactly the pixels whose rays the mirror
// sends to the display's emitting area; the aerial image is placed where it forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "airr/core/assets.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/ghost_table.hpp"
#include "plate_mesh.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The display (50 mm, facing +y at y = -150, centred on x = z = 0) seen in a mirror plate
// standing in z = -60 (x within +-60, y from -200 to -80), through a half mirror that passes 0.8:
// whether the ray from `eye` along `d` gets there.
bool mirror_shows_display(const glm::dvec3& eye, const glm::dvec3& d) {
  if (d.z >= 0) return false;
  const double t = (-60 - eye.z) / d.z;
  const glm::dvec3 m = eye + t * d;
  if (std::abs(m.x) > 60 || m.y < -200 || m.y > -80) return false;
  const glm::dvec3 r(d.x, d.y, -d.z);
  if (r.y >= 0) return false;
  const glm::dvec3 p = m + (-150 - m.y) / r.y * r;
  return std::abs(p.x) <= 25 && std::abs(p.z) <= 25;
}

}  // namespace

TEST(GhostTable, MirrorPropRanksFirstByPeakAndSelectsItsImage) {
  test::temp_dir dir;
  test::write_plate(test::plate(2, -60, -60, 60, -200, -80), dir.file("mirror.glb"));
  scene s = test::uniform_source_scene(50, 48);
  s.half_mirror.reflectance = 0.2;
  s.half_mirror.transmittance = 0.8;
  prop_params p;
  p.name = "mirror";
  p.mesh = dir.file("mirror.glb");
  p.surface = prop_surface::mirror;
  p.albedo = {0.7, 0.7, 0.7};
  s.props.push_back(p);
  s.observer.placement = observer_placement::look_at;
  s.observer.position_mm = {0, 150, 410};
  s.observer.look_at_mm = {0, -150, -120};
  s.observer.fov_deg = 8;
  const ghost_table t = compute_ghost_table(s, {.census_spp = 2, .spp = 8, .top = 6, .threads = 2});
  ASSERT_FALSE(t.classes.empty());
  const ghost_class& first = t.classes[t.by_peak.front()];
  std::printf("%zu labels seen; first by peak: %s (peak %.4g)\n", t.labels_seen, first.expression.c_str(), first.peak);
  for (const auto& g : t.classes)
    std::printf("  %-50s share %.4f peak %.4g separation %.1f arcmin distance %.1f mm\n", g.expression.c_str(), g.share,
                g.peak, g.separation_arcmin, g.distance_mm);
  EXPECT_NE(first.expression.find("P#0"), std::string::npos);
  // The display's image in the mirror is at (0, -150, -120), where the observer looks: 609.0 mm away.
  EXPECT_NEAR(first.distance_mm, std::hypot(300.0, 530.0), 3);
  // Off the mirror at 0.7, through the half mirror at 0.8 (the display lights the mirror directly).
  EXPECT_NEAR(first.peak, 0.8 * 0.7 * s.source.intensity, 1e-4 * s.source.intensity);

  const pinhole_camera cam = make_camera(s);
  int lit = 0, dark = 0;
  for (int y = 0; y < cam.height; ++y) {
    for (int x = 0; x < cam.width; ++x) {
      int corners = 0;
      for (const auto& [cx, cy] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
        corners += mirror_shows_display(cam.position, camera_direction(cam, x + cx, y + cy));
      const float* v = first.image.at(x, y);
      if (corners == 4) {
        EXPECT_GT(v[1], 0.0f) << x << ", " << y;
        ++lit;
      } else if (corners == 0) {
        EXPECT_EQ(v[1], 0.0f) << x << ", " << y;
        ++dark;
      }
    }
  }
  std::printf("%d pixels wholly in the mirror's image of the display, %d wholly out\n", lit, dark);
  EXPECT_GT(lit, 100);
  EXPECT_GT(dark, 100);
}

TEST(GhostTable, AerialImageIsPlacedWhereItForms) {
  // The ideal bench: the aerial image, face on, 300 mm from the observer.
  scene s = load_scene(ideal_bench_scene_path(), {{"observer.width", "96"}, {"observer.height", "96"}});
  const ghost_table t = compute_ghost_table(s, {.census_spp = 1, .spp = 4, .top = 4, .threads = 2});
  ASSERT_FALSE(t.classes.empty());
  std::printf("aerial image %.2f mm from the observer by parallax (300 by the layout)\n", t.aerial_distance_mm);
  for (const auto& g : t.classes)
    std::printf("  %-50s share %.4f peak %.4g separation %.1f arcmin distance %.1f mm\n", g.expression.c_str(), g.share,
                g.peak, g.separation_arcmin, g.distance_mm);
  // The centroids of what each eye sees of an extended image: within 2%.
  EXPECT_NEAR(t.aerial_distance_mm, 300, 6);
  EXPECT_TRUE(t.classes.front().aerial);
  EXPECT_EQ(t.classes.front().separation_arcmin, 0);
  EXPECT_THROW(compute_ghost_table(s, {.top = 0}), input_error);
  EXPECT_THROW(compute_ghost_table(s, {.baseline_mm = -1}), input_error);
}
