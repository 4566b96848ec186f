// The ghost table (airr ghosts): a mirror prop that shows the display to the observer is a path
// class of its own, first by peak, and its layer lights exactly the pixels whose rays the mirror
// sends to the display's emitting area; the aerial image is placed where it forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "airr/core/assets.hpp"
#include "airr/core/color.hpp"
#include "airr/core/error.hpp"
#include "airr/formats/scene_json.hpp"
#include "airr/layout/layout.hpp"
#include "airr/measure/ghost_table.hpp"
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
  scene s = test::display_in_mirror_scene(dir, 48);
  s.half_mirror.reflectance = 0.2;
  s.half_mirror.transmittance = 0.8;
  s.props[0].albedo = {0.7, 0.7, 0.7};
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

// A 3 mm glass plate (index 1.5) as the half mirror: a partial mirror (R = T = 0.5 for s and p) on
// the face the display's light meets first, the second face uncoated. The second face's
// reflection is a path class of its own (H:r1), placed as the plate's geometry puts it: across
// the line of sight by delta = 2 t tan(theta_t) cos(theta_i), seen from the observer as delta / L;
// along it nearer the observer by (2 t tan(theta_t) / tan(theta_i)) cos(theta_i), where its
// sagittal rays (the eyes' horizontal parallax) seem to come from; and with the light the faces
// let through: per polarization T R_glass T against R, both then through the uncoated face
// (T_glass; the sheet keeps the polarization). A small display (6 mm, the field a few degrees), so
// that the angles vary little across it: the glass's reflectance grows with the angle, and over a
// large image would move the ghost's centroid by a share of delta.
TEST(GhostTable, APlatesSecondSurfaceIsAClassOfItsOwnWhereTheGeometrySaysAndAsBright) {
  scene s = test::uniform_source_scene(6, 64);
  s.observer.fov_deg = 2;  // 10.5 mm across at 300 mm: the image 37 pixels wide
  s.half_mirror.kind = half_mirror_kind::plate;
  const double t_mm = 3, n = 1.5;
  s.half_mirror.plate.thickness_mm = t_mm;
  s.half_mirror.plate.index = n;
  s.half_mirror.plate.back = {.kind = coating_kind::partial_mirror, .rs = 0.5, .rp = 0.5, .ts = 0.5, .tp = 0.5};
  s.half_mirror.plate.front = {.kind = coating_kind::uncoated};
  derive_half_mirror_light(s.half_mirror);
  // The second face's paths are one in 40 of the reflected ones: 10,000 of them in the image.
  // Classes typed besides: every path that met the second face on the way to the sheet, and
  // every path the sheet did not retroreflect (whose text names a retroreflection all the same).
  const ghost_table t = compute_ghost_table(s, {.census_spp = 1,
                                                .spp = 256,
                                                .top = 6,
                                                .threads = 2,
                                                .expressions = {"D H:r1 S0:retro H:t E", "D [^S0:retro]* E"}});
  const auto light_of = [](const image_rgb& img) {
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) sum += rec709_luminance(img.at(x, y)[0], img.at(x, y)[1], img.at(x, y)[2]);
    return sum;
  };
  const ghost_class* first = nullptr;
  const ghost_class* second = nullptr;
  for (const auto& g : t.classes) {
    std::printf("  %-50s light %.5g separation %.2f arcmin distance %.2f mm\n", g.expression.c_str(), light_of(g.image),
                g.separation_arcmin, g.distance_mm);
    if (g.typed || !g.aerial) continue;
    if (g.expression.find("H:r0") != std::string::npos && !first) first = &g;
    if (g.expression.find("H:r1") != std::string::npos && !second) second = &g;
  }
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  const auto typed = std::find_if(t.classes.begin(), t.classes.end(), [](const ghost_class& g) { return g.typed; });
  ASSERT_NE(typed, t.classes.end());
  EXPECT_EQ(typed->expression, "D H:r1 S0:retro H:t E");
  EXPECT_TRUE(typed->aerial);
  const auto others = std::find_if(t.classes.begin(), t.classes.end(),
                                   [](const ghost_class& g) { return g.expression == "D [^S0:retro]* E"; });
  ASSERT_NE(others, t.classes.end());
  EXPECT_TRUE(others->typed);
  EXPECT_FALSE(others->aerial);
  // It holds the second face's class and its return through the plate's other orders.
  EXPECT_GE(light_of(typed->image), light_of(second->image));
  EXPECT_LT(light_of(typed->image), 1.2 * light_of(second->image));
  EXPECT_NEAR(typed->separation_arcmin, second->separation_arcmin, 2.0);

  const pinhole_camera cam = make_camera(s);
  const part_frame hm = half_mirror_frame(s);
  const double cos_i = std::abs(glm::dot(cam.forward, hm.n)), sin_i = std::sqrt(1 - cos_i * cos_i);
  const double sin_t = sin_i / n, cos_t = std::sqrt(1 - sin_t * sin_t), tan_t = sin_t / cos_t;
  const double delta = 2 * t_mm * tan_t * cos_i;
  const double distance = glm::length(aerial_image_center(s) - cam.position);
  const double separation = delta / distance * 180 / M_PI * 60;
  const double nearer = 2 * t_mm * tan_t / (sin_i / cos_i) * cos_i;
  // Fresnel at the uncoated face, from inside (theta_t) to outside (theta_i).
  const double rs = (n * cos_t - cos_i) / (n * cos_t + cos_i), rp = (cos_t - n * cos_i) / (cos_t + n * cos_i);
  const double R[2] = {rs * rs, rp * rp};
  double main = 0, ghost = 0;
  for (int k = 0; k < 2; ++k) {
    main += 0.5 * 0.5 * (1 - R[k]);                // the coat reflects, then through the plate
    ghost += 0.5 * R[k] * 0.5 * 0.5 * (1 - R[k]);  // through the coat, the glass's, the coat, the plate
  }
  const double measured = light_of(second->image) / light_of(first->image);
  std::printf(
      "second surface: %.3f arcmin (plate %.3f), %.3f mm nearer (plate %.3f), light %.5f of the first's "
      "(faces %.5f)\n",
      second->separation_arcmin, separation, t.aerial_distance_mm - second->distance_mm, nearer, measured,
      ghost / main);
  EXPECT_NEAR(second->separation_arcmin, separation, 0.5);
  EXPECT_NEAR(t.aerial_distance_mm - second->distance_mm, nearer, 2.0);
  EXPECT_NEAR(measured / (ghost / main), 1.0, 0.05);
}
