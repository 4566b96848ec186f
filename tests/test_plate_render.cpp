// The plate half mirror in the tracer (docs/polarization.md): the far face's reflection forms its
// own aerial image where the plate's geometry puts it.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "airr/core/geometry.hpp"
#include "airr/layout/layout.hpp"
#include "airr/render/render_session.hpp"
#include "test_helpers.hpp"

using namespace airr;

namespace {

// The aerial component's centroid in pixels.
test::centroid aerial_centroid(const scene& s, std::uint64_t spp) {
  render_session session(s, {.threads = 2, .target_spp = spp, .components = true});
  const render_snapshot snap = session.wait_for(0, spp);
  const image_rgb aerial = snap.component_image(component_aerial);
  test::centroid c;
  for (int y = 0; y < aerial.height; ++y) {
    for (int x = 0; x < aerial.width; ++x) {
      const float* p = aerial.at(x, y);
      const double v = (double(p[0]) + p[1] + p[2]) / 3;
      c.x += v * (x + 0.5);
      c.y += v * (y + 0.5);
      c.total += v;
    }
  }
  c.x /= c.total;
  c.y /= c.total;
  return c;
}

}  // namespace

// A 3 mm plate (index 1.5) at 45 deg on the bench, seen from 10 m through a 0.1 mm pixel (so every
// ray meets it at 45 deg within 0.01 deg). With the partial mirror on its back face (towards the
// display and the sheet) and an anti-reflection coat on the front, only the near face reflects;
// swapped, only the far face does. The two aerial images lie apart by the plate's
// 2 t tan(theta_t) cos(theta_i) across the line of sight, along the plane of incidence (the
// image's vertical), within 0.05 px.
TEST(PlateRender, TheFarFacesImageFormsWherePlateGeometryPutsIt) {
  scene s = test::uniform_source_scene(2, 160);
  s.observer.distance_mm = 10000;
  const double pitch_mm = 0.1;
  s.observer.fov_deg = degrees(2 * std::atan(80 * pitch_mm / s.observer.distance_mm));
  s.half_mirror.kind = half_mirror_kind::plate;
  s.half_mirror.plate.thickness_mm = 3;
  s.half_mirror.plate.index = 1.5;
  const coating_params mirror{.kind = coating_kind::partial_mirror, .rs = 0.5, .rp = 0.5, .ts = 0.5, .tp = 0.5};
  const coating_params clear{.kind = coating_kind::anti_reflection};

  scene near = s, far = s;
  near.half_mirror.plate.back = mirror;
  near.half_mirror.plate.front = clear;
  far.half_mirror.plate.back = clear;
  far.half_mirror.plate.front = mirror;
  derive_half_mirror_light(near.half_mirror);
  derive_half_mirror_light(far.half_mirror);
  const test::centroid a = aerial_centroid(near, 64), b = aerial_centroid(far, 64);

  const double theta_i = radians(45), theta_t = std::asin(std::sin(theta_i) / 1.5);
  const double expected_px = 2 * 3 * std::tan(theta_t) * std::cos(theta_i) / pitch_mm;
  std::printf(
      "near face's image at (%.3f, %.3f) px, far face's at (%.3f, %.3f) px: %.3f px apart, plate "
      "geometry %.3f px\n",
      a.x, a.y, b.x, b.y, std::hypot(b.x - a.x, b.y - a.y), expected_px);
  EXPECT_NEAR(std::abs(b.y - a.y), expected_px, 0.05);
  EXPECT_NEAR(b.x, a.x, 0.05);
  // Both images carry the light the coatings let through: R T of the partial mirror.
  EXPECT_NEAR(b.total / a.total, 1.0, 0.01);
}
